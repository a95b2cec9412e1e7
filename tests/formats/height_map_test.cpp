// bake_height_map (formats/height_map.h): a height map and a colour image -> a relief the relief reader takes.
#include <gtest/gtest.h>

#include <stdexcept>

#include "common/temp_dir.h"
#include "formats/height_map.h"
#include "formats/image_io.h"
#include "formats/relief_manifest.h"

namespace rtm {
namespace {

using objects_testing::TempDir;

TEST(HeightMap, RoundTripThroughTheReliefReader) {
    TempDir dir;
    ImageF height(5, 3);
    ImageRGBA8 color(5, 3);
    for (int r = 0; r < 3; ++r)
        for (int i = 0; i < 5; ++i) {
            height.at(i, r) = float(i + 5 * r) / 14.0f;
            color.at(i, r) = Rgba8{uint8_t(10 * i), uint8_t(50 * r), 7, 255};
        }
    write_gray(dir.file("rock_height.png"), height);
    write_rgba8(dir.file("rock_color.png"), color);
    HeightBakeOptions o;
    o.height_path = dir.file("rock_height.png");
    o.color_path = dir.file("rock_color.png");
    o.range_min = -0.5;
    o.range_max = 1.5;
    o.texel = 0.25;
    const std::string manifest = bake_height_map(o, dir.file("out"));
    EXPECT_EQ(manifest, dir.file("out/rock_height.relief.json"));
    ReliefManifest m;
    const ReliefTexture t = load_relief(manifest, &m);
    EXPECT_EQ(m.name, "rock_height");
    EXPECT_EQ(m.range_min, -0.5);
    EXPECT_EQ(m.range_max, 1.5);
    EXPECT_EQ(t.geometry.origin, glm::dvec3(0.0));
    EXPECT_EQ(t.geometry.a, glm::dvec3(0.25, 0, 0));
    EXPECT_EQ(t.geometry.b, glm::dvec3(0, 0.25, 0));
    ASSERT_EQ(t.width, 5);
    ASSERT_EQ(t.height, 3);
    for (int r = 0; r < 3; ++r)
        for (int i = 0; i < 5; ++i) {
            // Two 16-bit quantizations (the test's image and the bake's), half a step each over a range of 2.
            EXPECT_NEAR(t.displ(i, r), -0.5 + 2.0 * height.at(i, r), 2.0 / 65535 + 1e-6) << i << "," << r;
            const ReliefTexel& x = t.texel(i, r);
            EXPECT_EQ(Rgba8({x.r, x.g, x.b, 255}), color.at(i, r));
        }
}

TEST(HeightMap, DefaultsAndGreyColour) {
    TempDir dir;
    ImageF height(4, 4, 1.0f);
    height.at(0, 0) = 0.0f;
    write_gray(dir.file("h.png"), height);
    HeightBakeOptions o;
    o.height_path = dir.file("h.png");
    ReliefManifest m;
    const ReliefTexture t = load_relief(bake_height_map(o, dir.file("out")), &m);
    EXPECT_EQ(t.geometry.a, glm::dvec3(0.25, 0, 0));  // one unit wide
    EXPECT_EQ(m.range_min, 0.0);
    EXPECT_DOUBLE_EQ(m.range_max, 0.1);  // a tenth of the width
    EXPECT_EQ(t.texel(0, 0).r, 0);
    EXPECT_EQ(t.texel(1, 0).r, 255);
}

TEST(HeightMap, RefusesMismatchedColourNamingBothFiles) {
    TempDir dir;
    write_gray(dir.file("h.png"), ImageF(4, 4, 0.5f));
    write_rgba8(dir.file("c.png"), ImageRGBA8(3, 4, Rgba8{1, 2, 3, 255}));
    HeightBakeOptions o;
    o.height_path = dir.file("h.png");
    o.color_path = dir.file("c.png");
    try {
        (void)bake_height_map(o, dir.file("out"));
        ADD_FAILURE() << "accepted";
    } catch (const IoError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("c.png"), std::string::npos) << msg;
        EXPECT_NE(msg.find("h.png"), std::string::npos) << msg;
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
    o.color_path.clear();
    o.range_min = 1.0;
    o.range_max = 0.0;
    EXPECT_THROW(bake_height_map(o, dir.file("out")), std::invalid_argument);
}

TEST(HeightMap, SizeResamplesAndKeepsTheWorldSize) {
    // A 6x3 ramp resampled to 4 texels along the longer side: 4x2, each written texel 6/4 of the given one wide.
    TempDir dir;
    ImageF height(6, 3);
    for (int r = 0; r < 3; ++r)
        for (int i = 0; i < 6; ++i) height.at(i, r) = float(i) / 5.0f;
    write_gray(dir.file("ramp.png"), height);
    HeightBakeOptions o;
    o.height_path = dir.file("ramp.png");
    o.range_min = 0.0;
    o.range_max = 1.0;
    o.texel = 0.5;
    o.size = 4;
    ReliefManifest m;
    const ReliefTexture t = load_relief(bake_height_map(o, dir.file("out")), &m);
    ASSERT_EQ(t.width, 4);
    ASSERT_EQ(t.height, 2);
    EXPECT_DOUBLE_EQ(t.geometry.a.x * t.width, 3.0);  // 6 texels of 0.5: the same 3 units wide
    EXPECT_DOUBLE_EQ(t.geometry.b.y * t.height, 1.5);
    for (int r = 0; r < 2; ++r) {
        // Output texel 1 is centred on source texel coordinate 1.5 * 1.5 - 0.5 = 1.75, tent radius 1.5: weights
        // 1/2, 5/6, 1/6 on texels 1, 2, 3 (sum 3/2), so (1/2 + 10/6 + 3/6) / (3/2) / 5 = 16/45; texel 2, centred
        // on 3.25: 1/6, 5/6, 1/2 on texels 2, 3, 4, 29/45. Tolerance: the two 16-bit quantizations.
        EXPECT_NEAR(t.displ(1, r), 16.0 / 45, 2.0 / 65535 + 1e-6) << r;
        EXPECT_NEAR(t.displ(2, r), 29.0 / 45, 2.0 / 65535 + 1e-6) << r;
    }
    o.size = 0;
    EXPECT_THROW(bake_height_map(o, dir.file("out0")), std::invalid_argument);
}

}  // namespace
}  // namespace rtm
