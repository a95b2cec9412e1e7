#include "texmap/wall_clip.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace rtm {

Polygon3 clip_to_half_space(const Polygon3& poly, const glm::dvec3& n, double offset, bool keep_above) {
    Polygon3 out;
    const size_t count = poly.size();
    if (count < 3) return out;
    out.reserve(count + 1);
    auto side = [&](const glm::dvec3& p) {
        const double s = glm::dot(n, p) - offset;
        return keep_above ? s : -s;  // >= 0: kept (keep_above), > 0: kept (below)
    };
    auto kept = [&](double s) { return keep_above ? s >= 0.0 : s > 0.0; };
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec3& a = poly[i];
        const glm::dvec3& b = poly[(i + 1) % count];
        const double sa = side(a), sb = side(b);
        if (kept(sa)) out.push_back(a);
        if (kept(sa) != kept(sb)) out.push_back(a + (b - a) * (sa / (sa - sb)));  // the edge crosses the plane
    }
    if (out.size() < 3) out.clear();
    return out;
}

std::vector<Polygon3> outside_view_cone(const Polygon3& poly, const std::array<glm::dvec3, 4>& quad, double margin) {
    std::vector<Polygon3> pieces;
    const glm::dvec3 centre = 0.25 * (quad[0] + quad[1] + quad[2] + quad[3]);
    const glm::dvec3 normal = glm::cross(quad[1] - quad[0], quad[3] - quad[0]);
    const double scale = glm::length(quad[2] - quad[0]) + glm::length(centre);
    // The eye in (or within rounding of) the quad's plane: no cone to cut out.
    if (!(std::abs(glm::dot(glm::normalize(normal), centre)) > 1e-9 * scale)) {
        pieces.push_back(poly);
        return pieces;
    }
    std::array<glm::dvec3, 4> planes;
    for (size_t i = 0; i < 4; ++i) {
        glm::dvec3 n = glm::cross(quad[i], quad[(i + 1) % 4]);
        const double len = glm::length(n);
        if (!(len > 0.0)) {  // an edge on a line through the eye: no cone
            pieces.assign(1, poly);
            return pieces;
        }
        n /= len;
        if (glm::dot(n, centre) < 0.0) n = -n;  // inwards: the quad's centre is inside
        planes[i] = n;
    }
    // Piece i: outside plane i (shrunk), inside planes 0 .. i-1 (shrunk by half as much). Together: poly less the
    // shrunk cone. Neighbouring pieces overlap by a band instead of sharing an edge: a shared edge whose two sides
    // end at different vertices (a T-junction) is not watertight under rasterization.
    Polygon3 rest = poly;
    for (size_t i = 0; i < 4 && !rest.empty(); ++i) {
        Polygon3 piece = clip_to_half_space(rest, planes[i], margin, false);
        if (!piece.empty()) pieces.push_back(std::move(piece));
        rest = clip_to_half_space(rest, planes[i], 0.5 * margin, true);
    }
    return pieces;
}

}  // namespace rtm
