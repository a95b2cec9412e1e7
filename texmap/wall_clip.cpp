#include "texmap/wall_clip.h"

#include <glm/geometric.hpp>

#include <algorithm>
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

namespace {

// The bounding box of the pixels with alpha > 0 in columns [x0, x1), rows [r0, r1) of img; false if none.
bool alpha_bounds(const ImageRGBA8& img, int x0, int x1, int r0, int r1, int& xa, int& xb, int& ra, int& rb) {
    x0 = std::max(x0, 0), x1 = std::min(x1, img.width);
    r0 = std::max(r0, 0), r1 = std::min(r1, img.height);
    bool any = false;
    for (int r = r0; r < r1; ++r) {
        const Rgba8* row = &img.at(0, r);
        int first = x0;
        while (first < x1 && row[first].a == 0) ++first;
        if (first == x1) continue;
        int last = x1 - 1;
        while (row[last].a == 0) --last;
        if (!any) xa = first, xb = last, ra = r, any = true;
        xa = std::min(xa, first), xb = std::max(xb, last), rb = r;
    }
    return any;
}

}  // namespace

std::vector<PlaneRect> margin_content(const ImageRGBA8& img, int margin_left, int margin_right, int margin_bottom,
                                      int margin_top) {
    std::vector<PlaneRect> rects;
    const int W = img.width, H = img.height, ml = margin_left, mb = margin_bottom;
    auto band = [&](int x0, int x1, int r0, int r1) {
        int xa = 0, xb = 0, ra = 0, rb = 0;
        if (!alpha_bounds(img, x0, x1, r0, r1, xa, xb, ra, rb)) return;
        // Pixel (x, row) is the texel square u in [x - ml, x - ml + 1], v in [H - 1 - row - mb, H - row - mb].
        rects.push_back({double(xa - ml) - 1.0, double(H - 1 - rb - mb) - 1.0, double(xb - ml + 1) + 1.0,
                         double(H - ra - mb) + 1.0});
    };
    if (margin_left > 0) band(0, ml + 1, 0, H);
    if (margin_right > 0) band(W - margin_right - 1, W, 0, H);
    if (margin_bottom > 0) band(ml, W - margin_right, H - mb - 1, H);
    if (margin_top > 0) band(ml, W - margin_right, 0, margin_top + 1);
    return rects;
}

std::vector<Polygon3> inside_plane_rects(const Polygon3& poly, const glm::dvec3& c, const glm::dvec3& a,
                                         const glm::dvec3& b, const std::vector<PlaneRect>& rects) {
    const glm::dvec3 f = glm::cross(a, b);
    const double cf = glm::dot(c, f);
    // Every vertex's ray must meet the plane ahead of the eye: then so does every point's (the polygon is convex),
    // and a point lies on the same side of a plane through the eye as the point where its ray meets the plane.
    for (const glm::dvec3& p : poly)
        if (!(glm::dot(p, f) * cf > 0.0)) return {poly};
    std::vector<Polygon3> pieces;
    for (const PlaneRect& r : rects) {
        const std::array<glm::dvec3, 4> corner = {c + a * r.u0 + b * r.v0, c + a * r.u1 + b * r.v0,
                                                  c + a * r.u1 + b * r.v1, c + a * r.u0 + b * r.v1};
        const glm::dvec3 centre = 0.25 * (corner[0] + corner[1] + corner[2] + corner[3]);
        Polygon3 piece = poly;
        for (size_t i = 0; i < 4 && !piece.empty(); ++i) {
            glm::dvec3 n = glm::cross(corner[i], corner[(i + 1) % 4]);
            if (glm::dot(n, centre) < 0.0) n = -n;  // inwards
            piece = clip_to_half_space(piece, n, 0.0, true);
        }
        if (!piece.empty()) pieces.push_back(std::move(piece));
    }
    return pieces;
}

}  // namespace rtm
