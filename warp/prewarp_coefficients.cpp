#include "warp/prewarp_coefficients.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rtm {

PrewarpCoefficients compute_coefficients(const ReliefGeometry& g, const glm::dvec3& eye) {
    PrewarpCoefficients k;
    k.eye = eye;
    const glm::dvec3 f = g.f();
    const glm::dvec3 c = g.origin - eye;
    const double cf = glm::dot(c, f);
    k.distance = -cf;

    // The epipole is the orthogonal projection of E onto the plane, in (u, v) texel units: solve
    // E - origin - f*dist = a*u + b*v with the dual basis of (a, b) in the plane.
    const glm::dvec3 p = (eye - g.origin) - f * k.distance;
    const double aa = glm::dot(g.a, g.a), ab = glm::dot(g.a, g.b), bb = glm::dot(g.b, g.b);
    const double det = aa * bb - ab * ab;
    const double pa = glm::dot(p, g.a), pb = glm::dot(p, g.b);
    k.epipole_u = (pa * bb - pb * ab) / det;
    k.epipole_v = (pb * aa - pa * ab) / det;

    // The viewer counts as in the plane when its distance is below a tiny fraction of the scale of the
    // configuration (texel size and distance of E from the origin), where 1/dot(c, f) loses all meaning.
    const double scale = std::max({std::sqrt(aa), std::sqrt(bb), glm::length(c)});
    if (!(std::abs(cf) > 1e-12 * scale)) {
        k.side = ViewSide::on_plane;
        k.k1 = k.k2 = k.k3 = 0.0;
        return k;
    }
    k.side = cf < 0.0 ? ViewSide::front : ViewSide::behind;
    const glm::dvec3 bxc = glm::cross(g.b, c), cxa = glm::cross(c, g.a);
    const double den = glm::dot(g.a, bxc);
    k.k1 = glm::dot(f, bxc) / den;
    k.k2 = glm::dot(f, cxa) / den;
    k.k3 = 1.0 / cf;
    return k;
}

bool PrewarpCoefficients::warp(double u_s, double v_s, double d, double& u_i, double& v_i) const {
    const double den = 1.0 + k3 * d;
    if (!(den > 0.0)) return false;
    u_i = (u_s + k1 * d) / den;
    v_i = (v_s + k2 * d) / den;
    return true;
}

std::string PrewarpCoefficients::to_string() const {
    static const char* sides[] = {"front", "on_plane", "behind"};
    char buf[256];
    std::snprintf(buf, sizeof buf, "PrewarpCoefficients{k1=%.17g, k2=%.17g, k3=%.17g, epipole=(%.17g, %.17g), %s}", k1,
                  k2, k3, epipole_u, epipole_v, sides[int(side)]);
    return buf;
}

}  // namespace rtm
