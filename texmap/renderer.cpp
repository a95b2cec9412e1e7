// The texture-mapping stage in OpenGL 3.3 core.
//
// Texture orientation: images are uploaded as stored (row 0 = top of the picture), and glTexImage2D puts the first
// row at t = 0, so the picture's top row lies at t = 0. The relief convention puts the top row at v = 1
// (docs/FORMATS.md), hence every texture coordinate is given to GL as (u, t) = (u, 1 - v). Flipping t instead
// of the rows keeps upload() a straight copy and lets upload_rect() address rows as the image does.
//
// Output alpha: what is drawn is opaque. A quad fragment is kept when its bilinearly filtered texture alpha is at
// least one half (alpha is coverage, not translucency) and is written with alpha 1; so is a mesh fragment, whose
// alpha is the interpolated vertex alpha. The framebuffer therefore stays opaque everywhere (background 0,0,0,1).
#include "texmap/renderer.h"

#include <glad/gl.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <array>
#include <vector>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "texmap/gl_context.h"
#include "texmap/gl_program.h"
#include "texmap/wall_clip.h"

namespace rtm {
namespace {

static_assert(sizeof(Rgba8) == 4, "Rgba8 must be 4 tightly packed bytes");
static_assert(sizeof(MeshVertex) == 16, "MeshVertex must be 3 floats and 4 bytes, tightly packed");

constexpr const char* kQuadVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_texcoord;
uniform mat4 u_mvp;
out vec2 v_texcoord;
void main() {
    v_texcoord = a_texcoord;
    gl_Position = u_mvp * vec4(a_position, 1.0);
}
)";

constexpr const char* kQuadFragmentShader = R"(#version 330 core
in vec2 v_texcoord;
uniform sampler2D u_texture;
out vec4 o_color;
void main() {
    vec4 t = texture(u_texture, v_texcoord);
    if (t.a < 0.5) discard;  // empty texels show what is behind
    o_color = vec4(t.rgb, 1.0);
}
)";

// Relief surface: positions are relative to the eye (computed in double on the CPU), so the ray-plane
// intersection in the fragment shader works on small numbers whatever the world's scale.
constexpr const char* kReliefVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_rel;
layout(location = 1) in vec3 a_st;
uniform mat4 u_mvp_rel;
out vec3 v_rel;
out vec3 v_st;
void main() {
    v_rel = a_rel;
    v_st = a_st;
    gl_Position = u_mvp_rel * vec4(a_rel, 1.0);
}
)";

