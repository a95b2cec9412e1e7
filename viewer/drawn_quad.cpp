#include "viewer/drawn_quad.h"

#include <glm/geometric.hpp>

#include <algorithm>

#include "warp/prewarp_coefficients.h"

namespace rtm::viewer {

bool maps_prewarp(RenderMethod method, const std::vector<std::string>& skips) {
    return prewarps(method) && std::find(skips.begin(), skips.end(), kSkipSubpixelParallax) == skips.end();
}

DrawnQuad fill_drawn_quad(ReliefQuad& quad, const std::string& name, const Camera& cam, int level,
                          const GlTexture& texture, bool warped) {
    DrawnQuad q;
    q.name = name;
    q.corners = quad.corners();
    q.level = level;
    const ReliefTexture& t = quad.level(level);
    q.width = t.width;
    q.height = t.height;
    q.texture = texture.id();
    q.texture_width = texture.width();
    q.texture_height = texture.height();
    q.warped = warped;
    const PrewarpCoefficients k = compute_coefficients(t.geometry, cam.eye);
    q.epipole = {k.epipole_u, k.epipole_v};
    return q;
}

bool describe_drawn_quad(ReliefQuad& quad, const std::string& name, const Camera& cam, const ViewSettings& s,
                         const std::vector<std::string>& skips, int level, DrawnQuad& q) {
    auto fired = [&](const char* k) { return std::find(skips.begin(), skips.end(), k) != skips.end(); };
    if (fired(kSkipOutsideFrustum) || fired(kSkipBackFacing) || fired(kSkipInsideSlab) || !quad.texture()) return false;
    if (!quad.faces(cam.eye)) return false;
    q = fill_drawn_quad(quad, name, cam, level, *quad.texture(), maps_prewarp(s.method, skips));
    if (!q.warped) return true;
    q.margins = quad.last_stats().extent;
    if (s.side_polygons) {
        const ReliefTexture& t = quad.level(level);
        // The side polygons along each border that has a margin, spanning [min(0, dmin), max(0, dmax)] along f
        // (texmap/renderer.h, ReliefSurface); drawn clipped to what can show a texel, outlined whole here.
        const glm::dvec3 f = glm::normalize(glm::cross(t.geometry.a, t.geometry.b));
        const double lo = std::min(0.0, t.quant.min), hi = std::max(0.0, t.quant.max);
        const auto& c = q.corners;
        const int margin[4] = {q.margins.bottom, q.margins.right, q.margins.top, q.margins.left};
        for (int e = 0; e < 4; ++e) {
            if (margin[e] <= 0 || !(hi > lo)) continue;
            const glm::dvec3 p0 = c[size_t(e)], p1 = c[size_t((e + 1) % 4)];
            q.side_polygons.push_back({p0 + f * lo, p1 + f * lo, p1 + f * hi, p0 + f * hi});
        }
    }
    return true;
}

}  // namespace rtm::viewer
