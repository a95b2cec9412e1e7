// The supersampled truth of a pre-warped texture (truth/prewarp_truth.h), and what the coverage filter gains
// against it where the pre-warp compresses texels (the aliasing point sampling cannot avoid).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "truth/prewarp_truth.h"
#include "warp/prewarp.h"

namespace rtm {
namespace {

ReliefTexture make(int w, int h, auto colour, auto displ, double lo, double hi) {
    ImageRGBA8 c(w, h);
    ImageF d(w, h);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) {
            c.at(x, r) = colour(x, r);
            d.at(x, r) = float(displ(x, r));
        }
    return make_relief(c, d, lo, hi, ReliefGeometry{});
}

// A flat relief seen from anywhere in front: its truth is the colour texture box-filtered over each pixel
// (alpha 255 inside, the outer half texel ring uncovered since the surface ends at the texel centres).
TEST(PrewarpTruth, FlatReliefIsItsOwnTexture) {
    ReliefTexture t = make(
        16, 12,
        [](int x, int) {
            return Rgba8{uint8_t(x * 16), 100, 7, 255};
        },
        [](int, int) { return 0.0; }, -1, 1);
    PrewarpTruthOptions o;
    o.samples = 4;
    const ImageRGBA8 truth = prewarp_truth(t, {3.0, -5.0, 20.0}, PrewarpExtent{}, o);
    ASSERT_EQ(truth.width, 16);
    ASSERT_EQ(truth.height, 12);
    // Colour ramps linearly in x, so the box average over pixel x is the value at its centre: 16 x.
    for (int r = 1; r < 11; ++r)
        for (int x = 1; x < 15; ++x) {
            EXPECT_EQ(truth.at(x, r).a, 255);
            EXPECT_NEAR(truth.at(x, r).r, x * 16, 1) << x;
            EXPECT_EQ(truth.at(x, r).g, 100);
        }
    EXPECT_EQ(truth.at(0, 5).a, 128);  // 2 of 4 sample columns are beyond the first texel centre
}

// Texels compressed 2.4:1 to 8:1 by the pre-warp: a steep slope facing away from a viewer at the side. With a
// one-texel black/white stripe pattern, the truth is nearly uniform grey; point sampling picks one texel per
// pixel and shows stripes (aliasing); the coverage filter averages them. The gain asserted (at least 3x lower
// colour error) is far inside what the measurement shows (docs/ACCURACY.md), so the test does not depend on
// rounding details.
TEST(PrewarpTruth, CoverageFilterRemovesAliasingUnderCompression) {
    const int n = 48;
    ReliefTexture t = make(
        n, n,
        [](int x, int) {
            uint8_t v = x % 2 ? 255 : 0;
            return Rgba8{v, v, v, 255};
        },
        [&](int x, int) { return 1.2 * (n - x); }, 0.0, 1.2 * n + 1);
    const glm::dvec3 eye{-40.0, n * 0.5, 120.0};
    const PrewarpCoefficients k = compute_coefficients(t.geometry, eye);
    // Precondition: at the middle of the relief, neighbouring texels land less than half a pixel apart.
    double u0, v0, u1, v1;
    ASSERT_TRUE(k.warp(n / 2 + 0.5, n / 2 + 0.5, t.displ(n / 2, n / 2), u0, v0));
    ASSERT_TRUE(k.warp(n / 2 + 1.5, n / 2 + 0.5, t.displ(n / 2 + 1, n / 2), u1, v1));
    ASSERT_LT(std::abs(u1 - u0), 0.45);
    PrewarpTruthOptions to;
    to.samples = 8;
    const ImageRGBA8 truth = prewarp_truth(t, eye, PrewarpExtent{}, to);
    PrewarpOptions o;
    o.exact = true;
    const ImageRGBA8 point = prewarp(t, eye, o);
    o.filter = Filter::coverage;
    const ImageRGBA8 cov = prewarp(t, eye, o);
    const PrewarpError ep = prewarp_error(point, truth, {}), ec = prewarp_error(cov, truth, {});
    ASSERT_GT(ep.pixels, 100);
    ASSERT_GT(ec.pixels, 100);
    EXPECT_LT(ec.color_rmse * 3, ep.color_rmse) << "point " << ep.color_rmse << " coverage " << ec.color_rmse;
    std::printf("colour RMSE against the truth: point %.2f, coverage %.2f; coverage error %.4f, %.4f\n", ep.color_rmse,
                ec.color_rmse, ep.coverage_mae, ec.coverage_mae);
    EXPECT_LE(ec.coverage_mae, ep.coverage_mae + 0.01);
}

TEST(PrewarpTruth, BadArgumentsNameTheValue) {
    ReliefTexture t = make(
        4, 4,
        [](int, int) {
            return Rgba8{1, 2, 3, 255};
        },
        [](int, int) { return 0.0; }, 0, 1);
    PrewarpTruthOptions o;
    o.samples = 0;
    try {
        prewarp_truth(t, {0, 0, 5}, {}, o);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("found 0"), std::string::npos) << e.what();
    }
    EXPECT_THROW(prewarp_error(ImageRGBA8(3, 3), ImageRGBA8(4, 3), {}), std::invalid_argument);
}

}  // namespace
}  // namespace rtm