// Compiled four times. RTM_DEPTH 1 writes the corrected depth (depth correction), RTM_DEPTH 0 leaves the fragment
// depth alone -- a shader that writes gl_FragDepth costs llvmpipe its early depth test and about 0.1 ms a frame
// at 512x512 here. RTM_WALL 1 is the side polygons' program: each fragment finds where its eye ray meets the relief
// plane and looks the texture up there. RTM_WALL 0 is the quad's: its fragments lie on the plane, so the plane
// point is the interpolated position and the texture coordinate the interpolated (perspective-correct) vertex
// attribute; the ray-plane arithmetic took 0.32 of the 0.89 ms llvmpipe spent on a 256^2 quad in a 512x512 view.
// The side polygons' plane coordinates are homogeneous vertex attributes, (U, V, W) with (u, v) = (U, V) / W: the
// plane point of an eye-relative position r is r / W with W = dot(r, f) / dot(c, f), so U = dot(r, da) - W dot(c,
// da) (likewise V) and W are linear in r and interpolate exactly; the fragment divides once. It used to
// intersect the ray itself (a dot product, a division, three dot products). Table 1's view, pipelined, 2 threads,
// 4 interleaved runs: texture mapping ridges 0.66-0.71 -> 0.57-0.62 ms, bumps 0.50 -> 0.48. Images (the 4 media,
// 6 orbits, two-pass and pipelined, with and without depth correction): colours within 2 levels, 6 of the 96
// gain one pixel where the two ways round differently at the quad's outline (one a crack filled in).
constexpr const char* kReliefFragmentShaderBody = R"(
in vec3 v_rel;
in vec3 v_st;
uniform sampler2D u_color;
uniform sampler2D u_displ;
uniform vec3 u_forward;
uniform vec4 u_uv;       // (margin_left, margin_bottom, 1 / texture width, 1 / texture height)
uniform vec2 u_size;     // the quad in texels
uniform float u_k3, u_dmin, u_dmax, u_qs;
uniform vec2 u_ndc;      // ndc z = u_ndc.x + u_ndc.y / Z for eye-space distance Z along the view direction
out vec4 o_color;
void main() {
#if RTM_WALL
    float w = 1.0 / v_st.z;
    float u = v_st.x * w, v = v_st.y * w;
    if (u >= 0.0 && u <= u_size.x && v >= 0.0 && v <= u_size.y) discard;  // the quad's part
    vec2 st = vec2((u + u_uv.x) * u_uv.z, 1.0 - (v + u_uv.y) * u_uv.w);
    if (st.x < 0.0 || st.x > 1.0 || st.y < 0.0 || st.y > 1.0) discard;
    vec3 p = v_rel * w;  // where the eye ray meets the relief plane
#else
    vec3 p = v_rel;  // on the quad, inside the texture by construction
    vec2 st = v_st.xy;
#endif
    vec4 t = texture(u_color, st);
    if (t.a < 0.5) discard;  // empty texels show what is behind
    o_color = vec4(t.rgb / t.a, 1.0);
#if RTM_DEPTH
    float depth = gl_FragCoord.z;
    {
        ivec2 ts = textureSize(u_displ, 0);
        ivec2 ij = clamp(ivec2(st * vec2(ts)), ivec2(0), ts - 1);
        float qi = texelFetch(u_displ, ij, 0).r * 255.0;
        float z = dot(p, u_forward);
        if (qi < 254.5) z *= 1.0 + u_k3 * (qi > 253.5 ? u_dmax : u_dmin + qi * u_qs);
        depth = 0.5 * (u_ndc.x + u_ndc.y / z) + 0.5;
    }
    gl_FragDepth = depth;
#endif
}
)";

// The relief quad's 4 vertices and, for each of 4 side polygons, up to 4 pieces (outside_view_cone) of up to 8
// vertices, each cut into up to 4 parts (inside_plane_rects, one per margin band) of up to 12: clipping a convex
// n-gon by a plane adds at most one vertex, piece i has been clipped i + 1 times, and a part 4 times more.
constexpr GLint kMaxReliefVertices = 4 + 4 * 4 * 4 * 12;

constexpr const char* kMeshVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_color;
uniform mat4 u_mvp;
out vec4 v_color;
void main() {
    v_color = a_color;
    gl_Position = u_mvp * vec4(a_position, 1.0);
}
)";

constexpr const char* kMeshFragmentShader = R"(#version 330 core
in vec4 v_color;
out vec4 o_color;
void main() {
    if (v_color.a < 0.5) discard;
    o_color = vec4(v_color.rgb, 1.0);
}
)";

void require_context(const char* what) {
    // glad's pointers are null until a GlContext was made current.
    if (!glad_glCreateShader) throw GlError(std::string(what) + ": no OpenGL context is current");
}

// Model-view-projection in double (the camera's precision), handed to GL as float.
glm::mat4 mvp_of(const Camera& cam, const glm::dvec3& origin = glm::dvec3(0.0)) {
    return glm::mat4(cam.projection() * cam.view() * glm::translate(glm::dmat4(1.0), origin));  // in double, then float
}

void check_image(const ImageRGBA8& img, const char* what) {
    if (img.width <= 0 || img.height <= 0)
        throw std::invalid_argument(std::string(what) + ": image is " + std::to_string(img.width) + "x" +
                                    std::to_string(img.height));
    if (img.pixels.size() != size_t(img.width) * size_t(img.height))
        throw std::invalid_argument(std::string(what) + ": image claims " + std::to_string(img.width) + "x" +
                                    std::to_string(img.height) + " but holds " + std::to_string(img.pixels.size()) +
                                    " pixels");
}

