#include "warp/pyramid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "test_util.h"

namespace rtm {
namespace {

TEST(Pyramid, LevelsHalveAndCoverTheSameArea) {
    ReliefGeometry g;
    g.a = {0.01, 0.0, 0.002};
    g.b = {0.0, 0.02, 0.0};
    const ReliefTexture t = test::make_test_relief(
        37, 20, 0.0, 1.0, [](int x, int r) { return (x + r) / 60.0; }, g);
    const ReliefPyramid p(t);
    ASSERT_EQ(p.levels(), 7);  // 37x20, 19x10, 10x5, 5x3, 3x2, 2x1, 1x1
    EXPECT_EQ(p.level(1).width, 19);
    EXPECT_EQ(p.level(1).height, 10);
    EXPECT_EQ(p.level(6).width, 1);
    EXPECT_EQ(p.level(6).height, 1);
    for (int i = 0; i < p.levels(); ++i) {
        const ReliefTexture& l = p.level(i);
        EXPECT_NEAR(glm::length(l.geometry.a) * l.width, glm::length(g.a) * 37, 1e-12);
        EXPECT_NEAR(glm::length(l.geometry.b) * l.height, glm::length(g.b) * 20, 1e-12);
        EXPECT_EQ(l.geometry.origin, g.origin);
    }
}

TEST(Pyramid, PowerOfTwoDoublesAAndAveragesBlocks) {
    ReliefGeometry g;
    const ReliefTexture t = test::make_test_relief(
        4, 4, 0.0, 1.0, [](int x, int r) { return x * 0.1 + r * 0.01; }, g);
    const ReliefPyramid p(t);
    const ReliefTexture& l1 = p.level(1);
    EXPECT_EQ(l1.geometry.a, g.a * 2.0);
    EXPECT_EQ(l1.geometry.b, g.b * 2.0);
    // Level-1 texel (0, row 1) is the bottom-left block: storage rows 2, 3 and columns 0, 1 of level 0.
    double d = 0, cr = 0;
    for (int r = 2; r < 4; ++r)
        for (int x = 0; x < 2; ++x) {
            d += t.displ(x, r) / 4;
            cr += t.texel(x, r).r / 4.0;
        }
    EXPECT_FLOAT_EQ(l1.displ(0, 1), float(d));
    EXPECT_EQ(l1.texel(0, 1).r, uint8_t(std::lround(cr)));
}

TEST(Pyramid, EmptyTexelsDoNotPolluteAverages) {
    ReliefGeometry g;
    ImageRGBA8 c(2, 2, {100, 100, 100, 255});
    ImageF d(2, 2, 0.5f);
    c.at(0, 0) = {0, 0, 0, 0};  // empty, with a wild displacement that must not count
    d.at(0, 0) = 1.0f;
    const ReliefPyramid p(make_relief(c, d, 0.0, 1.0, g));
    EXPECT_EQ(p.level(1).texel(0, 0).r, 100);
    EXPECT_FLOAT_EQ(p.level(1).displ(0, 0), 0.5f);
    ImageRGBA8 e(2, 2, {0, 0, 0, 0});
    const ReliefPyramid q(make_relief(e, d, 0.0, 1.0, g));
    EXPECT_EQ(q.level(1).texel(0, 0).q, kEmptyIndex);
}

TEST(Pyramid, LevelForDensity) {
    EXPECT_EQ(level_for_density(256.0 * 256, 256.0 * 256, 8), 0);
    EXPECT_EQ(level_for_density(256.0 * 256, 128.0 * 128, 8), 1);
    EXPECT_EQ(level_for_density(256.0 * 256, 100.0 * 100, 8), 1);  // 6.55x: floor(log4) = 1
    EXPECT_EQ(level_for_density(256.0 * 256, 64.0 * 64, 8), 2);
    EXPECT_EQ(level_for_density(256.0 * 256, 1.0, 8), 8);
    EXPECT_EQ(level_for_density(256.0 * 256, 0.0, 8), 8);
    EXPECT_EQ(level_for_density(16, 1e6, 8), 0);
}

// Placed copies of one relief (other origin, a and b; the same texels) read their levels from one SharedPyramid: each
// level is exactly the level the copy's own downsampling gives (texels, displacements, quantizer, geometry), its
// texels shared with the other copies'; a relief with other texels is refused.
TEST(SharedPyramid, LevelsAreEachCopysOwnAndShareTexels) {
    const ReliefTexture t = test::make_test_relief(37, 20, -0.2, 0.5,
                                                   [](int x, int r) { return std::sin(x * 0.7) * 0.3 + r * 0.01; });
    ReliefTexture placed[2] = {t, t};
    placed[1].geometry.origin = {4.0, -2.0, 7.5};
    placed[1].geometry.a = {0.0, 0.0, -1.5};
    placed[1].geometry.b = {0.0, 1.5, 0.0};
    SharedPyramid shared;
    for (int i = 1; i <= 7; ++i) {  // 6 is the 1x1 level; 7 asks past it
        ReliefTexture levels[2];
        for (int k = 0; k < 2; ++k) {
            SCOPED_TRACE("level " + std::to_string(i) + ", copy " + std::to_string(k));
            const ReliefPyramid own(placed[k]);
            const ReliefTexture& want = own.level(std::min(i, own.levels() - 1));
            levels[k] = shared.level(placed[k], i);
            EXPECT_EQ(levels[k].width, want.width);
            EXPECT_EQ(levels[k].height, want.height);
            EXPECT_EQ(levels[k].texels, want.texels);
            EXPECT_EQ(levels[k].displacement, want.displacement);
            EXPECT_EQ(levels[k].quant.min, want.quant.min);
            EXPECT_EQ(levels[k].quant.max, want.quant.max);
            EXPECT_EQ(levels[k].geometry.origin, want.geometry.origin);
            EXPECT_EQ(levels[k].geometry.a, want.geometry.a);
            EXPECT_EQ(levels[k].geometry.b, want.geometry.b);
        }
        EXPECT_TRUE(levels[0].texels.shares_storage_with(levels[1].texels));
        EXPECT_TRUE(levels[0].displacement.shares_storage_with(levels[1].displacement));
    }
    ReliefTexture other = t;
    other.texels.edit()[3].r ^= 1;
    EXPECT_THROW(shared.level(other, 1), std::logic_error);
}

}  // namespace
}  // namespace rtm
