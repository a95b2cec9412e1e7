// The pyramid level of `--level auto` (objects/level_choice.h): the displacement spread of each level against a
// brute-force count over random reliefs, and the choice per quad: the texel density's level where the spread's
// parallax stays within the bound, finer levels where it does not.
#include "objects/level_choice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <random>

#include "common/seed.h"
#include "objects/bounds.h"
#include "objects/frame_plan.h"
#include "objects/view_analysis.h"
#include "procedural/procedural_media.h"
#include "texmap/camera_rig.h"
#include "warp/pyramid.h"

namespace rtm {
namespace {

// A w x h relief of unit texels in the z = 0 plane with displacement `d(x, v)` (v-row 0 at the bottom) and empty
// texels where `empty(x, v)`.
template <class D, class E>
ReliefTexture relief_of(int w, int h, double lo, double hi, D d, E empty) {
    ImageRGBA8 color(w, h);
    ImageF displ(w, h);
    for (int row = 0; row < h; ++row)
        for (int x = 0; x < w; ++x) {
            const int v = h - 1 - row;
            color.at(x, row) = empty(x, v) ? Rgba8{0, 0, 0, 0} : Rgba8{200, 100, 50, 255};
            displ.at(x, row) = float(d(x, v));
        }
    ReliefGeometry g;
    g.origin = {0, 0, 0};
    g.a = {1.0 / w, 0, 0};
    g.b = {0, 1.0 / h, 0};
    return make_relief(color, displ, lo, hi, g);
}

// The spreads by definition: every level-L block of level-0 texels, bottom-left aligned.
std::vector<double> brute_spreads(const ReliefTexture& t) {
    std::vector<double> s(size_t(pyramid_levels(t.width, t.height)), 0.0);
    for (size_t l = 1; l < s.size(); ++l) {
        const int n = 1 << l;
        for (int bv = 0; bv < t.height; bv += n)
            for (int bx = 0; bx < t.width; bx += n) {
                double lo = 1e300, hi = -1e300;
                for (int v = bv; v < std::min(bv + n, t.height); ++v)
                    for (int x = bx; x < std::min(bx + n, t.width); ++x) {
                        const int row = t.height - 1 - v;
                        if (t.texel(x, row).q == kEmptyIndex) continue;
                        lo = std::min(lo, double(t.displ(x, row)));
                        hi = std::max(hi, double(t.displ(x, row)));
                    }
                if (lo <= hi) s[l] = std::max(s[l], hi - lo);
            }
    }
    return s;
}

TEST(LevelSpreads, MatchTheBlocksOfEveryLevelOverRandomReliefs) {
    const uint64_t seed = test::test_seed(20261202);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const int cases = test::sweep_cases(200);
    for (int c = 0; c < cases; ++c) {
        const int w = std::uniform_int_distribution<int>(1, 40)(rng),
                  h = std::uniform_int_distribution<int>(1, 40)(rng);
        std::vector<double> d(size_t(w) * size_t(h));
        std::vector<char> e(d.size());
        // Smooth, stepped or noisy displacement, and some empty texels.
        const int kind = c % 3;
        const double empty_p = std::uniform_real_distribution<double>(0.0, 0.5)(rng);
        for (size_t i = 0; i < d.size(); ++i) {
            const int x = int(i % size_t(w)), v = int(i / size_t(w));
            d[i] = kind == 0   ? 0.01 * x + 0.002 * v
                   : kind == 1 ? (x > w / 3 ? 0.1 : -0.05)
                               : std::uniform_real_distribution<double>(-0.05, 0.1)(rng);
            e[i] = std::bernoulli_distribution(empty_p)(rng);
        }
        const ReliefTexture t = relief_of(
            w, h, -0.05, 0.1 + 0.01 * 80, [&](int x, int v) { return d[size_t(v) * size_t(w) + size_t(x)]; },
            [&](int x, int v) { return e[size_t(v) * size_t(w) + size_t(x)] != 0; });
        const std::vector<double> got = level_displacement_spreads(t), want = brute_spreads(t);
        ASSERT_EQ(got.size(), want.size()) << "case " << c << " " << w << "x" << h;
        for (size_t l = 0; l < got.size(); ++l) {
            // Both are differences of the same two floats, the fast one in double too: equal.
            EXPECT_EQ(got[l], want[l]) << "case " << c << " " << w << "x" << h << " level " << l;
            if (l > 0) {
                EXPECT_GE(got[l], got[l - 1]) << "case " << c;
            }
        }
        EXPECT_EQ(got[0], 0.0);
    }
}

TEST(LevelSpreads, AStepOnABlockBoundaryStaysOutOfTheFinerLevels) {
    // A step between columns 7 and 8: levels 1 to 3 (blocks of 2, 4, 8) never straddle it, level 4 does.
    const ReliefTexture t = relief_of(
        32, 32, 0.0, 0.1, [](int x, int) { return x < 8 ? 0.0 : 0.1; }, [](int, int) { return false; });
    const std::vector<double> s = level_displacement_spreads(t);
    ASSERT_EQ(s.size(), 6u);
    EXPECT_EQ(s[1], 0.0);
    EXPECT_EQ(s[3], 0.0);
    EXPECT_NEAR(s[4], 0.1, 1e-7);  // float displacement
    // Empty texels do not take part: a step to empty texels is no spread.
    const ReliefTexture holes = relief_of(
        32, 32, 0.0, 0.1, [](int, int) { return 0.05; }, [](int x, int) { return x % 3 == 0; });
    for (double v : level_displacement_spreads(holes)) EXPECT_EQ(v, 0.0);
}

struct View {
    ReliefTexture t;
    Camera orbit(double az, double el, double dist) const {
        const Bounds b = relief_bounds(t);
        return orbit_camera(b.centre(), b.radius(), {az, el, dist}, 256, 256);
    }
};

TEST(ChooseLevel, ADisplacementFreeReliefTakesTheDensityLevel) {
    const View flat{relief_of(
        256, 256, 0.0, 0.0, [](int, int) { return 0.0; }, [](int, int) { return false; })};
    const std::vector<double> s = level_displacement_spreads(flat.t);
    for (double dist : {1.2, 2.5, 5.0, 20.0}) {
        const Camera cam = flat.orbit(30, 20, dist);
        EXPECT_EQ(choose_level(cam, flat.t, s, 0.5), auto_level(cam, flat.t)) << dist;
        EXPECT_EQ(choose_level(cam, flat.t, s, 0.0), auto_level(cam, flat.t)) << dist;
    }
    EXPECT_GT(auto_level(flat.orbit(30, 20, 20.0), flat.t), 2);
}

TEST(ChooseLevel, ASharpStepKeepsTheFineLevelWhileItsParallaxIsVisible) {
    // A 256^2 wall with frames standing 0.12 out of it every 16 texels (a facade's window frames): every level's
    // blocks straddle a frame's edge from level 1 on, so the spread is the whole 0.12.
    const View wall{relief_of(
        256, 256, 0.0, 0.12, [](int x, int v) { return (x % 16 == 5 || v % 16 == 9) ? 0.12 : 0.0; },
        [](int, int) { return false; })};
    const std::vector<double> s = level_displacement_spreads(wall.t);
    ASSERT_NEAR(s[1], 0.12, 1e-7);
    int held = 0, coarse = 0;
    for (double dist : {1.5, 2.5, 4.0, 8.0, 16.0, 64.0, 256.0}) {
        for (double az : {0.0, 40.0, 70.0}) {
            const Camera cam = wall.orbit(az, 15, dist);
            const int density = auto_level(cam, wall.t);
            const int chosen = choose_level(cam, wall.t, s, 0.5);
            const double error = s[1] * parallax_pixels_per_unit(cam, wall.t);
            std::printf("distance %5.1f azimuth %2.0f: density level %d, chosen %d, spread parallax %.3f px\n", dist,
                        az, density, chosen, error);
            // Never coarser than the density; coarser than 0 only when the spread's parallax is within the bound.
            EXPECT_LE(chosen, density);
            if (chosen > 0) {
                EXPECT_LE(s[size_t(chosen)] * parallax_pixels_per_unit(cam, wall.t), 0.5);
            }
            if (density > 0 && error > 0.5) {
                EXPECT_EQ(chosen, 0);
            }
            if (density > 0 && error <= 0.5) {  // the same spread at every level
                EXPECT_EQ(chosen, density);
            }
            held += chosen < density;
            coarse += chosen > 0;
            // No bound: the density alone.
            EXPECT_EQ(choose_level(cam, wall.t, s, std::numeric_limits<double>::infinity()), density);
        }
    }
    EXPECT_GT(held, 0);    // the bound held some quads finer than their density
    EXPECT_GT(coarse, 0);  // and let the far ones go coarse
}

TEST(ChooseLevel, ASmoothReliefGoesAsCoarseAsItsSpreadAllows) {
    // Bumps: the spread of a level grows with its blocks, so the choice may stop between 0 and the density level.
    const View bumps{to_relief(make_bumps(256))};
    const std::vector<double> s = level_displacement_spreads(bumps.t);
    for (size_t l = 1; l < s.size(); ++l) EXPECT_GE(s[l], s[l - 1]);
    for (double dist : {1.2, 2.5, 5.0, 20.0, 80.0}) {
        const Camera cam = bumps.orbit(20, 30, dist);
        const int density = auto_level(cam, bumps.t), chosen = choose_level(cam, bumps.t, s, 0.5);
        const double per_unit = parallax_pixels_per_unit(cam, bumps.t);
        EXPECT_LE(chosen, density) << dist;
        // The coarsest level within the bound: the next coarser one (up to the density) exceeds it.
        if (chosen > 0) {
            EXPECT_LE(s[size_t(chosen)] * per_unit, 0.5) << dist;
        }
        if (chosen < density) {
            EXPECT_GT(s[size_t(chosen) + 1] * per_unit, 0.5) << dist;
        }
    }
}

TEST(ChooseLevel, PlanFrameUsesItForLevelAuto) {
    const View bumps{to_relief(make_bumps(64))};
    std::vector<ReliefTexture> pyramid;
    for (int i = 1; i < pyramid_levels(64, 64); ++i)
        pyramid.push_back(downsample(pyramid.empty() ? bumps.t : pyramid.back(), bumps.t));
    const LevelSource levels = [&](int i) -> const ReliefTexture& {
        return i == 0 ? bumps.t : pyramid.at(size_t(i) - 1);
    };
    const std::vector<double> s = level_displacement_spreads(bumps.t);
    DrawOptions d;
    d.level = -1;
    for (double bound : {0.0, 0.5, 4.0, std::numeric_limits<double>::infinity()}) {
        d.level_error_px = bound;
        for (double dist : {1.5, 6.0, 30.0}) {
            const Camera cam = bumps.orbit(10, 10, dist);
            const int want = choose_level(cam, bumps.t, s, bound);
            EXPECT_EQ(plan_frame(cam, RenderMethod::two_pass, {}, d, bumps.t, levels, {}).level, want) << dist;
            EXPECT_EQ(plan_frame(cam, RenderMethod::two_pass, {}, d, bumps.t, levels, {}, &s).level, want) << dist;
        }
    }
}

}  // namespace
}  // namespace rtm
