#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <random>

#include "test_util.h"
#include "warp/prewarp.h"

namespace rtm {
namespace {

TEST(TwoPass, ZeroDisplacementIsTheIdentity) {
    const uint64_t seed = test::test_seed(40001);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int i = 0; i < 50; ++i) {
        const int w = 1 + int(rng() % 70), h = 1 + int(rng() % 70);
        const ReliefGeometry g = test::random_geometry(rng);
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, 0.0, [](int, int) { return 0.0; }, g);
        const glm::dvec3 eye = g.origin + g.a * (U(rng) * 200) + g.b * (U(rng) * 200) +
                               g.f() * (0.01 + std::abs(U(rng)));
        for (bool exact : {false, true}) {
            const ImageRGBA8 out = prewarp(t, eye, {.exact = exact});
            ASSERT_EQ(out, color_image(t)) << w << "x" << h << " exact=" << exact;
        }
    }
}

TEST(TwoPass, ConstantDisplacementIsAScalingAboutTheEpipole) {
    // d constant: u_i - e = (u_s - e) / (1 + k3*d). Every output pixel centre c maps back to the source
    // position e + (c - e)*(1 + k3*d); the span interpolation is linear, so the output colour is the linear
    // interpolation of the two source texels around that position. Tolerance 1 level per channel: the two
    // passes each round to 8 bits.
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.01, 0};
    const int n = 64;
    const double d = 0.05;
    const ReliefTexture t = test::make_test_relief(
        n, n, d, d, [&](int, int) { return d; }, g);
    const glm::dvec3 eye{0.2, 0.3, 0.5};  // epipole at (20, 30) texels, inside
    const PrewarpCoefficients k = compute_coefficients(g, eye);
    const double s = 1 + k.k3 * d;  // < 1: the texture spreads out from the epipole
    const ImageRGBA8 out = prewarp(t, eye, {.exact = true});
    int checked = 0;
    for (int r = 0; r < n; ++r)
        for (int x = 0; x < n; ++x) {
            const double cu = x + 0.5, cv = (n - 1 - r) + 0.5;
            const double su = k.epipole_u + (cu - k.epipole_u) * s, sv = k.epipole_v + (cv - k.epipole_v) * s;
            ASSERT_EQ(out.at(x, r).a, 255) << x << "," << r;  // spreads: everything covered
            // Bilinear source lookup at (su, sv) between texel centres.
            const double fx = su - 0.5, fy = sv - 0.5;
            const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
            if (x0 < 0 || y0 < 0 || x0 + 1 >= n || y0 + 1 >= n) continue;
            const double tx = fx - x0, ty = fy - y0;
            auto c = [&](int xx, int vj, int ch) {
                const ReliefTexel& tt = t.texel(xx, n - 1 - vj);
                return double(ch == 0 ? tt.r : ch == 1 ? tt.g : tt.b);
            };
            for (int ch = 0; ch < 3; ++ch) {
                const double want = (c(x0, y0, ch) * (1 - tx) + c(x0 + 1, y0, ch) * tx) * (1 - ty) +
                                    (c(x0, y0 + 1, ch) * (1 - tx) + c(x0 + 1, y0 + 1, ch) * tx) * ty;
                const uint8_t* got = &out.at(x, r).r;
                ASSERT_NEAR(double(got[ch]), want, 1.0) << "pixel " << x << "," << r << " ch " << ch;
            }
            ++checked;
        }
    EXPECT_GT(checked, 1000);
}

