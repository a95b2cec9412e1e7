// How deep a point of the eye ray lies under the quadric of relief mapping with quadric silhouettes (Oliveira and
// Policarpo, "An efficient representation for surface details", UFRGS tech. report RP-351, 2005, section 3), in
// texture space: the fragment at the origin, on the quadric z = alpha x^2 + beta y^2 (z outwards, x and y along the
// tangent and the binormal, scaled so that the relief's depth range is 1 and the texture tile is 1 x 1; the paper's
// equation 8), the ray P(t) = v t going in (v.z < 0). The depth is 0 on the quadric, 1 at the bottom of the relief,
// negative outside the quadric.
//
// - Approximate (equation 7, section 3.2): the height of P above the quadric at (P.x, P.y), negated:
//   depth = alpha P.x^2 + beta P.y^2 - P.z.
// - Exact (equations 4 to 6, section 3.1): the distance s from P along U, the unit vector perpendicular to the ray in
//   the plane of the ray and the normal (pointing out), to where P + U s meets the quadric: the root of
//   A s^2 + B s + C = 0 with A = alpha U.x^2 + beta U.y^2, B = 2 alpha P.x U.x + 2 beta P.y U.y - U.z and C the
//   approximate depth above. The paper takes "the positive value"; here, for a point inside (C > 0), the smallest
//   positive root, and for one outside (C < 0) the largest negative one (a signed distance, which the silhouette
//   test reads). Where the discriminant is negative, or no root has that sign, or the ray is along the normal (no
//   U), the distance is equation 7's, as the paper prescribes for the negative discriminant (its Figure 8, right).
//
// What the exact distance is on a flat base (alpha = beta = 0): depth / sin(angle between the ray and the normal), the
// distance along U, not the depth under the surface, which equation 7 gives exactly there. So the two agree at
// grazing rays, where the silhouettes are, and differ most at steeper ones, where the exact one makes the ray reach
// the relief's depth sooner (docs/PERPIXEL.md measures it).
//
// These are the reference of the fragment shader (perpixel/quadric_silhouettes_glsl.cpp), which computes the same
// in float, step for step.
#pragma once

#include <glm/vec3.hpp>

namespace rtm {

struct QuadricRay {
    glm::dvec3 v{0.0, 0.0, -1.0};    // the ray's direction in texture space (not unit: texture space is scaled)
    double alpha = 0.0, beta = 0.0;  // the quadric z = alpha x^2 + beta y^2 in texture space (the paper's equation 8)
};

// Equation 7: alpha P.x^2 + beta P.y^2 - P.z at P = v t.
double quadric_depth_approximate(const QuadricRay& r, double t);

struct QuadricDepth {
    double depth = 0.0;
    bool exact = false;  // false: equation 7 stood in (no U, negative discriminant or no root of the right sign)
};

// U: the unit vector perpendicular to v in the plane of v and the normal (0, 0, 1), with U.z > 0; (0, 0, 0) when v is
// along the normal (within 1e-12 of it in sin(angle)).
glm::dvec3 quadric_distance_direction(const glm::dvec3& v);

// Equation 6 at P = v t, falling back to equation 7 as above.
QuadricDepth quadric_depth_exact(const QuadricRay& r, double t);

// The search range (section 3.3): the smallest t > 0 at which the depth returns to 0 (the ray leaves the quadric: a
// silhouette if it has not met the relief) or reaches 1 (the bottom). For the approximate distance both from
// equation 7; for the exact one from equation 5 with s = 0 (the same as equation 7's zero) and s = 1, as the paper
// says, and equation 7's bottom where equation 7 stands in for equation 6. On a convex quadric the exact depth is
// shorter than equation 7's and may never reach 1: such a ray leaves where equation 7 would have found the bottom.
struct QuadricSearchRange {
    double t_max = 0.0;
    bool leaves = false;  // t_max is where the ray comes back out at depth 0
    bool valid = false;   // false: the ray does not go in (v.z >= 0)
};
QuadricSearchRange quadric_search_range(const QuadricRay& r, bool exact);

}  // namespace rtm
