#include "viewer/perpixel_panel.h"

#include <imgui.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace rtm::viewer {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// A slider over an int setting, narrow like the panel's others.
void int_slider(const char* label, int& v, int lo, int hi, float u) {
    ImGui::SetNextItemWidth(140 * u);
    ImGui::SliderInt(label, &v, lo, hi);
}

bool float_slider(const char* label, float& v, float lo, float hi, float u, const char* format = "%.3f") {
    ImGui::SetNextItemWidth(140 * u);
    return ImGui::SliderFloat(label, &v, lo, hi, format);
}

// Relief mapping's two searches, shared by the methods that use them.
void linear_binary(int& linear, int& binary, float u) {
    int_slider("linear steps", linear, 1, 256, u);
    int_slider("binary steps", binary, 0, 32, u);
}

}  // namespace

void perpixel_settings_panel(PerPixelMethod m, PerPixelSettings& p, float u) {
    switch (m) {
        case PerPixelMethod::parallax:
        case PerPixelMethod::parallax_offset_limiting:
            float_slider("scale", p.parallax.scale, 0.0f, 2.0f, u);
            float_slider("bias", p.parallax.bias, -0.5f, 0.5f, u);
            break;
        case PerPixelMethod::steep_parallax:
            int_slider("min steps", p.steep_parallax.min_steps, 1, 256, u);
            int_slider("max steps", p.steep_parallax.max_steps, 1, 256, u);
            break;
        case PerPixelMethod::parallax_occlusion:
            int_slider("nMinSamples", p.parallax_occlusion.nMinSamples, 1, 256, u);
            int_slider("nMaxSamples", p.parallax_occlusion.nMaxSamples, 1, 256, u);
            break;
        case PerPixelMethod::relief_mapping:
            linear_binary(p.relief_mapping.linear_search_steps, p.relief_mapping.binary_search_steps, u);
            break;
        case PerPixelMethod::interval_mapping:
            int_slider("linear steps", p.interval_mapping.linear_search_steps, 1, 256, u);
            int_slider("max iterations", p.interval_mapping.max_iterations, 1, 64, u);
            float_slider("threshold", p.interval_mapping.convergence_threshold, 0.0f, 0.1f, u, "%.4f");
            break;
        case PerPixelMethod::protruded_displacement: {
            ProtrudedDisplacementSettings& pd = p.protruded_displacement;
            linear_binary(pd.linear_search_steps, pd.binary_search_steps, u);
            ImGui::Checkbox("steep slopes: wall texture", &pd.steep_texture);
            if (pd.steep_texture) {
                float_slider("steep threshold", pd.steep_threshold, 0.0f, 1.0f, u, "%.2f");
                float_slider("wall scale x", pd.steep_scale_x, 0.25f, 16.0f, u, "%.2f");
                float_slider("wall scale y", pd.steep_scale_y, 0.25f, 16.0f, u, "%.2f");
            }
            break;
        }
        case PerPixelMethod::quadric_silhouettes: {
            QuadricSilhouettesSettings& q = p.quadric_silhouettes;
            linear_binary(q.linear_search_steps, q.binary_search_steps, u);
            int base = q.base == CurvedShape::sphere ? 1 : 0;
            ImGui::RadioButton("cylinder", &base, 0);
            ImGui::SameLine();
            ImGui::RadioButton("sphere", &base, 1);
            const CurvedShape shape = base == 1 ? CurvedShape::sphere : CurvedShape::cylinder;
            if (shape != q.base) q.set_base(shape);
            float angle = float(q.angle);
            if (float_slider("bend (rad)", angle, 0.05f, 3.0f, u, "%.2f")) q.angle = angle;
            ImGui::Checkbox("quadrics (off: the mesh's silhouette)", &q.quadric);
            ImGui::Checkbox("exact distance (equation 6)", &q.exact_distance);
            break;
        }
    }
    PerPixelCommon& c = p.common;
    ImGui::Checkbox("shading", &c.shading);
    if (c.shading) {
        ImGui::SameLine();
        ImGui::Checkbox("self-shadowing", &c.self_shadowing);
        // The light's direction as azimuth about +y (0 = +z) and elevation, as the --orbit convention.
        const glm::dvec3 l = glm::normalize(c.light_dir);
        float az = float(std::atan2(l.x, l.z) / kDegree), el = float(std::asin(l.y) / kDegree);
        // Written back only when moved: the round trip through degrees in float would change the setting (and
        // the frame's cache keys) every frame.
        const bool moved = float_slider("light azimuth", az, -180.0f, 180.0f, u, "%.0f") |
                           float_slider("light elevation", el, -89.0f, 89.0f, u, "%.0f");
        if (moved)
            c.light_dir = glm::dvec3(std::cos(el * kDegree) * std::sin(az * kDegree), std::sin(el * kDegree),
                                     std::cos(el * kDegree) * std::cos(az * kDegree));
        float_slider("ambient", c.ambient, 0.0f, 1.0f, u, "%.2f");
        if (c.self_shadowing) int_slider("shadow steps", c.shadow_steps, 1, 256, u);
    }
    ImGui::Checkbox("iteration counts", &c.iteration_counts);
    bool papers = !c.float_textures;
    if (ImGui::Checkbox("8-bit textures (the papers')", &papers)) c.float_textures = !papers;
    if (ImGui::Button("defaults")) p = PerPixelSettings{};
}

}  // namespace rtm::viewer