TEST(TwoPass, NearerTexelWinsWhereTwoFallOnOneRay) {
    // A floor at d = 0 with a tall block (d = 0.3) in columns 4..7; the eye is far to the right, so the block's
    // top moves left over the floor. Where the block lands, its colour (nearer the viewer) must win.
    ReliefGeometry g;
    const int w = 32, h = 4;
    ImageRGBA8 c(w, h, {0, 0, 255, 255});
    ImageF d(w, h, 0.0f);
    for (int r = 0; r < h; ++r)
        for (int x = 4; x < 8; ++x) {
            c.at(x, r) = {255, 0, 0, 255};
            d.at(x, r) = 0.3f;
        }
    const ReliefTexture t = make_relief(c, d, 0.0, 0.3, g);
    const glm::dvec3 eye{30.0, 2.0, 1.0};  // epipole u = 30
    const PrewarpCoefficients k = compute_coefficients(g, eye);
    for (bool exact : {false, true}) {
        const ImageRGBA8 out = prewarp(t, eye, {.exact = exact});
        double lo, hi, vv;
        k.warp(4.5, 2.0, 0.3, lo, vv);
        k.warp(7.5, 2.0, 0.3, hi, vv);
        ASSERT_LT(hi, 4.0);  // the block top lands entirely over floor texels 0..3
        for (int x = int(std::ceil(lo - 0.5)); x <= int(std::floor(hi - 0.5)); ++x) {
            if (x < 0) continue;
            EXPECT_EQ(out.at(x, 1), (Rgba8{255, 0, 0, 255})) << "x " << x << " exact " << exact;
        }
    }
}

TEST(TwoPass, NoHoleAtTheEpipoleSplitOfAContinuousSurface) {
    // A smooth bump seen from above, with the epipole on a texel centre, on a texel boundary and in between:
    // texels standing out spread away from the epipole, so every pixel of the interior must be covered.
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.01, 0};
    const int n = 96;
    const ReliefTexture t = test::make_test_relief(
        n, n, 0.0, 0.1,
        [&](int x, int r) {
            const double dx = (x - 48.0) / 30, dy = (r - 48.0) / 30;
            return 0.1 * std::exp(-(dx * dx + dy * dy));
        },
        g);
    for (double eu : {40.5, 41.0, 41.3, 0.0, 96.0}) {
        for (double ev : {52.5, 52.0, 52.77}) {
            const glm::dvec3 eye{eu * 0.01, ev * 0.01, 0.4};
            for (bool exact : {false, true}) {
                const ImageRGBA8 out = prewarp(t, eye, {.exact = exact});
                for (int r = 8; r < n - 8; ++r)
                    for (int x = 8; x < n - 8; ++x)
                        ASSERT_EQ(out.at(x, r).a, 255) << "pixel " << x << "," << r << " epipole " << eu << "," << ev;
            }
        }
    }
}

TEST(TwoPass, OutputDoesNotDependOnThreadCount) {
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.01, 0};
    const ReliefTexture t = test::make_test_relief(
        200, 150, -0.05, 0.1,
        [](int x, int r) { return 0.1 * std::sin(x * 0.2) * std::cos(r * 0.13) * (x % 7 == 0 ? -0.5 : 1.0); }, g);
    for (bool exact : {false, true}) {
        const ImageRGBA8 one = prewarp(t, {0.3, 1.9, 0.7}, {.exact = exact, .threads = 1});
        const ImageRGBA8 two = prewarp(t, {0.3, 1.9, 0.7}, {.exact = exact, .threads = 2});
        const ImageRGBA8 all = prewarp(t, {0.3, 1.9, 0.7}, {.exact = exact, .threads = 0});
        EXPECT_EQ(one, two);
        EXPECT_EQ(one, all);
    }
}

TEST(TwoPass, EmptyTexelsStayEmptyAndTexelsAboveTheEyeAreDropped) {
    ReliefGeometry g;
    const int n = 16;
    ImageRGBA8 c(n, n, {9, 9, 9, 0});  // all empty
    ImageF d(n, n, 0.0f);
    const ReliefTexture empty = make_relief(c, d, 0.0, 1.0, g);
    const ImageRGBA8 out = prewarp(empty, {8, 8, 5});
    for (const Rgba8& p : out.pixels) ASSERT_EQ(p.a, 0);

    // Viewer 0.5 above the plane, every texel at 1.0: none can be pre-warped.
    const ReliefTexture tall = test::make_test_relief(
        n, n, 0.0, 1.0, [](int, int) { return 1.0; }, g);
    PrewarpWorkspace ws;
    ImageRGBA8 o2;
    const PrewarpStats st = prewarp(tall, compute_coefficients(g, {8, 8, 0.5}), {}, ws, o2);
    EXPECT_EQ(st.dropped, n * n);
    for (const Rgba8& p : o2.pixels) ASSERT_EQ(p.a, 0);
}

}  // namespace
}  // namespace rtm
