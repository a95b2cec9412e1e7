#include "warp/tables.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cfloat>
#include <random>

#include "test_util.h"

namespace rtm {
namespace {

TEST(Quantizer, RoundTripWithinHalfAStep) {
    const Quantizer q = Quantizer::from_range(-0.3, 1.7);
    EXPECT_DOUBLE_EQ(q.decode(0), -0.3);
    EXPECT_EQ(q.decode(254), 1.7);  // top level exact
    for (int i = 0; i <= 1000; ++i) {
        const double d = -0.3 + 2.0 * i / 1000;
        const uint8_t e = q.encode(d);
        ASSERT_LE(e, 254);
        ASSERT_LE(std::abs(q.decode(e) - d), q.qs / 2 * (1 + 1e-12)) << q.to_string() << " d=" << d;
    }
    EXPECT_EQ(q.encode(-5), 0);
    EXPECT_EQ(q.encode(5), 254);
}

TEST(Quantizer, EqualMinAndMaxIsOneLevel) {
    const Quantizer q = Quantizer::from_range(0.25, 0.25);
    EXPECT_EQ(q.encode(0.25), 0);
    EXPECT_EQ(q.decode(0), 0.25);
}

TEST(PrewarpTables, MatchTheFormulaAndMarkInvalidLevels) {
    ReliefGeometry g;
    const PrewarpCoefficients k = compute_coefficients(g, {10, 20, 0.5});  // eye 0.5 above the plane
    const Quantizer q = Quantizer::from_range(0.0, 1.0);                   // levels above 0.5 cannot be warped
    const PrewarpTables t = PrewarpTables::build(k, q);
    for (int i = 0; i < 255; ++i) {
        const double d = q.decode(uint8_t(i));
        const bool ok = 1 + k.k3 * d > 0;
        ASSERT_EQ(bool(t.valid[i]), ok) << i;
        if (!ok) continue;
        EXPECT_FLOAT_EQ(t.k1d[i], float(k.k1 * d));
        EXPECT_FLOAT_EQ(t.k2d[i], float(k.k2 * d));
        EXPECT_FLOAT_EQ(t.rcp[i], float(1 / (1 + k.k3 * d)));
    }
    EXPECT_FALSE(t.valid[255]);
    EXPECT_TRUE(t.still[0]);
    EXPECT_FALSE(t.still[1]);
}

// The lookup-table coordinate differs from the exact one by at most the quantization bound:
// u_i(d) = e_u + (u_s - e_u) / (1 + k3*d) is monotonic in d, and the quantized d' is within qs/2 of d, so the
// exact coordinate of d' lies between u_i(d - qs/2) and u_i(d + qs/2). The table path then adds float rounding:
// K1, R and the two operations each round once (relative 2^-24), so the float result is within
// 4 * FLT_EPSILON * (|u_s| + |K1|) * |R| of the exact value at d'.
TEST(PrewarpTables, LookupPathWithinTheQuantizationBound) {
    const uint64_t seed = test::test_seed(30001);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int view = 0; view < 500; ++view) {
        const ReliefGeometry g = test::random_geometry(rng);
        const double size = 512 * glm::length(g.a);
        const glm::dvec3 eye = g.origin + g.a * (U(rng) * 600 - 50) + g.b * (U(rng) * 600 - 50) +
                               g.f() * (size * std::pow(10.0, U(rng) * 3 - 1));
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        const double lo = -0.1 * size * U(rng), hi = 0.2 * size * U(rng);
        const Quantizer q = Quantizer::from_range(lo, hi);
        const PrewarpTables t = PrewarpTables::build(k, q);
        for (int s = 0; s < 20; ++s) {
            const double us = U(rng) * 512 + 0.5, vs = U(rng) * 512 + 0.5;
            const double d = lo + (hi - lo) * U(rng);
            const uint8_t qi = q.encode(d);
            if (!t.valid[qi]) continue;
            const double dlo = std::max(lo, d - q.qs / 2), dhi = std::min(hi, d + q.qs / 2);
            double u1, v1, u2, v2;
            if (!k.warp(us, vs, dlo, u1, v1) || !k.warp(us, vs, dhi, u2, v2)) continue;
            const float ul = (float(us) + t.k1d[qi]) * t.rcp[qi];
            const float vl = (float(vs) + t.k2d[qi]) * t.rcp[qi];
            const double epsu = 4 * FLT_EPSILON * (std::abs(us) + std::abs(t.k1d[qi])) * t.rcp[qi];
            const double epsv = 4 * FLT_EPSILON * (std::abs(vs) + std::abs(t.k2d[qi])) * t.rcp[qi];
            ASSERT_GE(ul, std::min(u1, u2) - epsu) << k.to_string() << " d=" << d;
            ASSERT_LE(ul, std::max(u1, u2) + epsu) << k.to_string() << " d=" << d;
            ASSERT_GE(vl, std::min(v1, v2) - epsv) << k.to_string() << " d=" << d;
            ASSERT_LE(vl, std::max(v1, v2) + epsv) << k.to_string() << " d=" << d;
        }
    }
}

}  // namespace
}  // namespace rtm
