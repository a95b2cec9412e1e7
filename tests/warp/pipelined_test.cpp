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
        const ReliefTexture t = test::make_test_relief(w, h, 0.0, 0.0, [](int, int) { return 0.0; }, g);
        const glm::dvec3 eye = g.origin + g.a * (U(rng) * 200) + g.b * (U(rng) * 200) + g.f() * (0.01 + std::abs(U(rng)));
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
    const ReliefTexture t = test::make_test_relief(n, n, 0.0, 0.05, [&](int x, int r) {
        const double dx = (x - 40.0) / 25, dy = (r - 37.0) / 25;
        return 0.05 * std::exp(-(dx * dx + dy * dy));
    }, g);
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
    const ReliefTexture t = test::make_test_relief(120, 90, 0.0, 0.3, [](int x, int r) {
        return 0.3 * std::abs(std::sin(x * 0.3)) * std::abs(std::cos(r * 0.21));  // steep: folds over
    }, g);
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
    const ReliefTexture t = test::make_test_relief(n, n, 2.0, 2.0, [](int, int) { return 2.0; }, g);
    for (double e : {20.5, 21.0, 21.2}) {
        const ImageRGBA8 out = prewarp(t, {e, e + 3, 40.0}, kPipe);
        for (const Rgba8& p : out.pixels) ASSERT_EQ(p.a, 255) << "epipole " << e;
    }
}

}  // namespace
}  // namespace rtm
