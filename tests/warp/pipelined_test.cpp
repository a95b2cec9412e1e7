#include <gtest/gtest.h>

#include <random>

#include "test_util.h"
#include "warp/prewarp.h"

namespace rtm {
namespace {

const PrewarpOptions kPipe{.method = Reconstruction::pipelined};

TEST(Pipelined, ZeroDisplacementIsTheIdentity) {
    std::mt19937_64 rng(test::test_seed(50001));
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int i = 0; i < 40; ++i) {
        const int w = 1 + int(rng() % 60), h = 1 + int(rng() % 60);
        const ReliefGeometry g = test::random_geometry(rng);
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, 0.0, [](int, int) { return 0.0; }, g);
        const glm::dvec3 eye = g.origin + g.a * (U(rng) * 200) + g.b * (U(rng) * 200) +
                               g.f() * (0.01 + std::abs(U(rng)));
        for (bool exact : {false, true}) {
            PrewarpOptions o = kPipe;
            o.exact = exact;
            const ImageRGBA8 a = prewarp(t, eye, o);
            const ImageRGBA8 b = prewarp(t, eye, {.exact = exact});
            ASSERT_EQ(a, b) << w << "x" << h;
        }
    }
}

// Without foldovers inside a row, no pixel of the intermediate image is overwritten, and both reconstructions
// connect the same pixels in the same order: they must agree exactly.
TEST(Pipelined, EqualsTwoPassWithoutFoldovers) {
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.01, 0};
    const int n = 80;
    const ReliefTexture t = test::make_test_relief(
        n, n, 0.0, 0.05,
        [&](int x, int r) {
            const double dx = (x - 40.0) / 25, dy = (r - 37.0) / 25;
            return 0.05 * std::exp(-(dx * dx + dy * dy));
        },
        g);
    for (const glm::dvec3 eye : {glm::dvec3{0.4, 0.4, 0.6}, glm::dvec3{-0.5, 0.2, 0.9}, glm::dvec3{0.31, 1.5, 0.5}}) {
        for (bool exact : {false, true}) {
            PrewarpOptions o = kPipe;
            o.exact = exact;
            EXPECT_EQ(prewarp(t, eye, o), prewarp(t, eye, {.exact = exact}));
        }
    }
}

TEST(Pipelined, OutputDoesNotDependOnThreadCount) {
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.01, 0};
    const ReliefTexture t = test::make_test_relief(
        120, 90, 0.0, 0.3,
        [](int x, int r) {
            return 0.3 * std::abs(std::sin(x * 0.3)) * std::abs(std::cos(r * 0.21));  // steep: folds over
        },
        g);
    for (bool exact : {false, true}) {
        PrewarpOptions o = kPipe;
        o.exact = exact;
        o.threads = 1;
        const ImageRGBA8 one = prewarp(t, {0.6, 0.45, 0.5}, o);
        o.threads = 2;
        EXPECT_EQ(one, prewarp(t, {0.6, 0.45, 0.5}, o));
    }
}

TEST(Pipelined, NoHoleAtTheSplits) {
    ReliefGeometry g;
    const int n = 64;
    const ReliefTexture t = test::make_test_relief(
        n, n, 2.0, 2.0, [](int, int) { return 2.0; }, g);
    for (double e : {20.5, 21.0, 21.2}) {
        const ImageRGBA8 out = prewarp(t, {e, e + 3, 40.0}, kPipe);
        for (const Rgba8& p : out.pixels) ASSERT_EQ(p.a, 255) << "epipole " << e;
    }
}

// PrewarpStats::row_pixels and column_samples, the work each reconstruction does.
PrewarpStats reference_stats(const ReliefTexture& t, const glm::dvec3& eye, Reconstruction m, bool exact) {
    PrewarpOptions o{.method = m, .exact = exact, .isa = Isa::generic};
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    return prewarp(t, compute_coefficients(t.geometry, eye), o, ws, out);
}