// The bound texture's sampling: `filter` for minification and magnification, one level, clamped to the edge.
void set_sampling(GLint filter) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
}

void reset_unpack_state() {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
}

}  // namespace

// -----------------------------------------------------------------------------------------------------------------
// GlTexture

void GlTexture::upload_gray(const Image2D<uint8_t>& img) {
    if (img.width <= 0 || img.height <= 0 || img.pixels.size() != size_t(img.width) * size_t(img.height))
        throw std::invalid_argument("GlTexture::upload_gray: image is " + std::to_string(img.width) + "x" +
                                    std::to_string(img.height));
    glBindTexture(GL_TEXTURE_2D, id_);
    reset_unpack_state();
    if (img.width != width_ || img.height != height_) {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, img.width, img.height, 0, GL_RED, GL_UNSIGNED_BYTE, img.pixels.data());
        set_sampling(GL_NEAREST);
        width_ = img.width;
        height_ = img.height;
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, img.width, img.height, GL_RED, GL_UNSIGNED_BYTE, img.pixels.data());
    }
    check_gl("GlTexture::upload_gray");
}

namespace {

// (Re)allocates the bound texture with one level, bilinear, clamped to the edge.
void allocate_linear(GLint internal, int w, int h, GLenum format, const void* data) {
    glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, GL_FLOAT, data);
    set_sampling(GL_LINEAR);
}

}  // namespace

void GlTexture::upload_float(const ImageF& img) {
    if (img.width <= 0 || img.height <= 0 || img.pixels.size() != size_t(img.width) * size_t(img.height))
        throw std::invalid_argument("GlTexture::upload_float: image is " + std::to_string(img.width) + "x" +
                                    std::to_string(img.height));
    glBindTexture(GL_TEXTURE_2D, id_);
    reset_unpack_state();
    allocate_linear(GL_R32F, img.width, img.height, GL_RED, img.pixels.data());
    width_ = img.width;
    height_ = img.height;
    check_gl("GlTexture::upload_float");
}

void GlTexture::upload_as_float(const ImageRGBA8& img) {
    check_image(img, "GlTexture::upload_as_float");
    std::vector<float> v(img.pixels.size() * 4);
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        const Rgba8& p = img.pixels[i];
        v[4 * i] = float(p.r) / 255.0f;
        v[4 * i + 1] = float(p.g) / 255.0f;
        v[4 * i + 2] = float(p.b) / 255.0f;
        v[4 * i + 3] = float(p.a) / 255.0f;
    }
    glBindTexture(GL_TEXTURE_2D, id_);
    reset_unpack_state();
    allocate_linear(GL_RGBA32F, img.width, img.height, GL_RGBA, v.data());
    width_ = img.width;
    height_ = img.height;
    check_gl("GlTexture::upload_as_float");
}

