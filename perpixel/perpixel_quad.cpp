#include "perpixel/perpixel_quad.h"

#include <glad/gl.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <array>
#include <string>
#include <vector>

#include "perpixel/curved_patch.h"
#include "perpixel/relief_map.h"
#include "perpixel/shader_common.h"
#include "perpixel/steep_texture.h"
#include "texmap/gl_context.h"
#include "texmap/gl_program.h"

namespace rtm {

extern const char* const kQuadricVertexShader;

PerPixelQuad::PerPixelQuad() = default;

PerPixelQuad::~PerPixelQuad() {
    if (!glad_glDeleteProgram) return;
    for (const auto& [key, p] : programs_) glDeleteProgram(p);
    if (vbo_) glDeleteBuffers(1, &vbo_);
    if (vao_) glDeleteVertexArrays(1, &vao_);
    if (quadric_vbo_) glDeleteBuffers(1, &quadric_vbo_);
    if (quadric_ebo_) glDeleteBuffers(1, &quadric_ebo_);
    if (quadric_vao_) glDeleteVertexArrays(1, &quadric_vao_);
}

unsigned PerPixelQuad::program(PerPixelMethod m, const PerPixelCommon& c, bool quadric_exact, bool steep) {
    quadric_exact = quadric_exact && m == PerPixelMethod::quadric_silhouettes;
    steep = steep && m == PerPixelMethod::protruded_displacement;
    const auto key = std::make_tuple(int(m), c.depth_correction, c.shading, c.shading && c.self_shadowing,
                                     c.iteration_counts, c.float_textures, quadric_exact, steep);
    auto it = programs_.find(key);
    if (it != programs_.end()) return it->second;
    const char* vs = m == PerPixelMethod::quadric_silhouettes ? kQuadricVertexShader : kPerPixelVertexShader;
    const GLuint p = link_program(vs, perpixel_fragment_shader(m, c, quadric_exact, steep), to_string(m));
    programs_[key] = p;
    return p;
}

void PerPixelQuad::prepare(PerPixelMethod m, const PerPixelCommon& common, bool quadric_exact, bool steep) {
    (void)program(m, common, quadric_exact, steep);
}

void PerPixelQuad::set_steep_texture(const ImageRGBA8& img) {
    if (img.width <= 0 || img.height <= 0)
        throw std::invalid_argument("steep texture: expected an image, found " + std::to_string(img.width) + "x" +
                                    std::to_string(img.height));
    steep_image_ = std::make_unique<ImageRGBA8>(img);
}

void PerPixelQuad::draw(Renderer& renderer, const Camera& cam, const ReliefTexture& t, PerPixelMethod m,
                        const PerPixelSettings& s) {
    s.validate();
    renderer.clear_if_pending();
    if (t.width <= 0 || t.height <= 0) return;
    if (!color_) {
        // Both colour textures and both depths (PerPixelCommon::float_textures picks per draw).
        const ImageRGBA8 color = perpixel_color_texture(t);
        color_ = std::make_unique<GlTexture>();
        color_->upload(color);
        color_float_ = std::make_unique<GlTexture>();
        color_float_->upload_as_float(color);
        relief_map_ = std::make_unique<GlTexture>();
        relief_map_->upload(perpixel_relief_map(t));
        depth_map_ = std::make_unique<GlTexture>();
        depth_map_->upload_float(perpixel_depth_map(t));
    }
    if (!vao_) {
        glGenVertexArrays(1, &vao_);
        glGenBuffers(1, &vbo_);
        glBindVertexArray(vao_);
        glBindBuffer(GL_ARRAY_BUFFER, vbo_);
        glBufferData(GL_ARRAY_BUFFER, 5 * 4 * 5 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 5 * sizeof(float), reinterpret_cast<void*>(0));
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 5 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
        glBindVertexArray(0);
    }
    const GLuint prog = program(m, s.common, s.quadric_silhouettes.exact_distance,
                                s.protruded_displacement.steep_texture);
    if (m == PerPixelMethod::quadric_silhouettes) return draw_quadric(cam, t, s, prog);

    const ReliefGeometry& g = t.geometry;
    const glm::dvec3 E = cam.eye, f = g.f();
    const double range = t.quant.max - t.quant.min;
    // A zero range (flat relief) still needs a finite V.z: a slab a millionth of the quad's size.
    const double depth_range = std::max(range,
                                        1e-6 * std::max(glm::length(g.a) * t.width, glm::length(g.b) * t.height));
    const glm::dvec3 top = g.origin + f * t.quant.max - E;  // eye-relative origin of the top polygon
    const glm::dvec3 aw = g.a * double(t.width), bh = g.b * double(t.height);
    // The top polygon; for protruded displacement mapping the base polygon and the four side faces instead
    // (their fragments compute their ray's top-plane point, so their st attribute is unused).
    const bool protruded = m == PerPixelMethod::protruded_displacement;
    const glm::dvec3 base = g.origin + f * t.quant.min - E, up = top - base;
    std::vector<std::array<glm::dvec3, 4>> faces;
    if (!protruded) {
        faces.push_back({top, top + aw, top + aw + bh, top + bh});
    } else {
        faces.push_back({base, base + aw, base + aw + bh, base + bh});
        const glm::dvec3 c[4] = {base, base + aw, base + aw + bh, base + bh};
        for (int i = 0; i < 4; ++i) faces.push_back({c[i], c[(i + 1) % 4], c[(i + 1) % 4] + up, c[i] + up});
    }
    const float st[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::vector<float> data;
    for (const auto& face : faces)
        for (int i = 0; i < 4; ++i)
            data.insert(data.end(), {float(face[size_t(i)].x), float(face[size_t(i)].y), float(face[size_t(i)].z),
                                     st[i][0], st[i][1]});
    // Dual basis of (a, b), scaled to st: s = dot(p - origin, da) / width.
    const double aa = glm::dot(g.a, g.a), ab = glm::dot(g.a, g.b), bb = glm::dot(g.b, g.b);
    const double det = aa * bb - ab * ab;
    const glm::dvec3 da = (g.a * bb - g.b * ab) / (det * t.width), db = (g.b * aa - g.a * ab) / (det * t.height);
    const glm::dmat4 mvp_rel = cam.projection() * cam.view() * glm::translate(glm::dmat4(1.0), E);
    const glm::dmat4 proj = cam.projection();
    const glm::dvec3 forward = glm::normalize(cam.look_at - cam.eye);
    const glm::dvec3 light = glm::normalize(s.common.light_dir);

    glUseProgram(prog);
    auto loc = [&](const char* name) { return glGetUniformLocation(prog, name); };
    auto vec3u = [&](const char* name, const glm::dvec3& v) {
        glUniform3f(loc(name), float(v.x), float(v.y), float(v.z));
    };
    const glm::mat4 mvpf(mvp_rel);
    glUniformMatrix4fv(loc("u_mvp_rel"), 1, GL_FALSE, glm::value_ptr(mvpf));
    glUniform1i(loc("u_color"), 0);
    glUniform1i(loc("u_relief"), 1);
    glUniform1i(loc("u_depth"), 2);
    vec3u("u_da", da);
    vec3u("u_db", db);
    vec3u("u_f", f);
    glUniform1f(loc("u_depth_range"), float(depth_range));
    vec3u("u_top", top);
    glUniform2f(loc("u_half_texel"), float(0.5 / t.width), float(0.5 / t.height));
    vec3u("u_forward", forward);
    glUniform2f(loc("u_ndc"), float(-proj[2][2]), float(proj[3][2]));
    vec3u("u_light", light);
    glUniform1f(loc("u_ambient"), s.common.ambient);
    glUniform1i(loc("u_shadow_steps"), s.common.shadow_steps);
    // Each method's parameters into the shared uniforms (perpixel/shader_common.cpp).
    switch (m) {
        case PerPixelMethod::parallax:
        case PerPixelMethod::parallax_offset_limiting:
            glUniform1f(loc("u_scale"), s.parallax.scale);
            glUniform1f(loc("u_bias"), s.parallax.bias);
            break;
        case PerPixelMethod::steep_parallax:
            glUniform1i(loc("u_min_steps"), s.steep_parallax.min_steps);
            glUniform1i(loc("u_max_steps"), s.steep_parallax.max_steps);
            break;
        case PerPixelMethod::parallax_occlusion:
            glUniform1i(loc("u_min_steps"), s.parallax_occlusion.nMinSamples);
            glUniform1i(loc("u_max_steps"), s.parallax_occlusion.nMaxSamples);
            break;
        case PerPixelMethod::relief_mapping:
            glUniform1i(loc("u_linear_search_steps"), s.relief_mapping.linear_search_steps);
            glUniform1i(loc("u_binary_search_steps"), s.relief_mapping.binary_search_steps);
            glUniform1f(loc("u_convergence_threshold"), s.relief_mapping.convergence_threshold);
            glUniform1i(loc("u_max_iterations"), s.relief_mapping.max_iterations);
            break;
        case PerPixelMethod::protruded_displacement:
            glUniform1i(loc("u_linear_search_steps"), s.protruded_displacement.linear_search_steps);
            glUniform1i(loc("u_binary_search_steps"), s.protruded_displacement.binary_search_steps);
            glUniform1f(loc("u_convergence_threshold"), 0.0f);
            glUniform1i(loc("u_max_iterations"), 1);
            if (s.protruded_displacement.steep_texture) {
                const ProtrudedDisplacementSettings& pd = s.protruded_displacement;
                glActiveTexture(GL_TEXTURE3);
                if (!steep_ || steep_image_) {  // the first use, or a texture set since the last upload
                    if (!steep_) steep_ = std::make_unique<GlTexture>();
                    steep_->upload(steep_image_ ? *steep_image_ : builtin_steep_texture());
                    steep_image_.reset();
                    glBindTexture(GL_TEXTURE_2D, steep_->id());
                    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);  // the coordinates run past 1
                    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
                }
                glBindTexture(GL_TEXTURE_2D, steep_->id());
                glUniform1i(loc("u_steep"), 3);
                glUniform4f(loc("u_steep_params"), pd.steep_threshold, pd.steep_scale_x, pd.steep_scale_y, pd.steep_s0);
            }
            break;
        case PerPixelMethod::interval_mapping:
            glUniform1i(loc("u_linear_search_steps"), s.interval_mapping.linear_search_steps);
            glUniform1f(loc("u_convergence_threshold"), s.interval_mapping.convergence_threshold);
            glUniform1i(loc("u_max_iterations"), s.interval_mapping.max_iterations);
            break;
        case PerPixelMethod::quadric_silhouettes:  // returned above: draw_quadric sets its own parameters
            break;
    }
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, depth_map_->id());
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, relief_map_->id());
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, (s.common.float_textures ? color_float_ : color_)->id());
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(data.size() * sizeof(float)), data.data());
    for (size_t i = 0; i < faces.size(); ++i) glDrawArrays(GL_TRIANGLE_FAN, GLint(4 * i), 4);
    glBindVertexArray(0);
    check_gl(("PerPixelQuad::draw " + to_string(m)).c_str());
}

