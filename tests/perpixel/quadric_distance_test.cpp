// The ray-quadric distances of relief mapping with quadric silhouettes (perpixel/quadric_distance.h): equation 6's
// point lies on the quadric along U, is the nearest one of its side, and equation 7 stands in only where equation 6
// has no root; the flat base's closed form; the search range ends where the depth reaches 0 or 1. Random sweeps
// print their seed (RTM_SEED reproduces one).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "common/seed.h"
#include "perpixel/quadric_distance.h"

namespace rtm {
namespace {

// The quadric function at a point: alpha x^2 + beta y^2 - z (0 on the quadric, > 0 inside, under it).
double quadric_at(const QuadricRay& r, const glm::dvec3& p) { return r.alpha * p.x * p.x + r.beta * p.y * p.y - p.z; }

// A ray going in (v.z < 0) of random direction and texture-space scale.
glm::dvec3 random_ray(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0), scale(0.2, 5.0);
    for (;;) {
        glm::dvec3 v(u(rng), u(rng), u(rng));
        if (v.z < -0.02 && glm::length(v) > 0.1 && glm::length(v) < 1.0)
            return glm::normalize(v) * glm::dvec3(scale(rng), scale(rng), scale(rng));
    }
}

// On a flat base the exact distance is the depth under the plane divided by sin(angle between the ray and the
// normal): the distance along U, perpendicular to the ray, up to the plane. Closed form, to rounding.
TEST(QuadricDistance, FlatBaseIsDepthOverSinAngle) {
    for (double deg : {1.0, 10.0, 30.0, 45.0, 60.0, 80.0, 89.0}) {
        const double a = deg * M_PI / 180.0;
        QuadricRay r;
        r.v = glm::dvec3(std::sin(a) * 0.8, std::sin(a) * 0.6, -std::cos(a));  // angle `a` from the inward normal
        for (double t : {0.0, 0.1, 0.5, 2.0}) {
            const double depth = quadric_depth_approximate(r, t);
            EXPECT_NEAR(depth, std::cos(a) * t, 1e-15) << deg << " " << t;
            const QuadricDepth e = quadric_depth_exact(r, t);
            EXPECT_TRUE(e.exact) << deg << " " << t;
            EXPECT_NEAR(e.depth, depth / std::sin(a), 1e-12 * (1.0 + depth / std::sin(a))) << deg << " " << t;
        }
        // The bottom: depth / sin = 1 at t = sin / cos.
        const QuadricSearchRange exact = quadric_search_range(r, true), approx = quadric_search_range(r, false);
        ASSERT_TRUE(exact.valid && approx.valid);
        EXPECT_FALSE(exact.leaves);
        EXPECT_FALSE(approx.leaves);
        EXPECT_NEAR(exact.t_max, std::tan(a), 1e-12 * (1.0 + std::tan(a))) << deg;
        EXPECT_NEAR(approx.t_max, 1.0 / std::cos(a), 1e-12) << deg;
    }
    // Along the normal there is no U: equation 7.
    QuadricRay down;
    const QuadricDepth e = quadric_depth_exact(down, 0.5);
    EXPECT_FALSE(e.exact);
    EXPECT_EQ(e.depth, 0.5);
    EXPECT_EQ(glm::length(quadric_distance_direction(down.v)), 0.0);
}

// Every quadric shape (paraboloids both ways, saddles, cylinders, planes): where equation 6 answers, U is a unit
// vector perpendicular to the ray in the plane of the ray and the normal, pointing out; P + U s is on the quadric;
// s has the sign of the approximate depth (inside or outside the same for both); and no point of the quadric along
// U on that side is nearer. Where it does not, equation 7's value stands, and indeed no root of that sign exists.
TEST(QuadricDistance, ExactDistanceIsTheNearestPointAlongU) {
    const uint64_t seed = test::test_seed(20261207);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> coef(-3.0, 3.0), unit(0.0, 1.0);
    int exact = 0, fallback = 0;
    const int cases = test::sweep_cases(20000);
    for (int i = 0; i < cases; ++i) {
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i));
        QuadricRay r;
        r.v = random_ray(rng);
        const int shape = i % 5;  // 0: any, 1: both <= 0 (convex), 2: cylinder, 3: plane, 4: saddle
        r.alpha = shape == 3 ? 0.0 : shape == 1 ? -std::abs(coef(rng)) : coef(rng);
        r.beta = shape == 2 || shape == 3 ? 0.0 : shape == 1 ? -std::abs(coef(rng)) : coef(rng);
        if (shape == 4 && r.alpha * r.beta > 0) r.beta = -r.beta;
        const double t = 2.0 * unit(rng) / glm::length(r.v);
        const glm::dvec3 P = r.v * t;
        const double C = quadric_at(r, P);
        EXPECT_EQ(quadric_depth_approximate(r, t), C);
        const glm::dvec3 U = quadric_distance_direction(r.v);
        ASSERT_NEAR(glm::length(U), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(U, glm::normalize(r.v)), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(glm::cross(r.v, glm::dvec3(0, 0, 1)), U), 0.0, 1e-12 * glm::length(r.v));
        EXPECT_GT(U.z, 0.0);
        const QuadricDepth d = quadric_depth_exact(r, t);
        // The roots of A s^2 + B s + C again, in long double (the stable form: the small root of a nearly linear
        // equation loses its digits in the textbook one).
        const long double A = (long double)r.alpha * U.x * U.x + (long double)r.beta * U.y * U.y;
        const long double B = 2.0L * ((long double)r.alpha * P.x * U.x + (long double)r.beta * P.y * U.y) - U.z;
        const long double disc = B * B - 4.0L * A * C;
        long double s1 = NAN, s2 = NAN;
        if (A == 0) {
            if (B != 0) s1 = s2 = -C / B;
        } else if (disc >= 0) {
            const long double q = -0.5L * (B + std::copysign(std::sqrt(disc), B));
            s1 = q / A;
            s2 = q != 0 ? C / q : s1;
        }
        auto right_side = [&](long double s) { return std::isfinite(double(s)) && (C > 0 ? s > 0 : s < 0); };
        if (C == 0.0) {
            EXPECT_EQ(d.depth, 0.0);
            continue;
        }
        if (!d.exact) {
            ++fallback;
            EXPECT_EQ(d.depth, C);
            // No root on its side, but for roots so far that rounding decides (|s| > 1e6).
            for (long double s : {s1, s2})
                if (right_side(s)) {
                    EXPECT_GT(std::fabs(double(s)), 1e6) << double(s);
                }
            continue;
        }
        ++exact;
        const double s = d.depth;
        EXPECT_TRUE(C > 0 ? s > 0 : s < 0) << s << " " << C;
        const glm::dvec3 R = P + U * s;
        const double scale = 1.0 + std::abs(r.alpha) * glm::dot(R, R) + std::abs(r.beta) * glm::dot(R, R) +
                             std::abs(R.z) + std::abs(C);
        EXPECT_NEAR(quadric_at(r, R), 0.0, 1e-9 * scale) << s;
        long double nearest = 0;
        for (long double x : {s1, s2})
            if (right_side(x) && (nearest == 0 || std::fabs(x) < std::fabs(nearest))) nearest = x;
        EXPECT_NEAR(s, double(nearest), 1e-8 * (1.0 + std::abs(s))) << "the nearest root of its side";
    }
    std::printf("seed %llu: %d exact, %d by equation 7\n", (unsigned long long)seed, exact, fallback);
    // Both branches well exercised (measured: 84% exact over 20,000 cases, 85% over the first 300): half the cases
    // at least exact, and 5% by equation 7 (concave and saddle quadrics give negative discriminants); asked of 100
    // cases or more (RTM_SWEEP_CASES may cut the sweep shorter).
    if (cases >= 100) {
        EXPECT_GT(exact, cases / 2);
        EXPECT_GT(fallback, cases / 20);
    }
}

