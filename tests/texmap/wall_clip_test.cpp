// Side polygons less the quad's viewing cone (texmap/wall_clip.h): exact on a hand-made case, and a sweep over
// random quads, eyes and walls (seed printed; RTM_SEED overrides it) checking that the pieces keep every point
// whose eye ray misses the quad and drop every point whose ray meets it well inside.
#include "texmap/wall_clip.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>

namespace rtm {
namespace {

uint64_t seed_or(uint64_t fallback) {
    if (const char* s = std::getenv("RTM_SEED")) return std::strtoull(s, nullptr, 10);
    return fallback;
}

TEST(ClipToHalfSpace, SquareCutThroughTheMiddleIsExact) {
    const Polygon3 square = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const Polygon3 right = clip_to_half_space(square, {1, 0, 0}, 0.5, true);
    const Polygon3 want_right = {{0.5, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0.5, 1, 1}};
    EXPECT_EQ(right, want_right);
    const Polygon3 left = clip_to_half_space(square, {1, 0, 0}, 0.5, false);
    const Polygon3 want_left = {{0, 0, 1}, {0.5, 0, 1}, {0.5, 1, 1}, {0, 1, 1}};
    EXPECT_EQ(left, want_left);
    EXPECT_TRUE(clip_to_half_space(square, {1, 0, 0}, 2.0, true).empty());  // nothing on that side
    EXPECT_EQ(clip_to_half_space(square, {1, 0, 0}, 2.0, false), square);   // all of it
    // A corner cut adds one vertex.
    EXPECT_EQ(clip_to_half_space(square, {1, 1, 0}, 0.5, false).size(), 3u);
    EXPECT_EQ(clip_to_half_space(square, {1, 1, 0}, 0.5, true).size(), 5u);
}

TEST(OutsideViewCone, EyeInThePlaneKeepsTheWallWhole) {
    const std::array<glm::dvec3, 4> quad = {glm::dvec3(1, 0, -1), {2, 0, -1}, {2, 0, 1}, {1, 0, 1}};  // plane y = 0
    const Polygon3 wall = {{1, 0, -1}, {1, 0, 1}, {1, 1, 1}, {1, 1, -1}};
    const auto pieces = outside_view_cone(wall, quad, 1e-4);
    ASSERT_EQ(pieces.size(), 1u);
    EXPECT_EQ(pieces[0], wall);
}

bool inside_convex(const Polygon3& poly, const glm::dvec3& normal, const glm::dvec3& p, double tol) {
    for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec3 e = poly[(k + 1) % poly.size()] - poly[k];
        if (glm::dot(glm::cross(e, p - poly[k]), normal) < -tol) return false;
    }
    return true;
}

// The sweep: a random relief plane and quad (a parallelogram), an eye off the plane, a wall standing on one of
// the quad's edges from displacement lo to hi. For random points of the wall: where the eye ray through the point
// meets the plane (ahead of the eye) outside the quad (the shader's test), some piece holds the point; a point
// inside the cone by twice the margin is in no piece.
TEST(OutsideViewCone, PiecesKeepWhatMissesTheQuadAndDropWhatMeetsIt) {
    const uint64_t seed = seed_or(20261201);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0), S(0.0, 1.0);
    int kept_checked = 0, dropped_checked = 0;
    for (int iter = 0; iter < 400; ++iter) {
        const glm::dvec3 origin{U(rng), U(rng), U(rng)};
        glm::dvec3 a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)};
        if (glm::length(glm::cross(glm::normalize(a), glm::normalize(b))) < 0.3) continue;
        const glm::dvec3 f = glm::normalize(glm::cross(a, b));
        const glm::dvec3 eye = origin + 0.5 * (a + b) + 3.0 * glm::dvec3(U(rng), U(rng), U(rng)) + f * (0.2 + 2.0 * S(rng)) * (S(rng) < 0.5 ? 1.0 : -1.0);
        // Eye-relative quad and wall.
        const glm::dvec3 c = origin - eye;
        const std::array<glm::dvec3, 4> quad = {c, c + a, c + a + b, c + b};
        const int edge = int(S(rng) * 4) % 4;
        const glm::dvec3 p0 = quad[size_t(edge)], p1 = quad[size_t((edge + 1) % 4)];
        const double lo = -S(rng), hi = S(rng);
        const Polygon3 wall = {p0 + f * lo, p1 + f * lo, p1 + f * hi, p0 + f * hi};
        const double margin = 1e-4 * (glm::length(a + b) + glm::length(c + 0.5 * (a + b)));
        const auto pieces = outside_view_cone(wall, quad, margin);
        const glm::dvec3 wall_normal = glm::cross(wall[1] - wall[0], wall[3] - wall[0]);
        const double tol = 1e-9 * glm::dot(wall_normal, wall_normal);
        for (const Polygon3& piece : pieces) {
            ASSERT_GE(piece.size(), 3u);
            ASSERT_LE(piece.size(), 8u);  // the renderer's vertex budget (kMaxReliefVertices)
            for (const glm::dvec3& v : piece) ASSERT_TRUE(inside_convex(wall, wall_normal, v, tol));
        }
        ASSERT_LE(pieces.size(), 4u);
        // Dual basis for (u, v) in the plane, as the shader has it.
        const double aa = glm::dot(a, a), ab = glm::dot(a, b), bb = glm::dot(b, b), det = aa * bb - ab * ab;
        const glm::dvec3 da = (a * bb - b * ab) / det, db = (b * aa - a * ab) / det;
        const double cf = glm::dot(c, f);
        for (int k = 0; k < 50; ++k) {
            const double s = S(rng), t = S(rng);
            const glm::dvec3 p = (wall[0] * (1 - s) + wall[1] * s) * (1 - t) + (wall[3] * (1 - s) + wall[2] * s) * t;
            const double pf = glm::dot(p, f);
            if (!(std::abs(pf) > 1e-9) || cf / pf <= 0.0) continue;  // the ray does not reach the plane ahead
            const glm::dvec3 q = p * (cf / pf) - c;
            const double u = glm::dot(q, da), v = glm::dot(q, db);
            bool in_some = false;
            for (const Polygon3& piece : pieces) in_some = in_some || inside_convex(piece, wall_normal, p, tol);
            // Well inside: at least twice the margin inside each of the cone's faces (the planes through the eye
            // and the quad's edges), which the ray test below must agree is inside the quad.
            double inside_by = 1e300;
            for (size_t e = 0; e < 4; ++e) {
                glm::dvec3 n = glm::normalize(glm::cross(quad[e], quad[(e + 1) % 4]));
                if (glm::dot(n, c + 0.5 * (a + b)) < 0.0) n = -n;
                inside_by = std::min(inside_by, glm::dot(n, p));
            }
            const bool outside = u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0;
            const bool well_inside = inside_by >= 2.0 * margin;
            ASSERT_FALSE(outside && well_inside) << "iteration " << iter << ": the cone and the ray disagree";
            if (outside) {
                ++kept_checked;
                ASSERT_TRUE(in_some) << "iteration " << iter << ": a point whose ray misses the quad (u " << u
                                     << ", v " << v << ") is in no piece";
            } else if (well_inside) {
                ++dropped_checked;
                ASSERT_FALSE(in_some) << "iteration " << iter << ": a point whose ray meets the quad at (u " << u
                                      << ", v " << v << ") is in a piece";
            }
        }
    }
    EXPECT_GT(kept_checked, 1000);
    EXPECT_GT(dropped_checked, 1000);
}

}  // namespace
}  // namespace rtm
