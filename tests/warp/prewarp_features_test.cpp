// Discontinuities (section 4.1.1), depth-correction output (section 4.2) and samples kept beyond the quad
// (section 4).
#include <gtest/gtest.h>

#include <random>

#include "test_util.h"
#include "warp/prewarp.h"

namespace rtm {
namespace {

// Left half at d = 0 (blue), right half at d = 0.5 (red). Seen from the left, the raised half moves right,
// away from the epipole, and opens a gap at the step.
ReliefTexture step_relief() {
    ReliefGeometry g;
    const int w = 40, h = 20;
    ImageRGBA8 c(w, h);
    ImageF d(w, h);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) {
            const bool up = x >= 20;
            c.at(x, r) = up ? Rgba8{255, 0, 0, 255} : Rgba8{0, 0, 255, 255};
            d.at(x, r) = up ? 0.5f : 0.0f;
        }
    return make_relief(c, d, 0.0, 0.5, g);
}

int mixed_pixels(const ImageRGBA8& img) {
    int n = 0;
    for (const Rgba8& p : img.pixels)
        if (p.a && p.r > 0 && p.b > 0) ++n;
    return n;
}

TEST(Discontinuities, NoSkinAcrossMarkedEdges) {
    ReliefTexture t = step_relief();
    const glm::dvec3 eye{5.0, 10.0, 2.0};
    for (Reconstruction m : {Reconstruction::two_pass, Reconstruction::pipelined}) {
        for (bool exact : {false, true}) {
            const PrewarpOptions o{.method = m, .exact = exact};
            mark_discontinuities(t, 0.0);
            const ImageRGBA8 skin = prewarp(t, eye, o);
            EXPECT_GT(mixed_pixels(skin), 20) << to_string(m);  // the gap is bridged by interpolated colours
            mark_discontinuities(t, 0.1);
            const ImageRGBA8 cut = prewarp(t, eye, o);
            EXPECT_EQ(mixed_pixels(cut), 0) << to_string(m);
            int empty = 0;
            for (const Rgba8& p : cut.pixels) empty += p.a == 0;
            EXPECT_GT(empty, 20) << to_string(m);  // the unsampled wall of the step is a hole
        }
    }
}

TEST(Discontinuities, MarksFollowTheThreshold) {
    ReliefTexture t = step_relief();
    mark_discontinuities(t, 0.1);
    ASSERT_EQ(t.breaks.size(), t.texels.size());
    EXPECT_EQ(t.breaks[19] & kBreakRight, kBreakRight);
    EXPECT_EQ(t.breaks[18] & kBreakRight, 0);
    EXPECT_EQ(t.breaks[40 + 5] & kBreakUp, 0);
    mark_discontinuities(t, 0.6);  // the step is below the threshold
    for (uint8_t b : t.breaks) EXPECT_EQ(b, 0);
}

TEST(DepthOutput, CarriesTheDisplacementSeenAtEachPixel) {
    ReliefGeometry g;
    const int n = 32;
    const double d = 0.2;
    const ReliefTexture t = test::make_test_relief(
        n, n, 0.0, 1.0, [&](int, int) { return d; }, g);
    const PrewarpCoefficients k = compute_coefficients(g, {10, 12, 5});
    for (Reconstruction m : {Reconstruction::two_pass, Reconstruction::pipelined}) {
        PrewarpWorkspace ws;
        ImageRGBA8 out;
        Image2D<uint8_t> displ;
        prewarp(t, k, {.method = m}, ws, out, &displ);
        ASSERT_EQ(displ.width, n);
        for (size_t i = 0; i < out.pixels.size(); ++i) {
            if (out.pixels[i].a == 0)
                ASSERT_EQ(displ.pixels[i], kEmptyIndex);
            else
                ASSERT_EQ(displ.pixels[i], t.quant.encode(d));
        }
    }
}

TEST(Outliers, ExtentHoldsEverySample) {
    const uint64_t seed = test::test_seed(60001);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        const ReliefGeometry g = test::random_geometry(rng);
        const int w = 8 + int(rng() % 40), h = 8 + int(rng() % 40);
        const double top = glm::length(g.a) * 20 * U(rng);
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, top, [&](int x, int r) { return top * ((x * 7 + r * 3) % 11) / 10.0; }, g);
        const glm::dvec3 eye = g.origin + g.a * (U(rng) * 3 * w - w) + g.b * (U(rng) * 3 * h - h) +
                               g.f() * (top * (1.2 + 5 * U(rng)));
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        const PrewarpExtent e = outlier_extent(t, k, 1 << 20);
        for (int r = 0; r < h; ++r)
            for (int x = 0; x < w; ++x) {
                double ui, vi;
                if (!k.warp(x + 0.5, (h - 1 - r) + 0.5, t.displ(x, r), ui, vi)) continue;
                ASSERT_GE(ui, -e.left - 1e-9);
                ASSERT_LE(ui, w + e.right + 1e-9);
                ASSERT_GE(vi, -e.bottom - 1e-9);
                ASSERT_LE(vi, h + e.top + 1e-9);
            }
    }
}

TEST(Outliers, TallDetailAtTheBorderIsKeptInTheMargin) {
    ReliefGeometry g;
    const int n = 32;
    // A tall wall along the left border, seen from the right: it leans out of the quad to the left.
    const ReliefTexture t = test::make_test_relief(
        n, n, 0.0, 4.0, [](int x, int) { return x < 4 ? 4.0 : 0.0; }, g);
    const glm::dvec3 eye{40.0, 16.0, 10.0};
    const ImageRGBA8 dropped = prewarp(t, eye, {});
    PrewarpWorkspace ws;
    ImageRGBA8 kept;
    const PrewarpStats st = prewarp(t, compute_coefficients(g, eye), {.keep_outliers = true}, ws, kept);
    EXPECT_GT(st.extent.left, 0);
    EXPECT_EQ(st.extent.right, 0);
    EXPECT_EQ(kept.width, n + st.extent.left);
    int outside = 0;
    for (int r = 0; r < kept.height; ++r)
        for (int x = 0; x < st.extent.left; ++x) outside += kept.at(x, r).a != 0;
    EXPECT_GT(outside, n);
    EXPECT_EQ(dropped.width, n);
}

TEST(Outliers, ZeroDisplacementNeedsNoMargin) {
    ReliefGeometry g;
    const ReliefTexture t = test::make_test_relief(
        16, 16, 0.0, 0.0, [](int, int) { return 0.0; }, g);
    PrewarpWorkspace ws;
    ImageRGBA8 a;
    const PrewarpStats st = prewarp(t, compute_coefficients(g, {3, 30, 2}), {.keep_outliers = true}, ws, a);
    EXPECT_EQ(st.extent, PrewarpExtent{});
    EXPECT_EQ(a, prewarp(t, glm::dvec3{3, 30, 2}));
}

}  // namespace
}  // namespace rtm
