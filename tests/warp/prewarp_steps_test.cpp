// The pre-warp step by step: the image after the horizontal pass, and the final texture as prewarp() makes it.
#include <gtest/gtest.h>

#include <random>

#include "test_util.h"
#include "warp/prewarp_steps.h"

namespace rtm {
namespace {

TEST(PrewarpSteps, FinalTextureIsPrewarpsOutput) {
    // The steps run the reference kernels; every target matches them bit for bit, so the final texture is exactly
    // what prewarp() gives on the default target.
    const uint64_t seed = test::test_seed(52001);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int i = 0; i < 20; ++i) {
        const int w = 2 + int(rng() % 60), h = 2 + int(rng() % 60);
        const ReliefGeometry g = test::random_geometry(rng);
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, 0.5, [&](int x, int r) { return 0.25 + 0.25 * std::sin(0.3 * x + 0.2 * r); }, g);
        const glm::dvec3 eye = g.origin + g.a * (U(rng) * 100) + g.b * (U(rng) * 100) +
                               g.f() * (2.0 + std::abs(U(rng)));
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        for (bool exact : {false, true}) {
            const PrewarpSteps s = prewarp_steps(t, k, {.exact = exact});
            ASSERT_EQ(s.prewarped, prewarp(t, eye, {.exact = exact})) << w << "x" << h << " exact=" << exact;
            ASSERT_EQ(s.horizontal.width, s.prewarped.width);
            ASSERT_EQ(s.horizontal.height, h);
        }
    }
}

TEST(PrewarpSteps, ZeroDisplacementLeavesBothPassesTheSource) {
    const ReliefTexture t = test::make_test_relief(37, 23, 0.0, 0.0, [](int, int) { return 0.0; });
    const PrewarpSteps s = prewarp_steps(t, compute_coefficients(t.geometry, {10, 5, 30}), {});
    ImageRGBA8 src(t.width, t.height);
    for (int r = 0; r < t.height; ++r)
        for (int x = 0; x < t.width; ++x) src.at(x, r) = {t.texel(x, r).r, t.texel(x, r).g, t.texel(x, r).b, 255};
    EXPECT_EQ(s.horizontal, src);
    EXPECT_EQ(s.prewarped, src);
}

TEST(PrewarpSteps, HorizontalPassKeepsEveryTexelOnItsRow) {
    // Each row has one colour of its own: whatever the displacement, the horizontal pass only moves texels along
    // their row (and interpolates between neighbours of that row), so every pixel it writes has its row's colour.
    // The vertical pass then moves them across rows: the final texture has pixels off their source row.
    const int w = 48, h = 40;
    ImageRGBA8 c(w, h);
    ImageF d(w, h);
    auto row_colour = [](int r) { return Rgba8{uint8_t(5 * r), uint8_t(255 - 5 * r), uint8_t(r * 37), 255}; };
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) {
            c.at(x, r) = row_colour(r);
            d.at(x, r) = float(0.5 + 0.5 * std::sin(0.4 * x) * std::cos(0.3 * r));
        }
    ReliefGeometry g;
    const ReliefTexture t = make_relief(c, d, 0.0, 8.0, g);
    const PrewarpCoefficients k = compute_coefficients(g, {-20.0, 70.0, 40.0});  // oblique: the epipole is outside
    for (bool exact : {false, true}) {
        const PrewarpSteps s = prewarp_steps(t, k, {.exact = exact});
        int written = 0, moved_rows = 0;
        for (int r = 0; r < h; ++r)
            for (int x = 0; x < w; ++x) {
                const Rgba8 p = s.horizontal.at(x, r);
                if (p.a == 0) continue;
                ++written;
                ASSERT_EQ(p, row_colour(r)) << "pixel " << x << "," << r << " exact=" << exact;
            }
        for (int r = 0; r < h; ++r)
            for (int x = 0; x < w; ++x)
                moved_rows += s.prewarped.at(x, r).a != 0 && s.prewarped.at(x, r) != row_colour(r);
        EXPECT_GT(written, w * h / 2);
        EXPECT_GT(moved_rows, 0);
    }
}

TEST(PrewarpSteps, ColumnsOfTheHorizontalPassKeepTheirColourInTheVerticalPass) {
    // Colours depend on the column only and the displacement is constant: every row warps alike, so each column
    // of the intermediate image has one colour, and the vertical pass (which only moves and interpolates within a
    // column) keeps it: here the two images are equal.
    const int w = 32, h = 32;
    ImageRGBA8 c(w, h);
    ImageF d(w, h, 1.0f);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) c.at(x, r) = {uint8_t(8 * x), uint8_t(200 - 3 * x), 77, 255};
    ReliefGeometry g;
    const ReliefTexture t = make_relief(c, d, 0.0, 4.0, g);
    const PrewarpSteps s = prewarp_steps(t, compute_coefficients(g, {10.0, 12.0, 30.0}), {});
    for (int x = 0; x < s.horizontal.width; ++x) {
        for (int r = 1; r < h; ++r) ASSERT_EQ(s.horizontal.at(x, r), s.horizontal.at(x, 0)) << x << "," << r;
        for (int r = 0; r < s.prewarped.height; ++r)
            if (s.prewarped.at(x, r).a != 0) {
                ASSERT_EQ(s.prewarped.at(x, r), s.horizontal.at(x, 0)) << x << "," << r;
            }
    }
    EXPECT_NE(s.horizontal, c);  // the horizontal pass moved columns (the scaling about the epipole)
}

TEST(PrewarpSteps, EyeInThePlaneGivesEmptyImagesOfTheRightSize) {
    const ReliefTexture t = test::make_test_relief(9, 7, 0.0, 1.0, [](int x, int) { return 0.1 * x; });
    const PrewarpSteps s = prewarp_steps(t, compute_coefficients(t.geometry, {3, 3, 0}), {});
    EXPECT_EQ(s.horizontal, ImageRGBA8(9, 7));
    EXPECT_EQ(s.prewarped.width, 9);
    EXPECT_EQ(s.prewarped.height, 7);
}

}  // namespace
}  // namespace rtm
