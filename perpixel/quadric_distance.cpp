#include "perpixel/quadric_distance.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <initializer_list>

namespace rtm {

namespace {

// The roots of a x^2 + b x + c = 0 in the stable form (no cancellation between -b and the square root); false when
// there is none. With a = 0 the one root of the linear equation, twice.
bool roots(double a, double b, double c, double& r1, double& r2) {
    if (a == 0.0) {
        if (b == 0.0) return false;
        r1 = r2 = -c / b;
        return true;
    }
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return false;
    const double q = -0.5 * (b + (b >= 0.0 ? 1.0 : -1.0) * std::sqrt(disc));
    r1 = q / a;
    r2 = q != 0.0 ? c / q : r1;  // q = 0 needs b = 0 and c = 0: the double root 0
    return true;
}

}  // namespace

double quadric_depth_approximate(const QuadricRay& r, double t) {
    const glm::dvec3 P = r.v * t;
    return r.alpha * P.x * P.x + r.beta * P.y * P.y - P.z;
}

glm::dvec3 quadric_distance_direction(const glm::dvec3& v) {
    const glm::dvec3 n = glm::normalize(v);
    const glm::dvec3 w = glm::dvec3(0.0, 0.0, 1.0) - n.z * n;  // the normal less its part along the ray
    const double len = glm::length(w);                         // sin(angle between the ray and the normal)
    return len < 1e-12 ? glm::dvec3(0.0) : w / len;
}

QuadricDepth quadric_depth_exact(const QuadricRay& r, double t) {
    const double C = quadric_depth_approximate(r, t);
    const glm::dvec3 U = quadric_distance_direction(r.v);
    if (!(U.z > 0.0)) return {C, false};
    if (C == 0.0) return {0.0, true};  // on the quadric
    const glm::dvec3 P = r.v * t;
    const double A = r.alpha * U.x * U.x + r.beta * U.y * U.y;
    const double B = 2.0 * (r.alpha * P.x * U.x + r.beta * P.y * U.y) - U.z;
    double r1 = 0, r2 = 0;
    if (!roots(A, B, C, r1, r2)) return {C, false};
    // Inside (C > 0): the nearest point of the quadric outwards along U; outside: the nearest inwards.
    double best = 0.0;
    for (double s : {r1, r2})
        if ((C > 0.0 ? s > 0.0 : s < 0.0) && (best == 0.0 || std::abs(s) < std::abs(best))) best = s;
    if (best == 0.0) return {C, false};
    return {best, true};
}

QuadricSearchRange quadric_search_range(const QuadricRay& r, bool exact) {
    QuadricSearchRange out;
    const double c1 = -r.v.z;
    if (!(c1 > 0.0)) return out;
    out.valid = true;
    const double k = -(r.alpha * r.v.x * r.v.x + r.beta * r.v.y * r.v.y);  // equation 7: depth = c1 t - k t^2
    const double t_out = k > 0.0 ? c1 / k : -1.0;  // back at depth 0 (both distances are 0 there: C = 0)
    // Equation 7 at depth 1: k t^2 - c1 t + 1 = 0, the smaller root (none when k > c1^2 / 4: the ray leaves first).
    const double disc7 = c1 * c1 - 4.0 * k;
    const double t7 = disc7 >= 0.0 ? 2.0 / (c1 + std::sqrt(disc7)) : -1.0;
    double t_bottom = t7;
    const glm::dvec3 U = quadric_distance_direction(r.v);
    if (exact && U.z > 0.0) {
        // The first t at which the exact depth is 1: where s = 1 solves equation 5,
        // alpha (v.x t + U.x)^2 + beta (v.y t + U.y)^2 - (v.z t + U.z) = 0, with P inside (C > 0) and 1 the nearest
        // root of its side (the other root of A s^2 + B s + C is C / A); or equation 7's bottom where equation 6 has
        // no root and equation 7 stands in. On a convex quadric the exact depth can stay under 1 all the way to where
        // the ray comes back out (it is shorter than equation 7's there), so equation 7's bottom is no bound for it.
        const double A = r.alpha * U.x * U.x + r.beta * U.y * U.y;
        t_bottom = -1.0;
        auto consider = [&](double t) {
            if (t > 0.0 && (t_bottom < 0.0 || t < t_bottom)) t_bottom = t;
        };
        double r1 = 0, r2 = 0;
        if (roots(-k, 2.0 * (r.alpha * r.v.x * U.x + r.beta * r.v.y * U.y) - r.v.z, A - U.z, r1, r2))
            for (double t : {r1, r2}) {
                const double C = quadric_depth_approximate(r, t);
                if (C > 0.0 && !(A != 0.0 && C / A > 0.0 && C / A < 1.0)) consider(t);
            }
        if (t7 > 0.0 && !quadric_depth_exact(r, t7).exact) consider(t7);
        if (t_bottom < 0.0 && t_out < 0.0) t_bottom = t7;  // neither found: equation 7's range
    }
    out.leaves = t_out > 0.0 && (t_bottom < 0.0 || t_out < t_bottom);
    out.t_max = out.leaves ? t_out : t_bottom;
    return out;
}

}  // namespace rtm
