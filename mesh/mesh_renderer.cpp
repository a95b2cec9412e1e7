// MeshRenderer: OpenGL 3.3 core, one draw call per part (mesh/mesh_renderer.h).
//
// Texture orientation: images are uploaded as stored (row 0 = top of the picture at t = 0), while mesh texture
// coordinates put v = 0 at the bottom of the picture (OpenGL's and assimp's convention), so the shader samples
// (u, 1 - v).
#include "mesh/mesh_renderer.h"

#include <glad/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "texmap/gl_context.h"
#include "texmap/gl_program.h"

namespace rtm {
namespace {

static_assert(sizeof(MeshVertexAttribs) == 24, "MeshVertexAttribs must be 5 floats and 4 bytes, tightly packed");

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec4 a_color;
uniform mat4 u_clip;
uniform vec4 u_plane;
out vec2 v_uv;
out vec4 v_color;
out float v_distance;
void main() {
    v_uv = a_uv;
    v_color = a_color;
    v_distance = dot(u_plane.xyz, a_position) + u_plane.w;
    gl_Position = u_clip * vec4(a_position, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 v_uv;
in vec4 v_color;
in float v_distance;
uniform sampler2D u_texture;
uniform int u_use_texture;
uniform int u_use_vertex_color;
uniform vec4 u_base;
layout(location = 0) out vec4 o_color;
layout(location = 1) out float o_distance;
void main() {
    vec4 c = u_base;
    if (u_use_texture != 0) c *= texture(u_texture, vec2(v_uv.x, 1.0 - v_uv.y));
    if (u_use_vertex_color != 0) c.rgb *= v_color.rgb;
    if (c.a < 0.5) discard;  // alpha is coverage
    o_color = vec4(c.rgb, 1.0);
    o_distance = v_distance;
}
)";

}  // namespace

struct MeshRenderer::Impl {
    GLuint program = 0, vao = 0, vbo = 0, ebo = 0;
    GLint u_clip = -1, u_plane = -1, u_texture = -1, u_use_texture = -1, u_use_vertex_color = -1, u_base = -1;
    std::vector<GLuint> textures;  // per material, 0 = none
    std::vector<MeshPart> parts;
    std::vector<MeshMaterial> materials;  // colours only (textures live on the GPU)
    GLuint fbo = 0, rb_color = 0, rb_distance = 0, rb_depth = 0;
    int fb_width = 0, fb_height = 0;

    void ensure_framebuffer(int w, int h) {
        if (fbo && w == fb_width && h == fb_height) return;
        GLint max_rb = 0, dims[2] = {0, 0};
        glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
        glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
        const int limit = std::min<int>(max_rb, std::min(dims[0], dims[1]));
        if (w <= 0 || h <= 0 || w > limit || h > limit)
            throw GlError("mesh rendering: image size " + std::to_string(w) + "x" + std::to_string(h) +
                          " is outside 1.." + std::to_string(limit) + " per side");
        if (!fbo) {
            glGenFramebuffers(1, &fbo);
            glGenRenderbuffers(1, &rb_color);
            glGenRenderbuffers(1, &rb_distance);
            glGenRenderbuffers(1, &rb_depth);
        }
        glBindRenderbuffer(GL_RENDERBUFFER, rb_color);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
        glBindRenderbuffer(GL_RENDERBUFFER, rb_distance);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_R32F, w, h);
        glBindRenderbuffer(GL_RENDERBUFFER, rb_depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb_color);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, rb_distance);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb_depth);
        const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            throw GlError("mesh rendering: framebuffer incomplete (status " + std::to_string(status) + ")");
        check_gl("mesh rendering: framebuffer");
        fb_width = w;
        fb_height = h;
    }
    void draw_parts(const glm::dmat4& clip_from_world, const std::optional<glm::dvec4>& plane);
};