namespace {

// A vertex array of MeshVertex (position, normalized colour) with its vertex and element buffers, the element
// buffer recorded in the array.
void make_mesh_vertex_array(GLuint& vao, GLuint& vbo, GLuint& ebo) {
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glGenBuffers(1, &ebo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                          reinterpret_cast<void*>(offsetof(MeshVertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(MeshVertex),
                          reinterpret_cast<void*>(offsetof(MeshVertex, color)));
    glBindVertexArray(0);
}

}  // namespace

GlMesh::GlMesh() {
    require_context("GlMesh");
    GLuint vao = 0, vbo = 0, ebo = 0;
    make_mesh_vertex_array(vao, vbo, ebo);
    vao_ = vao;
    vbo_ = vbo;
    ebo_ = ebo;
    check_gl("GlMesh: creating buffers");
}

GlMesh::~GlMesh() {
    if (vao_ && glad_glDeleteVertexArrays) {
        GLuint vao = vao_, buffers[2] = {vbo_, ebo_};
        glDeleteVertexArrays(1, &vao);
        glDeleteBuffers(2, buffers);
    }
}

void GlMesh::upload(const std::vector<MeshVertex>& vertices, const std::vector<uint32_t>& indices) {
    const size_t count = indices.size() - indices.size() % 3;  // whole triangles only
    for (size_t i = 0; i < count; ++i)
        if (indices[i] >= vertices.size())
            throw std::out_of_range("GlMesh::upload: index " + std::to_string(i) + " is " + std::to_string(indices[i]) +
                                    " but there are only " + std::to_string(vertices.size()) + " vertices");
    glBindVertexArray(vao_);  // its element buffer is ebo_
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(MeshVertex)), vertices.data(), GL_STATIC_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(count * sizeof(uint32_t)), indices.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
    index_count_ = count;
    check_gl("GlMesh::upload");
}

GlTexture::GlTexture() {
    require_context("GlTexture");
    GLuint id = 0;
    glGenTextures(1, &id);
    id_ = id;
    check_gl("GlTexture: glGenTextures");
}

GlTexture::~GlTexture() {
    if (id_ && glad_glDeleteTextures) {
        GLuint id = id_;
        glDeleteTextures(1, &id);
    }
}

void GlTexture::upload(const ImageRGBA8& img) {
    check_image(img, "GlTexture::upload");
    glBindTexture(GL_TEXTURE_2D, id_);
    reset_unpack_state();
    if (img.width != width_ || img.height != height_) {
        GLint max_size = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
        if (img.width > max_size || img.height > max_size)
            throw GlError("GlTexture::upload: a " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                          " texture exceeds GL_MAX_TEXTURE_SIZE " + std::to_string(max_size));
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, img.width, img.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                     img.pixels.data());
        set_sampling(GL_LINEAR);
        check_gl("GlTexture::upload: glTexImage2D");
        width_ = img.width;
        height_ = img.height;
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.pixels.data());
        check_gl("GlTexture::upload: glTexSubImage2D");
    }
}

void GlTexture::upload_rect(const ImageRGBA8& img, int x, int row, int w, int h) {
    check_image(img, "GlTexture::upload_rect");
    if (img.width != width_ || img.height != height_) {
        // The texture does not have this image's size yet: the whole image has to go up anyway.
        upload(img);
        return;
    }
    if (x < 0 || row < 0 || w < 0 || h < 0 || x > img.width - w || row > img.height - h)
        throw std::invalid_argument("GlTexture::upload_rect: rectangle x=" + std::to_string(x) +
                                    " row=" + std::to_string(row) + " " + std::to_string(w) + "x" + std::to_string(h) +
                                    " is outside the " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                                    " image");
    if (w == 0 || h == 0) return;
    glBindTexture(GL_TEXTURE_2D, id_);
    reset_unpack_state();
    glPixelStorei(GL_UNPACK_ROW_LENGTH, img.width);
    // Rows are stored top first and uploaded unflipped, so image row `row` is texture row `row`.
    glTexSubImage2D(GL_TEXTURE_2D, 0, x, row, w, h, GL_RGBA, GL_UNSIGNED_BYTE, &img.at(x, row));
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    check_gl("GlTexture::upload_rect: glTexSubImage2D");
}

// -----------------------------------------------------------------------------------------------------------------
// Renderer

struct Renderer::Impl {
    bool timed = true;  // finish() waits for the GPU
    GLuint quad_program = 0, mesh_program = 0;
    GLuint relief_program[2][2] = {};  // [depth correction][side polygon]
    GLuint relief_vao = 0, relief_vbo = 0;
    GLint quad_mvp = -1, quad_texture = -1, mesh_mvp = -1;
    GLuint quad_vao = 0, quad_vbo = 0;
    GLuint mesh_vao = 0, mesh_vbo = 0, mesh_ebo = 0;
    bool clear_pending = false;

    void issue_pending_clear() {
        if (!clear_pending) return;
        clear_pending = false;
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }

    void destroy() {
        if (!glad_glDeleteProgram) return;
        if (quad_program) glDeleteProgram(quad_program);
        if (mesh_program) glDeleteProgram(mesh_program);
        for (const auto& by_wall : relief_program)
            for (GLuint p : by_wall)
                if (p) glDeleteProgram(p);
        GLuint buffers[] = {quad_vbo, mesh_vbo, mesh_ebo, relief_vbo};
        glDeleteBuffers(4, buffers);
        GLuint arrays[] = {quad_vao, mesh_vao, relief_vao};
        glDeleteVertexArrays(3, arrays);
    }
};

