#include "warp/upsample.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <random>

#include "test_util.h"

namespace rtm {
namespace {

TEST(Upsample, FactorOneIsACopy) {
    const ReliefTexture t = test::make_test_relief(9, 7, 0.0, 1.0, [](int x, int r) { return (x * r) / 63.0; });
    const ReliefTexture o = upsample(t, 1);
    EXPECT_EQ(o.width, 9);
    EXPECT_EQ(o.texels, t.texels);
    EXPECT_EQ(o.displacement, t.displacement);
}

TEST(Upsample, RefusesABadFactorNamingIt) {
    const ReliefTexture t = test::make_test_relief(4, 4, 0.0, 1.0, [](int, int) { return 0.5; });
    try {
        upsample(t, 0);
        FAIL() << "factor 0 accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("found 0"), std::string::npos) << e.what();
    }
    const ReliefTexture big = test::make_test_relief(4096, 2, 0.0, 1.0, [](int, int) { return 0.5; });
    EXPECT_THROW(upsample(big, 256), std::invalid_argument);  // 1048576 x 512 texels: 2^29
}

// The fine grid covers the same quad: the same origin and the same far corner (a / factor is exact for powers of
// two; within rounding for 3).
TEST(Upsample, CoversTheSameQuad) {
    std::mt19937_64 rng(test::test_seed(11));
    const ReliefGeometry g = test::random_geometry(rng);
    const ReliefTexture t = test::make_test_relief(
        13, 6, 0.0, 1.0, [](int, int) { return 0.25; }, g);
    for (int factor : {2, 3, 4}) {
        const ReliefTexture o = upsample(t, factor);
        EXPECT_EQ(o.width, 13 * factor);
        EXPECT_EQ(o.height, 6 * factor);
        EXPECT_EQ(o.geometry.origin, g.origin);
        const glm::dvec3 far0 = g.origin + g.a * 13.0 + g.b * 6.0;
        const glm::dvec3 far1 = o.geometry.origin + o.geometry.a * double(o.width) + o.geometry.b * double(o.height);
        EXPECT_LT(glm::length(far1 - far0), 1e-12 * (1 + glm::length(far0))) << "factor " << factor;
    }
}

// Bilinear interpolation reproduces a displacement linear in u and v: every fine texel whose centre lies between
// source texel centres has the plane's value at its own centre (float rounding: the exact displacement is stored
// as float), and the colour of a constant-colour relief stays that colour.
TEST(Upsample, PlanesStayPlanes) {
    const uint64_t seed = test::test_seed(2026);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> c(-0.05, 0.05);
    for (int trial = 0; trial < 20; ++trial) {
        const double c0 = 0.5, cu = c(rng), cv = c(rng);
        const int w = 5 + int(rng() % 20), h = 5 + int(rng() % 20);
        // Displacement at source texel centre (u, v) = (x + 0.5, h - 1 - row + 0.5).
        const auto plane = [&](double u, double v) { return c0 + cu * u + cv * v; };
        ReliefTexture t = test::make_test_relief(w, h, -2.0, 3.0,
                                                 [&](int x, int r) { return plane(x + 0.5, h - 1 - r + 0.5); });
        for (ReliefTexel& tx : t.texels.edit()) tx.r = tx.g = tx.b = 77;
        const int factor = trial % 2 ? 2 : 4;
        const ReliefTexture o = upsample(t, factor);
        for (int r = 0; r < o.height; ++r)
            for (int x = 0; x < o.width; ++x) {
                const double u = (x + 0.5) / factor, v = (o.height - 1 - r + 0.5) / factor;  // source texel units
                ASSERT_EQ(o.texel(x, r).r, 77);
                if (u < 0.5 || u > w - 0.5 || v < 0.5 || v > h - 0.5) continue;  // clamped at the border
                ASSERT_NEAR(o.displ(x, r), plane(u, v), 1e-6) << "fine texel " << x << "," << r;
                ASSERT_EQ(o.texel(x, r).q, t.quant.encode(o.displ(x, r)));
            }
    }
}

// Each source texel is the nearest of exactly factor x factor fine texels, so the fine grid has factor^2 times the
// source's empty texels, each under an empty source texel.
TEST(Upsample, EmptyTexelsStayEmptyAndDoNotBleed) {
    ReliefTexture t = test::make_test_relief(8, 8, 0.0, 1.0, [](int x, int) { return x / 8.0; });
    int n_empty = 0;
    for (int r = 0; r < 8; ++r)
        for (int x = 0; x < 8; ++x)
            if ((x - 4) * (x - 4) + (r - 3) * (r - 3) <= 4) {
                t.texels.edit()[size_t(r) * 8 + size_t(x)].q = kEmptyIndex;
                ++n_empty;
            }
    for (int factor : {2, 4}) {
        const ReliefTexture o = upsample(t, factor);
        int fine_empty = 0;
        for (int r = 0; r < o.height; ++r)
            for (int x = 0; x < o.width; ++x) {
                const bool e = o.empty_at(x, r);
                fine_empty += e;
                ASSERT_EQ(e, t.empty_at(x / factor, r / factor)) << x << "," << r;
                // A non-empty fine texel is a mix of non-empty source texels only: within their displacement range.
                if (!e) {
                    ASSERT_TRUE(o.displ(x, r) >= 0.0f && o.displ(x, r) <= 7 / 8.0f + 1e-6f);
                }
            }
        EXPECT_EQ(fine_empty, n_empty * factor * factor);
    }
}

// No slope across a surface discontinuity: fine texels take one side's displacement or the other's, and the fine
// grid is marked along the step with the source's threshold.
TEST(Upsample, NoSlopeAcrossADiscontinuity) {
    ReliefTexture t = test::make_test_relief(10, 6, 0.0, 1.0, [](int x, int) { return x < 5 ? 0.1 : 0.9; });
    mark_discontinuities(t, 0.3);
    const ReliefTexture o = upsample(t, 4);
    EXPECT_EQ(o.discontinuity_threshold, 0.3);
    ASSERT_EQ(o.breaks.size(), o.texels.size());
    for (int r = 0; r < o.height; ++r) {
        for (int x = 0; x < o.width; ++x) {
            const float d = o.displ(x, r);
            ASSERT_TRUE(d == 0.1f || d == 0.9f) << x << "," << r << ": " << d;
        }
        EXPECT_TRUE(o.breaks[size_t(r) * size_t(o.width) + 19] & kBreakRight) << "row " << r;
    }
    // Without marks the same step is interpolated (a ramp of fine texels between the two levels).
    ReliefTexture u = t;
    mark_discontinuities(u, 0.0);
    const ReliefTexture ou = upsample(u, 4);
    EXPECT_GT(ou.displ(19, 0), 0.1f);
    EXPECT_LT(ou.displ(19, 0), 0.9f);
}

}  // namespace
}  // namespace rtm
