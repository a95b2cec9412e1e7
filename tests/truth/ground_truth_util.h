// Helpers for the ground-truth tests (micromesh, raycast): small reliefs built from functions, random geometry,
// and an independent evaluation of the bilinear surface and colour straight from docs/FORMATS.md.
// Header-only so it does not clash with other helpers compiled into objects_tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <random>

#include "common/seed.h"
#include "warp/relief_texture.h"

namespace rtm::truth_test {

inline uint64_t seed(uint64_t fallback) { return test::test_seed(fallback); }

// A w x h relief: displacement disp(x, row) (world units), colour col(x, row), texel empty where empty(x, row).
template <class Disp, class Col, class Empty>
ReliefTexture make_relief_fn(int w, int h, const ReliefGeometry& g, Disp disp, Col col, Empty empty) {
    ImageRGBA8 c(w, h);
    ImageF d(w, h);
    double lo = 1e300, hi = -1e300;
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) {
            Rgba8 p = col(x, r);
            p.a = empty(x, r) ? 0 : 255;
            c.at(x, r) = p;
            d.at(x, r) = float(disp(x, r));
            lo = std::min(lo, double(d.at(x, r)));
            hi = std::max(hi, double(d.at(x, r)));
        }
    return make_relief(c, d, lo, hi, g);
}

// Colours from a hash of the texel position (every texel different, so orientation mistakes show).
inline Rgba8 hash_color(int x, int r) {
    uint32_t s = uint32_t(x) * 73856093u ^ uint32_t(r) * 19349663u;
    s *= 2654435761u;
    return {uint8_t(s >> 24), uint8_t(s >> 16), uint8_t(s >> 8), 255};
}

// Non-axis-aligned, non-orthogonal, non-square a and b.
inline ReliefGeometry random_geometry(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> U(-1.0, 1.0), S(0.3, 3.0);
    for (;;) {
        const glm::dvec3 a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)};
        if (glm::length(glm::cross(glm::normalize(a), glm::normalize(b))) < 0.3) continue;
        ReliefGeometry g;
        g.origin = {U(rng), U(rng), U(rng)};
        g.a = glm::normalize(a) * (S(rng) * 0.01);
        g.b = glm::normalize(b) * (S(rng) * 0.01);
        return g;
    }
}

// (u, v, d) coordinates of a world point: P = origin + a*u + b*v + f*d.
inline glm::dvec3 to_uvd(const ReliefGeometry& g, const glm::dvec3& p) {
    return glm::inverse(glm::dmat3(g.a, g.b, g.f())) * (p - g.origin);
}
inline glm::dvec3 from_uvd(const ReliefGeometry& g, const glm::dvec3& q) {
    return g.origin + g.a * q.x + g.b * q.y + g.f() * q.z;
}

// The bilinear surface through the texel centres at (u, v) in [0.5, w-0.5] x [0.5, h-0.5] (no holes assumed).
inline double surface_height(const ReliefTexture& t, double u, double v) {
    const int i = std::min(int(std::floor(u - 0.5)), t.width - 2), j = std::min(int(std::floor(v - 0.5)), t.height - 2);
    const double s = u - (i + 0.5), r = v - (j + 0.5);
    // v-row j is image row h-1-j (docs/FORMATS.md)
    const double h00 = t.displ(i, t.height - 1 - j), h10 = t.displ(i + 1, t.height - 1 - j);
    const double h01 = t.displ(i, t.height - 2 - j), h11 = t.displ(i + 1, t.height - 2 - j);
    return h00 * (1 - s) * (1 - r) + h10 * s * (1 - r) + h01 * (1 - s) * r + h11 * s * r;
}

// Unrounded bilinear colour channel (0 = r, 1 = g, 2 = b) at (u, v).
inline double surface_color(const ReliefTexture& t, double u, double v, int ch) {
    const int i = std::min(int(std::floor(u - 0.5)), t.width - 2), j = std::min(int(std::floor(v - 0.5)), t.height - 2);
    const double s = u - (i + 0.5), r = v - (j + 0.5);
    const auto c = [&](int x, int row) {
        const ReliefTexel& tx = t.texel(x, row);
        return double(ch == 0 ? tx.r : ch == 1 ? tx.g : tx.b);
    };
    return c(i, t.height - 1 - j) * (1 - s) * (1 - r) + c(i + 1, t.height - 1 - j) * s * (1 - r) +
           c(i, t.height - 2 - j) * (1 - s) * r + c(i + 1, t.height - 2 - j) * s * r;
}

}  // namespace rtm::truth_test