Renderer::Renderer() : impl_(new Impl) {
    require_context("Renderer");
    Impl& m = *impl_;
    try {
        m.quad_program = link_program(kQuadVertexShader, kQuadFragmentShader, "textured quad");
        m.mesh_program = link_program(kMeshVertexShader, kMeshFragmentShader, "mesh");
        m.quad_mvp = glGetUniformLocation(m.quad_program, "u_mvp");
        m.quad_texture = glGetUniformLocation(m.quad_program, "u_texture");
        m.mesh_mvp = glGetUniformLocation(m.mesh_program, "u_mvp");
        for (int depth = 0; depth < 2; ++depth)
            for (int wall = 0; wall < 2; ++wall) {
                const std::string fs = "#version 330 core\n#define RTM_DEPTH " + std::to_string(depth) +
                                       "\n#define RTM_WALL " + std::to_string(wall) + "\n" + kReliefFragmentShaderBody;
                const std::string what = std::string(wall ? "relief side polygon" : "relief quad") +
                                         (depth ? " with depth correction" : "");
                m.relief_program[depth][wall] = link_program(kReliefVertexShader, fs, what);
            }

        // Relief surface: the relief quad and the pieces of up to 4 side polygons (kMaxReliefVertices), as
        // eye-relative positions and texture coordinates: (s, t, 1) on the quad, the homogeneous plane coordinates
        // (U, V, W) on the side polygons.
        glGenVertexArrays(1, &m.relief_vao);
        glGenBuffers(1, &m.relief_vbo);
        glBindVertexArray(m.relief_vao);
        glBindBuffer(GL_ARRAY_BUFFER, m.relief_vbo);
        glBufferData(GL_ARRAY_BUFFER, kMaxReliefVertices * 6 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(0));
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));

        // Quad: 4 vertices of (x, y, z, s, t), rewritten per draw.
        glGenVertexArrays(1, &m.quad_vao);
        glGenBuffers(1, &m.quad_vbo);
        glBindVertexArray(m.quad_vao);
        glBindBuffer(GL_ARRAY_BUFFER, m.quad_vbo);
        glBufferData(GL_ARRAY_BUFFER, 4 * 5 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 5 * sizeof(float), reinterpret_cast<void*>(0));
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 5 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));

        // Mesh: MeshVertex array and 32-bit indices, re-specified per draw.
        make_mesh_vertex_array(m.mesh_vao, m.mesh_vbo, m.mesh_ebo);
        check_gl("Renderer: creating shaders and buffers");
    } catch (...) {
        m.destroy();
        delete impl_;
        throw;
    }
}

Renderer::~Renderer() {
    impl_->destroy();
    delete impl_;
}

void Renderer::begin_frame(const Camera& cam) {
    if (cam.width <= 0 || cam.height <= 0)
        throw std::invalid_argument("Renderer::begin_frame: camera image size " + std::to_string(cam.width) + "x" +
                                    std::to_string(cam.height) + " is not positive");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, cam.width, cam.height);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);  // relief quads and mesh faces are visible from both sides
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClearDepth(1.0);
    impl_->clear_pending = true;
    check_gl("Renderer::begin_frame");
}

void Renderer::clear_if_pending() { impl_->issue_pending_clear(); }

void Renderer::draw_textured_quad(const Camera& cam, const std::array<glm::dvec3, 4>& corners, const GlTexture& tex) {
    impl_->issue_pending_clear();
    if (tex.width() <= 0 || tex.height() <= 0) return;  // nothing uploaded: nothing to draw
    // (u, v) of the corners, in texture units: (0,0), (1,0), (1,1), (0,1); GL gets t = 1 - v (see the top of file).
    static constexpr float kUV[4][2] = {{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}};
    float data[4][5];
    for (int i = 0; i < 4; ++i) {
        data[i][0] = float(corners[size_t(i)].x);
        data[i][1] = float(corners[size_t(i)].y);
        data[i][2] = float(corners[size_t(i)].z);
        data[i][3] = kUV[i][0];
        data[i][4] = 1.0f - kUV[i][1];
    }
    const glm::mat4 mvp = mvp_of(cam);
    Impl& m = *impl_;
    glUseProgram(m.quad_program);
    glUniformMatrix4fv(m.quad_mvp, 1, GL_FALSE, glm::value_ptr(mvp));
    glUniform1i(m.quad_texture, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex.id());
    glBindVertexArray(m.quad_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m.quad_vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof(data), data);
    glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
    glBindVertexArray(0);
    check_gl("Renderer::draw_textured_quad");
}

