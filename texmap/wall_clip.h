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

}  // namespace rtm
