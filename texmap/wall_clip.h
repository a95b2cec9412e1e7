// The part of a side polygon that can show anything: what lies outside the quad's viewing cone.
//
// A side polygon's fragment shows the texture where its eye ray meets the relief plane, and is discarded when that
// point is on the quad itself (the quad draws it; texmap/renderer.cpp). Those are exactly the fragments inside the
// cone from the eye through the quad, so cutting that cone out of the polygon on the CPU leaves the same picture
// and spares llvmpipe the shading of every fragment the shader would discard (the near wall of a tall relief stands
// in front of most of the quad). Cutting a convex region out of a convex polygon leaves up to four convex pieces.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <vector>

#include "warp/image.h"

namespace rtm {

using Polygon3 = std::vector<glm::dvec3>;

// The part of convex polygon `poly` where dot(n, p) >= offset (keep_above) or dot(n, p) < offset (otherwise),
// by Sutherland-Hodgman; empty when nothing (or a degenerate sliver of fewer than 3 vertices) remains.
Polygon3 clip_to_half_space(const Polygon3& poly, const glm::dvec3& n, double offset, bool keep_above);

// Positions are relative to the eye (the cone's apex is the origin); `quad` is the relief quad's corners in order
// (convex). Returns up to four convex pieces whose union is `poly` less the cone through `quad` shrunk by `margin`
// (a length: each of the cone's four planes moved that far inwards), so that the pieces overlap the cone by a
// sliver and float rounding of their edges cannot open a gap along the quad's outline; the shader's own test still
// discards what falls on the quad. Neighbouring pieces overlap by a band too (see the .cpp). When the eye lies in
// the quad's plane (no cone: every ray misses the quad or grazes it), `poly` is returned whole.
std::vector<Polygon3> outside_view_cone(const Polygon3& poly, const std::array<glm::dvec3, 4>& quad, double margin);

// A rectangle of the relief plane in texel units: u to the right, v up, the quad is [0, width] x [0, height].
struct PlaneRect {
    double u0 = 0.0, v0 = 0.0, u1 = 0.0, v1 = 0.0;
    bool operator==(const PlaneRect&) const = default;
};

// Where a side polygon can show anything. A side polygon's fragment is drawn only where the texture, bilinearly
// filtered at its eye ray's plane point outside the quad, has alpha of at least one half; the weights are zero
// beyond one texel from a texel's centre, so some texel with alpha > 0 lies within one texel of that point: a
// texel of a margin, or of the quad's outermost row or column. Returns one rectangle per margin band that has
// such texels (left and right bands: all rows of the margin's columns; bottom and top bands: the margin's rows
// between them; each band also takes the quad's row or column next to it): the bounding box of those texels'
// squares widened by one texel on every side (half a texel of it spare, against rounding). `img` is the texture
// (rows top first) whose quad lies margin_left texels from its left and margin_bottom from its bottom, and so on;
// a band whose margin is 0 cannot be reached (its plane points fall outside the texture). Scans only
// the margins and the quad's outermost texels: about 5 us for a 256^2 relief with margins (bumps, 296x290; 2-core
// development machine).
std::vector<PlaneRect> margin_content(const ImageRGBA8& img, int margin_left, int margin_right, int margin_bottom,
                                      int margin_top);

// The parts of convex polygon `poly` (eye-relative, like the quad's plane: origin `c`, texel axes `a`, `b`) whose
// eye rays meet the plane inside one of `rects`: `poly` clipped by the four planes through the eye and each
// rectangle's edges, one piece per rectangle it reaches (pieces may overlap where rectangles do; an overlap is
// drawn twice, the same fragments). `poly` is returned whole when some point of it sends its eye ray away from the
// plane (at or beyond the eye's side of the plane's parallel through the eye), where the side test would not hold.
std::vector<Polygon3> inside_plane_rects(const Polygon3& poly, const glm::dvec3& c, const glm::dvec3& a,
                                         const glm::dvec3& b, const std::vector<PlaneRect>& rects);

}  // namespace rtm
