// Procedural relief textures: geometry, ranges, determinism, the properties each generator promises (bricks at
// exactly zero, facade protrusions and recesses, smooth bumps, steep ridges), and the shipped media/ files.
#include "procedural/procedural_media.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "formats/relief_manifest.h"
#include "common/temp_dir.h"

namespace rtm {
namespace {

namespace fs = std::filesystem;
using objects_testing::TempDir;

// World displacement of texel (x, row), decoded the way load_relief and to_relief decode it.
double world(const ProceduralRelief& p, int x, int row) {
    return p.range_min + double(p.displacement.at(x, row)) * (p.range_max - p.range_min);
}

// Texel (column, row) nearest to relief coordinates (x right, y up) in 0..1.
std::pair<int, int> texel_at(const ProceduralRelief& p, double x, double y) {
    const int i = std::clamp(int(x * p.color.width), 0, p.color.width - 1);
    const int r = std::clamp(p.color.height - 1 - int(y * p.color.height), 0, p.color.height - 1);
    return {i, r};
}

TEST(ProceduralMedia, Names) {
    EXPECT_EQ(procedural_names(), (std::vector<std::string>{"bricks", "facade", "bumps", "ridges"}));
}

TEST(ProceduralMedia, UnknownNameAndBadSize) {
    try {
        make_procedural("marble", 64);
        FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "unknown procedural relief \"marble\"; known: bricks, facade, bumps, ridges");
    }
    for (const std::string& name : procedural_names()) {
        EXPECT_THROW(make_procedural(name, 0), std::invalid_argument) << name;
        EXPECT_THROW(make_procedural(name, -5), std::invalid_argument) << name;
        EXPECT_THROW(make_procedural(name, 100000), std::invalid_argument) << name;
    }
}

TEST(ProceduralMedia, GeometrySizesAndRanges) {
    for (const std::string& name : procedural_names()) {
        for (int size : {8, 64, 100}) {
            SCOPED_TRACE(name + " at " + std::to_string(size));
            const ProceduralRelief p = make_procedural(name, size);
            EXPECT_EQ(p.name, name);
            ASSERT_EQ(p.color.width, size);
            ASSERT_EQ(p.color.height, size);
            ASSERT_EQ(p.displacement.width, size);
            ASSERT_EQ(p.displacement.height, size);
            ASSERT_EQ(p.color.pixels.size(), size_t(size) * size_t(size));
            ASSERT_EQ(p.displacement.pixels.size(), size_t(size) * size_t(size));
            EXPECT_LT(p.range_min, p.range_max);
            // About one world unit wide, texel spacing 1/size, centred on the world origin.
            EXPECT_EQ(p.geometry.a, glm::dvec3(1.0 / size, 0, 0));
            EXPECT_EQ(p.geometry.b, glm::dvec3(0, 1.0 / size, 0));
            EXPECT_EQ(p.geometry.origin, glm::dvec3(-0.5, -0.5, 0.0));
            EXPECT_EQ(p.geometry.validate(), "");
            for (float n : p.displacement.pixels) {
                ASSERT_TRUE(std::isfinite(n));
                ASSERT_GE(n, 0.0f);
                ASSERT_LE(n, 1.0f);
            }
            for (const Rgba8& c : p.color.pixels) ASSERT_EQ(c.a, 255);
            const ReliefTexture t = to_relief(p);
            EXPECT_EQ(t.width, size);
            EXPECT_EQ(t.quant.min, p.range_min);
            EXPECT_EQ(t.quant.max, p.range_max);
        }
    }
}

TEST(ProceduralMedia, Deterministic) {
    for (const std::string& name : procedural_names()) {
        const ProceduralRelief a = make_procedural(name, 96);
        const ProceduralRelief b = make_procedural(name, 96);
        EXPECT_TRUE(a.color == b.color) << name;
        EXPECT_TRUE(a.displacement == b.displacement) << name;
        EXPECT_EQ(a.range_min, b.range_min);
        EXPECT_EQ(a.range_max, b.range_max);
    }
    // Different generators give different pictures.
    EXPECT_FALSE(make_procedural("bricks", 32).color == make_procedural("facade", 32).color);
}

TEST(ProceduralMedia, BrickTexelsHaveExactlyZeroDisplacement) {
    const ProceduralRelief p = make_brick_wall(256);
    EXPECT_EQ(p.range_min, -0.04);
    EXPECT_EQ(p.range_max, 0.0);
    const ReliefTexture t = to_relief(p);
    size_t bricks = 0, mortar = 0;
    for (int r = 0; r < t.height; ++r) {
        for (int x = 0; x < t.width; ++x) {
            if (p.displacement.at(x, r) == 1.0f) {
                ++bricks;
                ASSERT_EQ(t.displ(x, r), 0.0f);
                ASSERT_EQ(t.quant.decode(t.texel(x, r).q), 0.0) << "brick texel (" << x << ", " << r << ")";
            } else {
                ++mortar;
                ASSERT_LT(t.displ(x, r), -0.015f);  // recessed: a step at the brick edge, deeper in the middle
            }
        }
    }
    // Most of a wall is brick; the mortar is a real fraction of it.
    EXPECT_GT(bricks, size_t(0.6 * 256 * 256));
    EXPECT_GT(mortar, size_t(0.1 * 256 * 256));
    // Rounded joints: the deepest mortar is at the full range, the shallowest about half of it.
    const auto [lo, hi] = std::minmax_element(t.displacement.begin(), t.displacement.end());
    EXPECT_NEAR(*lo, -0.04, 0.004);
    EXPECT_EQ(*hi, 0.0f);
}

// The lifted and sunk walls of `rtm bench-skips` (and `rtm-warp-run lifted-bricks`): the wall's texels, colours and
// levels byte for byte over a range moved by the shift, so no texel is still and every one is shifted alike.
TEST(ProceduralMedia, ShiftedBrickWallKeepsTheLevelsAndLeavesNothingStill) {
    const ProceduralRelief wall = make_brick_wall(128);
    const ReliefTexture t = to_relief(wall);
    for (double shift : {0.05, -0.05}) {
        SCOPED_TRACE("shift " + std::to_string(shift));
        const ProceduralRelief p = make_shifted_brick_wall(128, shift);
        EXPECT_EQ(p.range_min, wall.range_min + shift);
        EXPECT_EQ(p.range_max, wall.range_max + shift);
        EXPECT_EQ(p.color.pixels, wall.color.pixels);
        EXPECT_EQ(p.displacement.pixels, wall.displacement.pixels);
        const ReliefTexture s = to_relief(p);
        ASSERT_EQ(s.texels.size(), t.texels.size());
        for (size_t i = 0; i < s.texels.size(); ++i) {
            ASSERT_EQ(s.texels[i].q, t.texels[i].q) << "texel " << i;
            ASSERT_NE(s.quant.decode(s.texels[i].q), 0.0) << "texel " << i;
            // min + q * (max - min) / 254 over the moved range: the wall's level plus the shift, but for the rounding
            // of a few double operations on values below 0.1 (1e-12 is thousands of times that).
            ASSERT_NEAR(s.quant.decode(s.texels[i].q), t.quant.decode(t.texels[i].q) + shift, 1e-12) << "texel " << i;
        }
    }
}

TEST(ProceduralMedia, BrickZeroSurvivesTheFileRoundTrip) {
    TempDir dir;
    const ProceduralRelief p = make_brick_wall(64);
    ReliefManifest m;
    m.range_min = p.range_min;
    m.range_max = p.range_max;
    m.geometry = p.geometry;
    const std::string path = dir.file("bricks.relief.json");
    write_relief(path, m, p.color, p.displacement);
    const ReliefTexture t = load_relief(path);
    for (int r = 0; r < t.height; ++r)
        for (int x = 0; x < t.width; ++x)
            if (p.displacement.at(x, r) == 1.0f) {
                ASSERT_EQ(t.quant.decode(t.texel(x, r).q), 0.0);
                ASSERT_EQ(t.displ(x, r), 0.0f);
            }
}

TEST(ProceduralMedia, FacadeHasWallProtrusionsAndRecesses) {
    const ProceduralRelief p = make_facade(256);
    EXPECT_LT(p.range_min, 0.0);
    EXPECT_GT(p.range_max, 0.0);
    auto at = [&](double x, double y) {
        const auto [i, r] = texel_at(p, x, y);
        return world(p, i, r);
    };
    // Wall plane at zero (to float precision of the normalized value).
    for (auto [x, y] : {std::pair{0.03, 0.35}, {0.97, 0.2}, {0.35, 0.55}, {0.65, 0.25}})
        EXPECT_NEAR(at(x, y), 0.0, 1e-6) << "wall at " << x << ", " << y;
    EXPECT_LT(at(0.5, 0.15), -0.03);                 // door recessed
    EXPECT_LT(at(0.17, 0.2), 0.0);                   // glass recessed behind the frame
    EXPECT_GT(at(0.2 - 0.055 - 0.008, 0.2), 0.0);    // window frame protrudes
    EXPECT_GT(at(0.2, 0.13 - 0.016 - 0.008), 0.04);  // sill protrudes further
    EXPECT_GT(at(0.5, 0.72), 0.03);                  // cornice
    // Dormers stand out of the roof: the dormer's face is in front of the roof beside it at the same height.
    EXPECT_GT(at(0.3 - 0.05, 0.85), at(0.5, 0.85) + 0.02);
    // The whole range is used (a little slack: the extremes are thin features).
    const auto [lo, hi] = std::minmax_element(p.displacement.pixels.begin(), p.displacement.pixels.end());
    EXPECT_LT(*lo, 0.05f);
    EXPECT_GT(*hi, 0.95f);
}

TEST(ProceduralMedia, BumpsAreSmoothAndRidgesAreSteep) {
    constexpr int size = 256;
    auto max_step = [&](const ProceduralRelief& p) {  // largest world-unit change between neighbouring texels
        double m = 0.0;
        for (int r = 0; r < size; ++r)
            for (int x = 0; x + 1 < size; ++x) {
                m = std::max(m, std::abs(world(p, x + 1, r) - world(p, x, r)));
                if (r + 1 < size) m = std::max(m, std::abs(world(p, x, r + 1) - world(p, x, r)));
            }
        return m;
    };
    const ProceduralRelief bumps = make_bumps(size);
    EXPECT_EQ(bumps.range_min, 0.0);
    EXPECT_EQ(bumps.range_max, 0.15);
    const auto [blo, bhi] = std::minmax_element(bumps.displacement.pixels.begin(), bumps.displacement.pixels.end());
    EXPECT_EQ(*blo, 0.0f);
    EXPECT_EQ(*bhi, 1.0f);
    // Smooth: slope below about 1.5 (a step of 1.5 texel spacings).
    EXPECT_LT(max_step(bumps), 1.5 / size);

    const ProceduralRelief ridges = make_ridges(size);
    EXPECT_EQ(ridges.range_min, 0.0);
    EXPECT_GE(ridges.range_max, 0.25);
    // Steep: slope over 3 (the crest-to-trough walls are much taller than they are wide).
    EXPECT_GT(max_step(ridges), 3.0 / size);
    // Ridges run along y: every row is the same.
    for (int r = 1; r < size; ++r)
        for (int x = 0; x < size; ++x) ASSERT_EQ(ridges.displacement.at(x, r), ridges.displacement.at(x, 0));
}

TEST(ShippedMedia, LoadAndMatchTheGenerators) {
    const fs::path media = fs::path(RTM_SOURCE_DIR) / "media";
    std::uintmax_t total = 0;
    for (const auto& e : fs::directory_iterator(media))
        if (e.is_regular_file()) total += e.file_size();
    EXPECT_LT(total, 10u * 1024u * 1024u) << "media/ should stay well under 10 MB";
    for (const std::string& name : procedural_names()) {
        SCOPED_TRACE(name);
        const std::string path = (media / (name + ".relief.json")).string();
        ReliefManifest m;
        ReliefTexture t;
        ASSERT_NO_THROW(t = load_relief(path, &m));
        EXPECT_EQ(m.name, name);
        EXPECT_EQ(t.width, 256);
        EXPECT_EQ(t.height, 256);
        // The shipped files are what the generator makes now (regenerate with rtm-make-media --out media).
        const ProceduralRelief p = make_procedural(name, 256);
        const ReliefTexture direct = to_relief(p);
        EXPECT_EQ(m.range_min, p.range_min);
        EXPECT_EQ(m.range_max, p.range_max);
        EXPECT_EQ(t.geometry.origin, p.geometry.origin);
        EXPECT_EQ(t.geometry.a, p.geometry.a);
        EXPECT_EQ(t.geometry.b, p.geometry.b);
        int q_off = 0;
        for (size_t k = 0; k < t.texels.size(); ++k) {
            const ReliefTexel a = t.texels[k], b = direct.texels[k];
            ASSERT_TRUE(a.r == b.r && a.g == b.g && a.b == b.b) << "colour differs at texel " << k;
            // 16-bit files can move a value sitting on a half-level boundary by one 8-bit level.
            ASSERT_LE(std::abs(int(a.q) - int(b.q)), 1) << "texel " << k;
            q_off += a.q != b.q;
        }
        EXPECT_LT(q_off, int(t.texels.size() / 100));
    }
}

}  // namespace
}  // namespace rtm