void Renderer::draw_relief(const Camera& cam, const ReliefSurface& rs, const GlTexture& color) {
    impl_->issue_pending_clear();
    if (color.width() <= 0 || color.height() <= 0 || rs.width <= 0 || rs.height <= 0) return;
    const glm::dvec3 E = cam.eye;
    const glm::dvec3 f = glm::normalize(glm::cross(rs.a, rs.b));
    const glm::dvec3 c = rs.origin - E;
    const double cf = glm::dot(c, f);  // the plane's signed distance from the eye
    const glm::dvec3 aw = rs.a * double(rs.width), bh = rs.b * double(rs.height);
    // Dual basis of (a, b) in the plane: u = dot(p - origin, da), v = dot(p - origin, db).
    const double aa = glm::dot(rs.a, rs.a), ab = glm::dot(rs.a, rs.b), bb = glm::dot(rs.b, rs.b);
    const double det = aa * bb - ab * ab;
    const glm::dvec3 da = (rs.a * bb - rs.b * ab) / det, db = (rs.b * aa - rs.a * ab) / det;

    // Eye-relative positions: the quad, then the side polygons' pieces outside the quad's viewing cone
    // (texmap/wall_clip.h). Fragment shader invocations at 512x512, 256^2 reliefs (GL_ARB_pipeline_statistics_query
    // on llvmpipe): facade 181,360 -> 168,048 at azimuth 30, elevation 20 and 132,176 -> 93,296 at 80, 5; where the
    // walls stand beside the quad rather than in front of it (bumps, bricks, ridges) 0.0 to 0.7% more, from the
    // overlap bands and partly covered blocks along the cuts.
    const std::array<glm::dvec3, 4> quad = {c, c + aw, c + aw + bh, c + bh};
    std::vector<Polygon3> polygons{Polygon3(quad.begin(), quad.end())};
    if (rs.wall_high > rs.wall_low) {
        const glm::dvec3 lo = f * rs.wall_low, hi = f * rs.wall_high;
        // The cone shrunk by a sliver: 1e-4 of the eye's distance plus the quad's size, about a tenth of a pixel
        // where the quad fills the view, far above float rounding of the positions (6e-8 of the distance).
        const double margin = 1e-4 * (glm::length(aw + bh) + glm::length(c + 0.5 * (aw + bh)));
        // Cut down further to what can show a sample (wall_content): at 512x512, 256^2 reliefs, azimuth 30,
        // elevation 20, pipelined, the side polygons' fragment shader invocations and the texture-mapping time
        // (median of 3000 frames, 2 runs each): bumps 30,272 -> 13,264, 0.59 -> 0.49 ms; ridges 55,728 -> 49,616,
        // 0.70 -> 0.65 ms; bricks 5,280 -> 5,424 (parts overlap), 0.47 either way. margin_content costs 5 us.
        auto wall = [&](glm::dvec3 p0, glm::dvec3 p1) {
            for (Polygon3& piece : outside_view_cone({p0 + lo, p1 + lo, p1 + hi, p0 + hi}, quad, margin)) {
                if (!rs.wall_content) {
                    polygons.push_back(std::move(piece));
                    continue;
                }
                for (Polygon3& part : inside_plane_rects(piece, c, rs.a, rs.b, *rs.wall_content))
                    polygons.push_back(std::move(part));
            }
        };
        if (rs.margin_left > 0) wall(c, c + bh);
        if (rs.margin_right > 0) wall(c + aw, c + aw + bh);
        if (rs.margin_bottom > 0) wall(c, c + aw);
        if (rs.margin_top > 0) wall(c + bh, c + aw + bh);
    }
    // The quad's corners carry their texture coordinates (the texture holds the quad at (margin_left,
    // margin_bottom); t = 1 - v as everywhere in this file); the side polygons carry their homogeneous plane
    // coordinates (U, V, W) (see kReliefFragmentShaderBody).
    const double inv_w = 1.0 / color.width(), inv_h = 1.0 / color.height();
    const double u0 = rs.margin_left * inv_w, u1 = (rs.margin_left + rs.width) * inv_w;
    const double t0 = 1.0 - rs.margin_bottom * inv_h, t1 = 1.0 - (rs.margin_bottom + rs.height) * inv_h;
    const std::array<glm::dvec2, 4> quad_st = {glm::dvec2(u0, t0), glm::dvec2(u1, t0), glm::dvec2(u1, t1),
                                               glm::dvec2(u0, t1)};
    const double c_da = glm::dot(c, da), c_db = glm::dot(c, db);
    std::vector<float> data;
    std::vector<GLint> first{0};  // each polygon's first vertex; first.back() = vertices in all
    for (size_t i = 0; i < polygons.size(); ++i) {
        for (size_t k = 0; k < polygons[i].size(); ++k) {
            const glm::dvec3& r = polygons[i][k];
            glm::dvec3 st;
            if (i == 0) {
                st = glm::dvec3(quad_st[k], 1.0);
            } else {
                const double w = glm::dot(r, f) / cf;
                st = glm::dvec3(glm::dot(r, da) - w * c_da, glm::dot(r, db) - w * c_db, w);
            }
            data.insert(data.end(), {float(r.x), float(r.y), float(r.z), float(st.x), float(st.y), float(st.z)});
        }
        first.push_back(first.back() + GLint(polygons[i].size()));
    }
    if (first.back() > kMaxReliefVertices)
        throw std::logic_error("Renderer::draw_relief: " + std::to_string(first.back()) + " vertices exceed " +
                               std::to_string(kMaxReliefVertices));
    const glm::dmat4 mvp_rel = cam.projection() * cam.view() * glm::translate(glm::dmat4(1.0), E);
    const glm::dmat4 proj = cam.projection();
    const glm::dvec3 forward = glm::normalize(cam.look_at - cam.eye);

    Impl& m = *impl_;
    auto use_program = [&](GLuint prog) {
        glUseProgram(prog);
        auto loc = [&](const char* name) { return glGetUniformLocation(prog, name); };
        auto vec3u = [&](const char* name, const glm::dvec3& v) {
            glUniform3f(loc(name), float(v.x), float(v.y), float(v.z));
        };
        const glm::mat4 mvpf(mvp_rel);
        glUniformMatrix4fv(loc("u_mvp_rel"), 1, GL_FALSE, glm::value_ptr(mvpf));
        vec3u("u_forward", forward);
        glUniform4f(loc("u_uv"), float(rs.margin_left), float(rs.margin_bottom), float(inv_w), float(inv_h));
        glUniform2f(loc("u_size"), float(rs.width), float(rs.height));
        glUniform1f(loc("u_k3"), float(rs.k3));
        glUniform1f(loc("u_dmin"), float(rs.dmin));
        glUniform1f(loc("u_dmax"), float(rs.dmax));
        glUniform1f(loc("u_qs"), float(rs.qs));
        // Perspective: ndc z = -P[2][2] + P[3][2] / Z for a point at distance Z in front of the eye.
        glUniform2f(loc("u_ndc"), float(-proj[2][2]), float(proj[3][2]));
        glUniform1i(loc("u_color"), 0);
        glUniform1i(loc("u_displ"), 1);
    };
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, color.id());
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, rs.displ ? rs.displ->id() : color.id());
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(m.relief_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m.relief_vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(data.size() * sizeof(float)), data.data());
    const int depth = rs.displ ? 1 : 0;
    use_program(m.relief_program[depth][0]);
    glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
    if (polygons.size() > 1) {
        use_program(m.relief_program[depth][1]);
        for (size_t i = 1; i < polygons.size(); ++i) glDrawArrays(GL_TRIANGLE_FAN, first[i], first[i + 1] - first[i]);
    }
    glBindVertexArray(0);
    check_gl("Renderer::draw_relief");
}