TEST(PipelinedWork, AFlatReliefIsOneSampleATexel) {
    // Zero displacement: every texel lands on its own pixel centre. With the epipole outside the relief, each is
    // written once in both passes of both reconstructions. With the epipole inside, every row also draws the span
    // across its split (warp_line_to), which writes the pixel of the texel after the split again: one pixel more a
    // row, which the intermediate image keeps once and the pipelined reconstruction rasterizes twice.
    const int w = 37, h = 23;
    const ReliefTexture t = test::make_test_relief(w, h, 0.0, 0.1, [](int, int) { return 0.0; });
    const ReliefGeometry& g = t.geometry;
    for (bool inside : {false, true}) {
        const glm::dvec3 eye = inside ? g.origin + g.a * 18.3 + g.b * 11.7 + g.f() * 0.3
                                      : g.origin - g.a * 20.0 - g.b * 15.0 + g.f() * 0.3;
        const int extra = inside ? h : 0;
        for (Reconstruction m : {Reconstruction::two_pass, Reconstruction::pipelined})
            for (bool exact : {false, true}) {
                SCOPED_TRACE(to_string(m) + (exact ? " exact" : " lut") + (inside ? ", epipole inside" : ""));
                const PrewarpStats s = reference_stats(t, eye, m, exact);
                EXPECT_EQ(s.row_pixels, w * h + extra);
                EXPECT_EQ(s.column_samples, m == Reconstruction::two_pass ? w * h : w * h + extra);
            }
    }
}

TEST(PipelinedWork, FoldoversCostThePipelinedReconstructionMore) {
    // Over random steep reliefs and views: both row warps produce the same pixels (the same row warp), the
    // two-pass column warp takes at most one sample per intermediate pixel, and the pipelined one every finite
    // pixel of the row warp, so at least the two-pass samples (each intermediate pixel is the last of the row
    // warp's pixels at its place). Exact counts: no tolerance.
    const uint64_t seed = test::test_seed(50007);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    int strictly_more = 0;
    for (int i = 0; i < 30; ++i) {
        const int w = 8 + int(rng() % 50), h = 8 + int(rng() % 50);
        const double amp = 0.02 + 0.3 * std::abs(U(rng)), fx = 0.1 + std::abs(U(rng)), fy = 0.1 + std::abs(U(rng));
        ReliefGeometry g;
        g.a = {0.01, 0, 0};
        g.b = {0, 0.01, 0};
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, amp, [&](int x, int r) { return amp * std::abs(std::sin(x * fx)) * std::abs(std::cos(r * fy)); },
            g);
        const glm::dvec3 eye{0.005 * w + U(rng), 0.005 * h + U(rng), 0.05 + std::abs(U(rng))};
        for (bool exact : {false, true}) {
            SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + (exact ? " exact" : " lut"));
            const PrewarpStats two = reference_stats(t, eye, Reconstruction::two_pass, exact);
            const PrewarpStats pipe = reference_stats(t, eye, Reconstruction::pipelined, exact);
            ASSERT_EQ(two.row_pixels, pipe.row_pixels);
            ASSERT_LE(pipe.column_samples, pipe.row_pixels);
            ASSERT_LE(two.column_samples, (long long)(w + two.extent.left + two.extent.right) * h);
            ASSERT_LE(two.column_samples, two.row_pixels);
            ASSERT_GE(pipe.column_samples, two.column_samples);
            ASSERT_GT(two.column_samples, 0);
            strictly_more += pipe.column_samples > two.column_samples;
        }
    }
    EXPECT_GT(strictly_more, 10);  // the sweep does fold over
}

TEST(PipelinedWork, TheFastKernelsDoNotCount) {
    const ReliefTexture t = test::make_test_relief(40, 30, 0.0, 0.2, [](int x, int) { return 0.2 * (x % 3); });
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    for (Reconstruction m : {Reconstruction::two_pass, Reconstruction::pipelined}) {
        const PrewarpStats s = prewarp(t, compute_coefficients(t.geometry, {0.3, 0.2, 0.5}),
                                       PrewarpOptions{.method = m}, ws, out);
        if (s.isa == Isa::generic) continue;  // no SIMD kernel for this reconstruction on this CPU
        EXPECT_EQ(s.row_pixels, 0);
        EXPECT_EQ(s.column_samples, 0);
    }
}

}  // namespace
}  // namespace rtm
