// Pre-warp coefficients (paper section 3.1, equations 4a/4b) for one relief texture and one centre of projection.
// With c = origin - E:
//     k1 = dot(f, cross(b, c)) / dot(a, cross(b, c)),  k2 = dot(f, cross(c, a)) / dot(a, cross(b, c)),
//     k3 = 1 / dot(c, f)
//     u_i = (u_s + k1*d) / (1 + k3*d),  v_i = (v_s + k2*d) / (1 + k3*d)      (texel units, d in world units)
// Equivalently u_i - e_u = (u_s - e_u) / (1 + k3*d): a scaling about the epipole (e_u, e_v) = (k1/k3, k2/k3),
// the orthogonal projection of E onto the relief plane. For a viewer in front of the relief (+f side, k3 < 0),
// texels standing out (d > 0) move away from the epipole; the occlusion-compatible order warps from the borders
// towards the epipole. All in double precision.
#pragma once

#include <glm/vec3.hpp>

#include <string>

#include "relief_texture.h"

namespace rtm {

enum class ViewSide {
    front,     // E strictly on the +f side: the relief quad faces the viewer
    on_plane,  // E in the relief plane (|dot(c, f)| tiny relative to the scene): no pre-warp is defined
    behind,    // E on the -f side: the quad faces away and is not drawn (paper section 6)
};

struct PrewarpCoefficients {
    double k1 = 0.0, k2 = 0.0, k3 = 0.0;
    double epipole_u = 0.0, epipole_v = 0.0;  // in texel units
    double distance = 0.0;                    // signed distance of E from the plane along f (= -dot(c, f))
    ViewSide side = ViewSide::front;
    glm::dvec3 eye{0.0};

    // Exact pre-warp of one texel centre (u_s, v_s) with displacement d. Returns false when 1 + k3*d <= 0 (the
    // point is at or behind the viewer's plane parallel to the relief: it cannot be pre-warped).
    bool warp(double u_s, double v_s, double d, double& u_i, double& v_i) const;
    std::string to_string() const;
};

PrewarpCoefficients compute_coefficients(const ReliefGeometry& g, const glm::dvec3& eye);

}  // namespace rtm
