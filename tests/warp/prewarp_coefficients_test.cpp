#include "warp/prewarp_coefficients.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <random>

#include "test_util.h"

namespace rtm {
namespace {

// Eye somewhere in front of the relief plane (+f side), at a random distance and lateral offset.
glm::dvec3 random_eye_in_front(const ReliefGeometry& g, std::mt19937_64& rng, double size) {
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::uniform_real_distribution<double> L(-2.0, 1.5);  // log10 of distance in units of the relief size
    const glm::dvec3 f = g.f();
    const double dist = std::pow(10.0, L(rng)) * size;
    return g.origin + g.a * (U(rng) * 300) + g.b * (U(rng) * 300) + f * dist;
}

TEST(PrewarpCoefficients, PrewarpedPointAndSurfacePointLieOnOneRay) {
    const uint64_t seed = test::test_seed(20001);
    SCOPED_TRACE("seed " + std::to_string(seed) + " (set RTM_SEED to reproduce)");
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int checked = 0;
    for (int view = 0; view < 2000; ++view) {
        const ReliefGeometry g = test::random_geometry(rng);
        const double size = 256 * glm::length(g.a);
        const glm::dvec3 eye = random_eye_in_front(g, rng, size);
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        ASSERT_EQ(k.side, ViewSide::front) << k.to_string();
        for (int t = 0; t < 5; ++t) {
            const double us = U(rng) * 256, vs = U(rng) * 256;
            // Displacement up to well below the eye's height so 1 + k3*d > 0.
            const double d = (U(rng) * 1.2 - 0.2) * 0.9 * k.distance;
            double ui, vi;
            ASSERT_TRUE(k.warp(us, vs, d, ui, vi));
            const glm::dvec3 X = g.origin + g.a * us + g.b * vs + g.f() * d;
            const glm::dvec3 P = g.origin + g.a * ui + g.b * vi;
            const glm::dvec3 r1 = X - eye, r2 = P - eye;
            // Relative error of collinearity: |sin(angle)| between the two rays. Both are computed from
            // well-conditioned doubles; 1e-9 leaves ~6 orders of magnitude above double rounding.
            const double s = glm::length(glm::cross(r1, r2)) / (glm::length(r1) * glm::length(r2));
            ASSERT_LT(s, 1e-9) << k.to_string() << " us=" << us << " vs=" << vs << " d=" << d;
            ASSERT_GT(glm::dot(r1, r2), 0.0);  // same side of the eye: one ray, not one line
            ++checked;
        }
    }
    EXPECT_EQ(checked, 10000);
}

TEST(PrewarpCoefficients, EpipoleIsFootOfEyeAndEqualsK1OverK3) {
    std::mt19937_64 rng(test::test_seed(20002));
    for (int i = 0; i < 1000; ++i) {
        const ReliefGeometry g = test::random_geometry(rng);
        const glm::dvec3 eye = random_eye_in_front(g, rng, 256 * glm::length(g.a));
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        // Foot of the eye: origin + a*e_u + b*e_v + f*distance == eye.
        const glm::dvec3 back = g.origin + g.a * k.epipole_u + g.b * k.epipole_v + g.f() * k.distance;
        ASSERT_LT(glm::length(back - eye), 1e-9 * (1 + glm::length(eye - g.origin))) << k.to_string();
        ASSERT_NEAR(k.k1 / k.k3, k.epipole_u, 1e-7 * (1 + std::abs(k.epipole_u))) << k.to_string();
        ASSERT_NEAR(k.k2 / k.k3, k.epipole_v, 1e-7 * (1 + std::abs(k.epipole_v))) << k.to_string();
    }
}

TEST(PrewarpCoefficients, SideOfThePlane) {
    ReliefGeometry g;  // a = x, b = y, f = +z
    EXPECT_EQ(compute_coefficients(g, {3, 4, 10}).side, ViewSide::front);
    EXPECT_EQ(compute_coefficients(g, {3, 4, -10}).side, ViewSide::behind);
    EXPECT_EQ(compute_coefficients(g, {3, 4, 0}).side, ViewSide::on_plane);
    const PrewarpCoefficients k = compute_coefficients(g, {3, 4, 10});
    EXPECT_DOUBLE_EQ(k.epipole_u, 3.0);
    EXPECT_DOUBLE_EQ(k.epipole_v, 4.0);
    EXPECT_DOUBLE_EQ(k.k3, -0.1);
    EXPECT_DOUBLE_EQ(k.distance, 10.0);
}

TEST(PrewarpCoefficients, WarpRefusesPointsAtOrAboveTheEyePlane) {
    ReliefGeometry g;
    const PrewarpCoefficients k = compute_coefficients(g, {0, 0, 2});
    double u, v;
    EXPECT_TRUE(k.warp(1, 1, 1.9, u, v));
    EXPECT_FALSE(k.warp(1, 1, 2.0, u, v));
    EXPECT_FALSE(k.warp(1, 1, 3.0, u, v));
}

}  // namespace
}  // namespace rtm