// The search range: on convex quadrics (both coefficients <= 0, the bulging base where silhouettes arise) the depth,
// either distance, stays in [0, 1] over [0, t_max] and is 1 at t_max (the bottom) or 0 (the ray leaves first).
// On any quadric the range is positive and the approximate one is equation 7's closed form.
TEST(QuadricDistance, SearchRangeEndsAtTheBottomOrWhereTheRayLeaves) {
    const uint64_t seed = test::test_seed(7122026);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> coef(0.0, 3.0);
    int leaves = 0, bottom = 0;
    const int cases = test::sweep_cases(5000);
    for (int i = 0; i < cases; ++i) {
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i));
        QuadricRay r;
        r.v = random_ray(rng);
        r.alpha = -coef(rng);
        r.beta = i % 3 == 0 ? 0.0 : -coef(rng);
        for (bool exact : {false, true}) {
            const QuadricSearchRange range = quadric_search_range(r, exact);
            ASSERT_TRUE(range.valid);
            ASSERT_GT(range.t_max, 0.0);
            auto depth = [&](double t) {
                return exact ? quadric_depth_exact(r, t).depth : quadric_depth_approximate(r, t);
            };
            const double end = depth(range.t_max);
            EXPECT_NEAR(end, range.leaves ? 0.0 : 1.0, 1e-9) << (exact ? "exact" : "approximate");
            for (int k = 1; k < 64; ++k) {
                const double d = depth(range.t_max * k / 64.0);
                EXPECT_GE(d, -1e-12);
                EXPECT_LE(d, 1.0 + 1e-9);
            }
            (range.leaves ? leaves : bottom) += 1;
        }
    }
    std::printf("seed %llu: %d ranges end where the ray leaves, %d at the bottom\n", (unsigned long long)seed, leaves,
                bottom);
    // Both ends well exercised (measured: 18% of the ranges at the bottom over 5,000 cases, 16% over the first 300;
    // each case gives two ranges): a tenth of the ranges at least each, of 100 cases or more.
    if (cases >= 100) {
        EXPECT_GT(leaves, cases / 5);
        EXPECT_GT(bottom, cases / 5);
    }
    // Equation 7's range on a concave quadric: the smaller root of k t^2 - c1 t + 1 = 0 (k < 0: one positive root).
    QuadricRay bowl;
    bowl.v = glm::dvec3(0.6, 0.0, -0.8);
    bowl.alpha = 2.0;
    const QuadricSearchRange r = quadric_search_range(bowl, false);
    ASSERT_TRUE(r.valid);
    EXPECT_FALSE(r.leaves);
    EXPECT_NEAR(quadric_depth_approximate(bowl, r.t_max), 1.0, 1e-12);
    // A ray going out is no range.
    QuadricRay out;
    out.v = glm::dvec3(0.0, 0.0, 1.0);
    EXPECT_FALSE(quadric_search_range(out, true).valid);
}

}  // namespace
}  // namespace rtm