void PerPixelQuad::draw_quadric(const Camera& cam, const ReliefTexture& t, const PerPixelSettings& s, unsigned prog) {
    const QuadricSilhouettesSettings& q = s.quadric_silhouettes;
    const CurvedPatch patch = curved_patch_for(t, q.base, q.angle);
    std::vector<QuadricVertex> vertices;
    std::vector<uint32_t> indices;
    const glm::dvec3 E = cam.eye;
    curved_base_mesh(patch, q.segments, q.rows, vertices, indices, E);  // eye-relative positions
    if (!q.quadric)
        for (QuadricVertex& v : vertices) v.quadric = glm::vec2(0.0f);
    if (!quadric_vao_) {
        glGenVertexArrays(1, &quadric_vao_);
        glGenBuffers(1, &quadric_vbo_);
        glGenBuffers(1, &quadric_ebo_);
        glBindVertexArray(quadric_vao_);
        glBindBuffer(GL_ARRAY_BUFFER, quadric_vbo_);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, quadric_ebo_);
        const GLsizei stride = sizeof(QuadricVertex);
        const size_t offsets[7] = {offsetof(QuadricVertex, position), offsetof(QuadricVertex, normal),
                                   offsetof(QuadricVertex, tangent),  offsetof(QuadricVertex, binormal),
                                   offsetof(QuadricVertex, st),       offsetof(QuadricVertex, quadric),
                                   offsetof(QuadricVertex, tile)};
        const GLint sizes[7] = {3, 3, 3, 3, 2, 2, 2};
        for (GLuint i = 0; i < 7; ++i) {
            glEnableVertexAttribArray(i);
            glVertexAttribPointer(i, sizes[i], GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsets[i]));
        }
        glBindVertexArray(0);
    }
    const double depth = std::max(patch.depth, 1e-6 * std::max(patch.width, patch.height));
    const glm::dmat4 mvp_rel = cam.projection() * cam.view() * glm::translate(glm::dmat4(1.0), E);
    const glm::dmat4 proj = cam.projection();
    const glm::dvec3 forward = glm::normalize(cam.look_at - cam.eye);
    glUseProgram(prog);
    auto loc = [&](const char* name) { return glGetUniformLocation(prog, name); };
    const glm::mat4 mvpf(mvp_rel);
    glUniformMatrix4fv(loc("u_mvp_rel"), 1, GL_FALSE, glm::value_ptr(mvpf));
    glUniform1i(loc("u_color"), 0);
    glUniform1i(loc("u_relief"), 1);
    glUniform1i(loc("u_depth"), 2);
    glUniform1f(loc("u_depth_range"), float(depth));
    glUniform2f(loc("u_half_texel"), float(0.5 / t.width), float(0.5 / t.height));
    glUniform3f(loc("u_forward"), float(forward.x), float(forward.y), float(forward.z));
    glUniform2f(loc("u_ndc"), float(-proj[2][2]), float(proj[3][2]));
    glUniform1i(loc("u_linear_search_steps"), q.linear_search_steps);
    glUniform1i(loc("u_binary_search_steps"), q.binary_search_steps);
    const glm::vec3 light(glm::normalize(s.common.light_dir));
    glUniform3f(loc("u_light"), light.x, light.y, light.z);
    glUniform1f(loc("u_ambient"), s.common.ambient);
    glUniform1i(loc("u_shadow_steps"), s.common.shadow_steps);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, depth_map_->id());
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, relief_map_->id());
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, (s.common.float_textures ? color_float_ : color_)->id());
    glBindVertexArray(quadric_vao_);
    glBindBuffer(GL_ARRAY_BUFFER, quadric_vbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(QuadricVertex)), vertices.data(), GL_STREAM_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(),
                 GL_STREAM_DRAW);
    glDrawElements(GL_TRIANGLES, GLsizei(indices.size()), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    check_gl("PerPixelQuad::draw quadric-silhouettes");
}

}  // namespace rtm
