// The coverage-weighted (Fant-style) filter of the pre-warp, PrewarpOptions::filter = Filter::coverage
// (warp/coverage_line.h). What it must do, exactly where the maths is exact.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_util.h"
#include "warp/coverage_line.h"
#include "warp/line_warp.h"
#include "warp/prewarp.h"

namespace rtm {
namespace {

using Cell1 = CoverageCell<double, 0>;

std::vector<Cell1> run_line(const std::vector<double>& pos, const std::vector<Rgba8>& col, int split, int n_out,
                            std::vector<uint8_t> valid = {}) {
    if (valid.empty()) valid.assign(pos.size(), 1);
    std::vector<Cell1> cells(size_t(n_out), Cell1{});
    const CoverageLineInput<double, 0> in{int(pos.size()), pos.data(), col.data(), nullptr, valid.data()};
    coverage_warp_line(in, split, cells.data(), n_out, AlwaysConnected{});
    return cells;
}

// A linear span is integrated exactly: a uniform stretch by 3 of two samples, colour 0 -> 240 over [1.5, 4.5].
TEST(CoverageLine, IntegratesTheLinearSpan) {
    const auto cells = run_line({1.5, 4.5}, {{0, 0, 0, 255}, {240, 240, 240, 255}}, 2, 6);
    // Pixel 1 covers [1.5, 2): alpha 1/2, mean t = 1/12; pixel 2: [2, 3), t = 1/3; pixel 4: [4, 4.5), t = 11/12.
    EXPECT_DOUBLE_EQ(cells[0].cov, 0.0);
    EXPECT_DOUBLE_EQ(cells[1].cov, 0.5);
    EXPECT_NEAR(cells[1].r / cells[1].cov, 240.0 / 12, 1e-9);
    EXPECT_DOUBLE_EQ(cells[2].cov, 1.0);
    EXPECT_NEAR(cells[2].r, 240.0 / 3, 1e-9);
    EXPECT_NEAR(cells[3].r, 240.0 * 2 / 3, 1e-9);
    EXPECT_DOUBLE_EQ(cells[4].cov, 0.5);
    EXPECT_NEAR(cells[4].r / cells[4].cov, 240.0 * 11 / 12, 1e-9);
    EXPECT_DOUBLE_EQ(cells[5].cov, 0.0);
}

// Compression: 8 samples in one pixel average instead of picking one (what point sampling aliases).
TEST(CoverageLine, AveragesCompressedSamples) {
    std::vector<double> pos;
    std::vector<Rgba8> col;
    for (int k = 0; k <= 8; ++k) {
        pos.push_back(1.0 + k / 8.0);
        const uint8_t v = k % 2 ? 255 : 0;
        col.push_back({v, v, v, 255});
    }
    const auto cells = run_line(pos, col, 9, 3);
    EXPECT_NEAR(cells[1].cov, 1.0, 1e-12);
    EXPECT_NEAR(cells[1].r / cells[1].cov, 127.5, 1e-9);  // eight spans 0<->255, each averaging 127.5
}

// Occlusion: a later piece hides the earlier one where they overlap, and only there.
TEST(CoverageLine, LaterPiecesHideOnlyWhereTheyOverlap) {
    // Left part: red over [0.5, 1.5] (pixel 0 gets [0.5, 1), pixel 1 [1, 1.5)); right part (drawn later, towards
    // the split): blue over [1.25, 2.25] folding back over pixel 1.
    const std::vector<double> pos{0.5, 1.5, 2.25, 1.25};
    const std::vector<Rgba8> col{{255, 0, 0, 255}, {255, 0, 0, 255}, {0, 0, 255, 255}, {0, 0, 255, 255}};
    // Samples 0, 1 form the left part (split = 2), samples 3, 2 the right part; the seam joins 1 and 2, but
    // they are made not connected so the parts stay apart.
    std::vector<uint8_t> valid(4, 1);
    std::vector<Cell1> cells(3, Cell1{});
    const CoverageLineInput<double, 0> in{4, pos.data(), col.data(), nullptr, valid.data()};
    coverage_warp_line(in, 2, cells.data(), 3,
                       [](int a, int b) { return !(std::min(a, b) == 1 && std::max(a, b) == 2); });
    // Pixel 1: red on [1, 1.5) = 16 positions, blue on [1.25, 2) = 24 positions, 8 of red's hidden.
    EXPECT_NEAR(cells[1].cov, 0.25 + 0.75, 1e-12);
    EXPECT_NEAR(cells[1].r, 0.25 * 255, 1e-9);
    EXPECT_NEAR(cells[1].b, 0.75 * 255, 1e-9);
}

// Zero displacement: every texel stays on its centre, so each output pixel is the box filter of the linear
// interpolant, (c[k-1] + 6 c[k] + c[k+1]) / 8 along rows, then along columns. Both passes round to 8 bits, so
// the result is the separable filter applied with rounding after each pass (recomputed here exactly that way;
// the only slack is a float sum landing on the other side of a .5 rounding boundary: at most 1 level).
TEST(CoverageFilter, ZeroDisplacementIsTheBoxFilteredInterpolant) {
    const uint64_t seed = test::test_seed(4242);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    for (int trial = 0; trial < 20; ++trial) {
        const int w = 5 + int(rng() % 40), h = 5 + int(rng() % 40);
        ReliefTexture t = test::make_test_relief(w, h, -1.0, 1.0, [](int, int) { return 0.0; });
        std::uniform_real_distribution<double> U(-50, 50);
        const glm::dvec3 eye{U(rng), U(rng), 1.0 + std::abs(U(rng))};
        PrewarpOptions o;
        o.filter = Filter::coverage;
        o.exact = trial % 2;
        const ImageRGBA8 out = prewarp(t, eye, o);
        ASSERT_EQ(out.width, w);
        ASSERT_EQ(out.height, h);
        auto filt = [](double a, double b, double c) { return (a + 6 * b + c) / 8; };
        ImageF hr(w, h), hg(w, h), hb(w, h);
        for (int r = 0; r < h; ++r)
            for (int x = 1; x + 1 < w; ++x) {
                const ReliefTexel a = t.texel(x - 1, r), b = t.texel(x, r), c = t.texel(x + 1, r);
                hr.at(x, r) = float(std::floor(filt(a.r, b.r, c.r) + 0.5));
                hg.at(x, r) = float(std::floor(filt(a.g, b.g, c.g) + 0.5));
                hb.at(x, r) = float(std::floor(filt(a.b, b.b, c.b) + 0.5));
            }
        for (int r = 1; r + 1 < h; ++r)
            for (int x = 1; x + 1 < w; ++x) {
                const Rgba8 p = out.at(x, r);
                ASSERT_EQ(p.a, 255) << x << "," << r;
                const double er = std::floor(filt(hr.at(x, r - 1), hr.at(x, r), hr.at(x, r + 1)) + 0.5);
                const double eg = std::floor(filt(hg.at(x, r - 1), hg.at(x, r), hg.at(x, r + 1)) + 0.5);
                const double eb = std::floor(filt(hb.at(x, r - 1), hb.at(x, r), hb.at(x, r + 1)) + 0.5);
                ASSERT_LE(std::abs(p.r - er), 1.0) << x << "," << r;
                ASSERT_LE(std::abs(p.g - eg), 1.0) << x << "," << r;
                ASSERT_LE(std::abs(p.b - eb), 1.0) << x << "," << r;
            }
        // The surface ends at the outermost texel centres: border pixels are half covered, corners a quarter.
        EXPECT_NEAR(out.at(0, h / 2).a, 128, 1);
        EXPECT_NEAR(out.at(w / 2, 0).a, 128, 1);
        EXPECT_NEAR(out.at(0, 0).a, 64, 1);
    }
}

// A relief of one colour stays that colour wherever anything lands, for any displacement and view: the filter
// only forms weighted averages (exact: the weights cancel far below half a level).
TEST(CoverageFilter, OneColourStaysExact) {
    const uint64_t seed = test::test_seed(4343);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        const int w = 4 + int(rng() % 30), h = 4 + int(rng() % 30);
        const double f1 = 0.1 + std::abs(U(rng)), f2 = 0.1 + std::abs(U(rng)), amp = 3 * std::abs(U(rng));
        ReliefTexture t = test::make_test_relief(
            w, h, -amp, amp, [&](int x, int r) { return amp * std::sin(f1 * x) * std::cos(f2 * r); },
            test::random_geometry(rng));
        const Rgba8 c{uint8_t(rng()), uint8_t(rng()), uint8_t(rng()), 255};
        for (ReliefTexel& tx : t.texels.edit()) tx.r = c.r, tx.g = c.g, tx.b = c.b;
        const glm::dvec3 centre = t.point(w / 2, h / 2);
        const glm::dvec3 eye = centre + glm::dvec3(U(rng), U(rng), U(rng)) * 20.0 + t.geometry.f() * 3.0;
        PrewarpOptions o;
        o.filter = Filter::coverage;
        o.keep_outliers = trial % 2;
        o.exact = trial % 3 == 0;
        const ImageRGBA8 out = prewarp(t, eye, o);
        for (const Rgba8& p : out.pixels) {
            if (p.a == 0) continue;
            ASSERT_EQ(p.r, c.r);
            ASSERT_EQ(p.g, c.g);
            ASSERT_EQ(p.b, c.b);
        }
    }
}

// Same output for any number of threads, and the same pixels covered as the point filter away from edges.
TEST(CoverageFilter, ThreadIndependentAndPixelsAgreeWithPointInside) {
    const uint64_t seed = test::test_seed(4444);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    for (int trial = 0; trial < 30; ++trial) {
        const int w = 64 + int(rng() % 64), h = 64 + int(rng() % 64);
        ReliefTexture t = test::make_test_relief(w, h, 0.0, 4.0, [&](int x, int r) {
            return 2.0 + 2.0 * std::sin(0.1 * x) * std::sin(0.13 * r);
        });
        const glm::dvec3 eye{w * 0.5 + 100 * U(rng), h * 0.5 + 100 * U(rng), 150.0 + 50 * U(rng)};
        PrewarpOptions o;
        o.filter = Filter::coverage;
        o.threads = 1;
        const ImageRGBA8 one = prewarp(t, eye, o);
        o.threads = 2;
        ASSERT_EQ(prewarp(t, eye, o), one);
        o.filter = Filter::point;
        const ImageRGBA8 point = prewarp(t, eye, o);
        // Inside the covered region (3x3 neighbourhood covered by the point filter) the surface covers all.
        for (int r = 1; r + 1 < h; ++r)
            for (int x = 1; x + 1 < w; ++x) {
                bool inside = true;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) inside = inside && point.at(x + dx, r + dy).a == 255;
                if (inside) {
                    ASSERT_EQ(one.at(x, r).a, 255) << x << "," << r;
                }
            }
    }
}

TEST(CoverageFilter, PipelinedIsRefused) {
    ReliefTexture t = test::make_test_relief(8, 8, 0.0, 1.0, [](int, int) { return 0.5; });
    PrewarpOptions o;
    o.filter = Filter::coverage;
    o.method = Reconstruction::pipelined;
    try {
        prewarp(t, glm::dvec3(4, 4, 10), o);
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("two-pass"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace rtm