// One draw call per part into the bound framebuffer; `plane` (n, w) feeds the distance output.
void MeshRenderer::Impl::draw_parts(const glm::dmat4& clip_from_world, const std::optional<glm::dvec4>& plane) {
    Impl& m = *this;
    glUseProgram(m.program);
    const glm::mat4 clip(clip_from_world);
    glUniformMatrix4fv(m.u_clip, 1, GL_FALSE, glm::value_ptr(clip));
    const glm::vec4 pl = plane ? glm::vec4(*plane) : glm::vec4(0.0f);
    glUniform4f(m.u_plane, pl.x, pl.y, pl.z, pl.w);
    glUniform1i(m.u_texture, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(m.vao);
    for (const MeshPart& p : m.parts) {
        const size_t mi = size_t(std::max(p.material, 0));
        const bool tex = p.use_texture && mi < m.textures.size() && m.textures[mi] != 0;
        // Vertex colours without a texture stand alone (mesh/triangle_mesh.h).
        const glm::vec4 base = (p.use_vertex_color && !tex) || mi >= m.materials.size() ? glm::vec4(1.0f)
                                                                                        : m.materials[mi].base_color;
        glUniform4f(m.u_base, base.r, base.g, base.b, base.a);
        glUniform1i(m.u_use_texture, tex ? 1 : 0);
        glUniform1i(m.u_use_vertex_color, p.use_vertex_color ? 1 : 0);
        glBindTexture(GL_TEXTURE_2D, tex ? m.textures[mi] : 0);
        glDrawElements(GL_TRIANGLES, GLsizei(p.index_count), GL_UNSIGNED_INT,
                       (void*)(size_t(p.first_index) * sizeof(uint32_t)));
    }
    glBindVertexArray(0);
    check_gl("mesh rendering: draw");
}

MeshRenderer::MeshRenderer(const TriangleMesh& mesh) : impl_(new Impl) {
    Impl& m = *impl_;
    try {
        m.program = link_program(kVertexShader, kFragmentShader, "mesh");
        m.u_clip = glGetUniformLocation(m.program, "u_clip");
        m.u_plane = glGetUniformLocation(m.program, "u_plane");
        m.u_texture = glGetUniformLocation(m.program, "u_texture");
        m.u_use_texture = glGetUniformLocation(m.program, "u_use_texture");
        m.u_use_vertex_color = glGetUniformLocation(m.program, "u_use_vertex_color");
        m.u_base = glGetUniformLocation(m.program, "u_base");

        glGenVertexArrays(1, &m.vao);
        glBindVertexArray(m.vao);
        glGenBuffers(1, &m.vbo);
        glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertices.size() * sizeof(MeshVertexAttribs)),
                     mesh.vertices.data(), GL_STATIC_DRAW);
        glGenBuffers(1, &m.ebo);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ebo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(),
                     GL_STATIC_DRAW);
        const GLsizei stride = sizeof(MeshVertexAttribs);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(MeshVertexAttribs, position));
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(MeshVertexAttribs, uv));
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, (void*)offsetof(MeshVertexAttribs, color));
        glBindVertexArray(0);

        GLint max_tex = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_tex);
        for (const MeshMaterial& mat : mesh.materials) {
            MeshMaterial colour_only{mat.name, mat.base_color, {}};
            m.materials.push_back(colour_only);
            GLuint t = 0;
            if (!mat.texture.empty()) {
                if (mat.texture.width > max_tex || mat.texture.height > max_tex)
                    throw GlError("mesh rendering: material " + mat.name + ": texture of " +
                                  std::to_string(mat.texture.width) + "x" + std::to_string(mat.texture.height) +
                                  " exceeds the GL limit of " + std::to_string(max_tex));
                glGenTextures(1, &t);
                glBindTexture(GL_TEXTURE_2D, t);
                glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
                glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
                glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, mat.texture.width, mat.texture.height, 0, GL_RGBA,
                             GL_UNSIGNED_BYTE, mat.texture.pixels.data());
                glGenerateMipmap(GL_TEXTURE_2D);
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
            }
            m.textures.push_back(t);
        }
        m.parts = mesh.parts;
        check_gl("mesh rendering: upload");
    } catch (...) {
        delete impl_;
        throw;
    }
}

MeshRenderer::~MeshRenderer() {
    Impl& m = *impl_;
    if (glad_glDeleteProgram) {
        for (GLuint t : m.textures)
            if (t) glDeleteTextures(1, &t);
        if (m.program) glDeleteProgram(m.program);
        if (m.vbo) glDeleteBuffers(1, &m.vbo);
        if (m.ebo) glDeleteBuffers(1, &m.ebo);
        if (m.vao) glDeleteVertexArrays(1, &m.vao);
        if (m.fbo) {
            glDeleteFramebuffers(1, &m.fbo);
            glDeleteRenderbuffers(1, &m.rb_color);
            glDeleteRenderbuffers(1, &m.rb_distance);
            glDeleteRenderbuffers(1, &m.rb_depth);
        }
    }
    delete impl_;
}

MeshFrame MeshRenderer::render(const glm::dmat4& clip_from_world, int width, int height, Rgba8 background,
                               const std::optional<glm::dvec4>& plane, bool cull_back_faces) {
    Impl& m = *impl_;
    m.ensure_framebuffer(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, buffers);
    glViewport(0, 0, width, height);
    glDisable(GL_BLEND);
    if (cull_back_faces) {
        glEnable(GL_CULL_FACE);
        glFrontFace(GL_CCW);
        glCullFace(GL_BACK);
    } else {
        glDisable(GL_CULL_FACE);
    }
    glDisable(GL_MULTISAMPLE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const float bg[4] = {background.r / 255.0f, background.g / 255.0f, background.b / 255.0f, background.a / 255.0f};
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    glClearBufferfv(GL_COLOR, 0, bg);
    glClearBufferfv(GL_COLOR, 1, zero);
    glClearBufferfv(GL_DEPTH, 0, &one);

    m.draw_parts(clip_from_world, plane);

    MeshFrame frame;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    ImageRGBA8 color(width, height);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, color.pixels.data());
    // GL returns the bottom row first; ours is top first.
    frame.color = ImageRGBA8(width, height);
    for (int r = 0; r < height; ++r)
        std::copy(color.row(height - 1 - r), color.row(height - 1 - r) + width, frame.color.row(r));
    if (plane) {
        ImageF d(width, height);
        glReadBuffer(GL_COLOR_ATTACHMENT1);
        glReadPixels(0, 0, width, height, GL_RED, GL_FLOAT, d.pixels.data());
        frame.distance = ImageF(width, height);
        for (int r = 0; r < height; ++r)
            std::copy(d.row(height - 1 - r), d.row(height - 1 - r) + width, frame.distance.row(r));
    }
    check_gl("mesh rendering: read back");
    glDisable(GL_CULL_FACE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return frame;
}

void MeshRenderer::draw(const glm::dmat4& clip_from_world) { impl_->draw_parts(clip_from_world, std::nullopt); }

ImageRGBA8 MeshRenderer::render(const Camera& cam) {
    return render(cam.projection() * cam.view(), cam.width, cam.height, Rgba8{0, 0, 0, 255}).color;
}

}  // namespace rtm
