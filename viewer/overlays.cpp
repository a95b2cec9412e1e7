#include "viewer/overlays.h"

#include <imgui.h>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "warp/quadrants.h"

namespace rtm::viewer {

bool project(const Camera& cam, const glm::dvec3& p, glm::dvec2& px) {
    const glm::dvec4 clip = cam.projection() * cam.view() * glm::dvec4(p, 1.0);
    if (!(clip.w > 1e-12)) return false;
    const double x = clip.x / clip.w, y = clip.y / clip.w;
    px = {(x * 0.5 + 0.5) * cam.width, (0.5 - y * 0.5) * cam.height};
    return std::isfinite(px.x) && std::isfinite(px.y);
}

glm::dvec2 inset_position(const DrawnQuad& q, const glm::dvec2& uv, const glm::dvec2& size) {
    const double w = q.width + q.margins.left + q.margins.right;
    const double h = q.height + q.margins.bottom + q.margins.top;
    return {(uv.x + q.margins.left) / w * size.x, (q.height + q.margins.top - uv.y) / h * size.y};
}

namespace {

ImU32 colour(const Rgba& c) { return IM_COL32(c[0], c[1], c[2], c[3]); }

void polygon(ImDrawList* list, const Camera& cam, const std::array<glm::dvec3, 4>& c, float scale, ImU32 colour) {
    for (size_t i = 0; i < 4; ++i) {
        glm::dvec2 a, b;
        // A segment with an end behind the eye is left out (outlines are a guide, not clipped geometry).
        if (!project(cam, c[i], a) || !project(cam, c[(i + 1) % 4], b)) continue;
        list->AddLine(ImVec2(float(a.x) / scale, float(a.y) / scale), ImVec2(float(b.x) / scale, float(b.y) / scale),
                      colour, 1.5f);
    }
}

}  // namespace

void draw_outlines(ImDrawList* list, const Camera& cam, const FrameReport& report, float scale) {
    for (const DrawnQuad& q : report.quads) {
        for (const auto& s : q.side_polygons) polygon(list, cam, s, scale, IM_COL32(0, 220, 255, 255));
        polygon(list, cam, q.corners, scale, IM_COL32(255, 220, 0, 255));
    }
}

glm::vec4 draw_insets(ImDrawList* list, const FrameReport& report, float display_w, float display_h) {
    constexpr float kMax = 240.f, kGap = 8.f, kLabel = 16.f;
    float right = display_w - kGap;
    glm::vec4 box(0.f);
    float x0 = display_w, y0 = display_h, x1 = 0, y1 = 0;
    for (const DrawnQuad& q : report.quads) {
        if (q.texture_width <= 0 || q.texture_height <= 0) continue;
        const float aspect = float(q.texture_width) / float(q.texture_height);
        const float w = aspect >= 1 ? kMax : kMax * aspect, h = aspect >= 1 ? kMax / aspect : kMax;
        const ImVec2 p0(right - w, display_h - kGap - h), p1(right, display_h - kGap);
        if (p0.x < 0) break;
        list->AddRectFilled(ImVec2(p0.x - 2, p0.y - kLabel - 2), ImVec2(p1.x + 2, p1.y + 2), IM_COL32(40, 40, 40, 255));
        list->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(q.texture)), p0, p1);
        char label[128];
        std::snprintf(label, sizeof label, "%s L%d %dx%d", q.warped ? "pre-warp" : "flat", q.level, q.texture_width,
                      q.texture_height);
        list->AddText(ImVec2(p0.x, p0.y - kLabel), IM_COL32(255, 255, 255, 255), label);
        // The quad itself within the texture's margins.
        const glm::dvec2 size(w, h);
        const glm::dvec2 qa = inset_position(q, {0, q.height}, size), qb = inset_position(q, {q.width, 0}, size);
        list->AddRect(ImVec2(p0.x + float(qa.x), p0.y + float(qa.y)), ImVec2(p0.x + float(qb.x), p0.y + float(qb.y)),
                      IM_COL32(255, 220, 0, 255));
        if (q.warped && std::isfinite(q.epipole.x) && std::isfinite(q.epipole.y)) {
            // The four occlusion-compatible quadrants about the epipole, clipped to the inset, then the epipole.
            const glm::dvec2 e = inset_position(q, q.epipole, size);
            const QuadrantOverlay o = quadrant_overlay({p0.x, p0.y}, {p1.x, p1.y}, {p0.x + e.x, p0.y + e.y});
            for (const QuadrantOverlay::Box& b : o.quadrants)
                list->AddRectFilled(ImVec2(float(b.p0.x), float(b.p0.y)), ImVec2(float(b.p1.x), float(b.p1.y)),
                                    colour(b.colour));
            const float ex = float(o.epipole.x), ey = float(o.epipole.y);
            list->AddLine(ImVec2(ex, p0.y), ImVec2(ex, p1.y), colour(kQuadrantLineColour));
            list->AddLine(ImVec2(p0.x, ey), ImVec2(p1.x, ey), colour(kQuadrantLineColour));
            if (o.inside)
                list->AddCircleFilled(ImVec2(ex, ey), 4.f, colour(kEpipoleColour));
            else
                list->AddCircle(ImVec2(ex, ey), 5.f, colour(kEpipoleColour), 0, 2.f);  // beyond the inset
        }
        // The box reaches the epipole's circle (radius 5, line 2) where it is clamped to the inset's border.
        x0 = std::min(x0, p0.x - 7);
        y0 = std::min(y0, p0.y - kLabel - 7);
        x1 = std::max(x1, std::min(display_w, p1.x + 7));
        y1 = std::max(y1, std::min(display_h, p1.y + 7));
        box = {x0, y0, x1 - x0, y1 - y0};
        right = p0.x - kGap - 4;
    }
    return box;
}

}  // namespace rtm::viewer