void Renderer::draw_mesh(const Camera& cam, const std::vector<MeshVertex>& vertices,
                         const std::vector<uint32_t>& indices, const glm::dvec3& origin) {
    impl_->issue_pending_clear();
    const size_t count = indices.size() - indices.size() % 3;  // whole triangles only
    if (vertices.empty() || count == 0) return;
    for (size_t i = 0; i < count; ++i)
        if (indices[i] >= vertices.size())
            throw std::out_of_range("Renderer::draw_mesh: index " + std::to_string(i) + " is " +
                                    std::to_string(indices[i]) + " but there are only " +
                                    std::to_string(vertices.size()) + " vertices");
    const glm::mat4 mvp = mvp_of(cam, origin);
    Impl& m = *impl_;
    glUseProgram(m.mesh_program);
    glUniformMatrix4fv(m.mesh_mvp, 1, GL_FALSE, glm::value_ptr(mvp));
    glBindVertexArray(m.mesh_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m.mesh_vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(MeshVertex)), vertices.data(), GL_STREAM_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(count * sizeof(uint32_t)), indices.data(), GL_STREAM_DRAW);
    glDrawElements(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    check_gl("Renderer::draw_mesh");
}

void Renderer::draw_mesh_ranges(const Camera& cam, const GlMesh& mesh, const std::vector<IndexRange>& ranges,
                                const glm::dvec3& origin) {
    impl_->issue_pending_clear();
    std::vector<GLsizei> counts;
    std::vector<const void*> offsets;
    counts.reserve(ranges.size());
    offsets.reserve(ranges.size());
    for (size_t i = 0; i < ranges.size(); ++i) {
        const IndexRange& r = ranges[i];
        if (r.first % 3 != 0 || r.count % 3 != 0 || size_t(r.first) + r.count > mesh.index_count())
            throw std::out_of_range("Renderer::draw_mesh_ranges: range " + std::to_string(i) + " (first " +
                                    std::to_string(r.first) + ", count " + std::to_string(r.count) +
                                    ") is not whole triangles within the mesh's " + std::to_string(mesh.index_count()) +
                                    " indices");
        if (r.count == 0) continue;
        counts.push_back(GLsizei(r.count));
        offsets.push_back(reinterpret_cast<const void*>(size_t(r.first) * sizeof(uint32_t)));
    }
    if (counts.empty()) return;
    const glm::mat4 mvp = mvp_of(cam, origin);
    Impl& m = *impl_;
    glUseProgram(m.mesh_program);
    glUniformMatrix4fv(m.mesh_mvp, 1, GL_FALSE, glm::value_ptr(mvp));
    glBindVertexArray(mesh.vertex_array());
    glMultiDrawElements(GL_TRIANGLES, counts.data(), GL_UNSIGNED_INT, offsets.data(), GLsizei(counts.size()));
    glBindVertexArray(0);
    check_gl("Renderer::draw_mesh_ranges");
}

void Renderer::finish() {
    if (impl_->timed) glFinish();
}

void Renderer::set_timed(bool timed) { impl_->timed = timed; }

bool Renderer::timed() const { return impl_->timed; }

int Renderer::max_texture_size() const {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    return max_size;
}

ImageRGBA8 Renderer::read_pixels(int width, int height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("Renderer::read_pixels: size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is not positive");
    impl_->issue_pending_clear();
    ImageRGBA8 flipped(width, height);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, flipped.pixels.data());
    check_gl("Renderer::read_pixels: glReadPixels");
    // GL returns the bottom row first; ours is top first.
    ImageRGBA8 img(width, height);
    for (int r = 0; r < height; ++r)
        std::copy(flipped.row(height - 1 - r), flipped.row(height - 1 - r) + width, img.row(r));
    return img;
}

}  // namespace rtm
