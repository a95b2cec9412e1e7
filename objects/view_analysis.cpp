#include "objects/view_analysis.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtm {

bool outside_frustum(const Camera& cam, const Bounds& box) {
    if (box.empty()) return true;
    const glm::dmat4 m = cam.projection() * cam.view();
    glm::dvec4 clip[8];
    int n = 0;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p{(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y, (i & 4) ? box.hi.z : box.lo.z};
        clip[n++] = m * glm::dvec4(p, 1.0);
    }
    // Clip planes: -w <= x, y, z <= w.
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            bool all_out = true;
            for (int i = 0; i < 8 && all_out; ++i) all_out = sign * clip[i][axis] > clip[i].w;
            if (all_out) return true;
        }
    return false;
}

double projected_area_pixels(const Camera& cam, const std::array<glm::dvec3, 4>& quad) {
    const glm::dmat4 m = cam.projection() * cam.view();
    double xs[4], ys[4];
    for (int i = 0; i < 4; ++i) {
        const glm::dvec4 c = m * glm::dvec4(quad[size_t(i)], 1.0);
        if (!(c.w > 1e-12)) return -1.0;
        xs[i] = (c.x / c.w * 0.5 + 0.5) * cam.width;
        ys[i] = (c.y / c.w * 0.5 + 0.5) * cam.height;
    }
    double a = 0;
    for (int i = 0; i < 4; ++i) {
        const int j = (i + 1) % 4;
        a += xs[i] * ys[j] - xs[j] * ys[i];
    }
    return std::abs(a) * 0.5;
}

double max_parallax_texels(const ReliefTexture& t, const PrewarpCoefficients& k) {
    if (k.side == ViewSide::on_plane) return std::numeric_limits<double>::infinity();
    double du = 0, dv = 0;
    for (double d : {t.quant.min, t.quant.max}) {
        const double den = 1.0 + k.k3 * d;
        if (!(den > 0.0)) return std::numeric_limits<double>::infinity();
        const double s = 1.0 / den - 1.0;
        for (double us : {0.0, double(t.width)}) du = std::max(du, std::abs((us - k.epipole_u) * s));
        for (double vs : {0.0, double(t.height)}) dv = std::max(dv, std::abs((vs - k.epipole_v) * s));
    }
    return std::hypot(du, dv);
}

double max_texel_motion(const ReliefTexture& t, const PrewarpCoefficients& k0, const PrewarpCoefficients& k1) {
    if (k0.side == ViewSide::on_plane || k1.side == ViewSide::on_plane) return std::numeric_limits<double>::infinity();
    double worst = 0;
    const int levels = 33;
    for (int i = 0; i < levels; ++i) {
        const double d = t.quant.min + (t.quant.max - t.quant.min) * i / (levels - 1);
        for (double us : {0.0, double(t.width)})
            for (double vs : {0.0, double(t.height)}) {
                double u0, v0, u1, v1;
                const bool ok0 = k0.warp(us, vs, d, u0, v0), ok1 = k1.warp(us, vs, d, u1, v1);
                if (ok0 != ok1) return std::numeric_limits<double>::infinity();
                if (!ok0) continue;
                worst = std::max(worst, std::hypot(u1 - u0, v1 - v0));
            }
    }
    return worst;
}

bool eye_inside_slab(const ReliefTexture& t, const glm::dvec3& eye) {
    const double dist = glm::dot(eye - t.geometry.origin, t.geometry.f());
    const double lo = std::min(0.0, t.quant.min), hi = std::max(0.0, t.quant.max);
    if (!(hi > lo)) return false;
    return dist >= lo && dist <= hi;
}

}  // namespace rtm
