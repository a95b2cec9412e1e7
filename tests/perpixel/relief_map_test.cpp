// The per-pixel methods' textures (perpixel/relief_map.h): the float depth map against the 8-bit relief map.
#include <gtest/gtest.h>

#include <cmath>

#include "perpixel/relief_map.h"

namespace rtm {
namespace {

// Displacements in [-1, 3] (range 4) on a 3x2 relief, one texel empty.
ReliefTexture small_relief() {
    ImageRGBA8 color(3, 2);
    for (Rgba8& p : color.pixels) p = {10, 20, 30, 255};
    color.at(2, 1).a = 0;
    ImageF d(3, 2);
    d.pixels = {3.0f, -1.0f, 1.0f, 0.3f, 2.0f, 0.0f};
    return make_relief(color, d, -1.0, 3.0, ReliefGeometry{});
}

TEST(PerPixelReliefMap, FloatDepthIsTheExactDisplacementScaledToTheRange) {
    const ReliefTexture t = small_relief();
    const ImageF depth = perpixel_depth_map(t);
    ASSERT_EQ(depth.width, 3);
    ASSERT_EQ(depth.height, 2);
    // depth = (3 - displacement) / 4, exact in float for these values except 0.3 (one float rounding).
    EXPECT_EQ(depth.at(0, 0), 0.0f);
    EXPECT_EQ(depth.at(1, 0), 1.0f);
    EXPECT_EQ(depth.at(2, 0), 0.5f);
    EXPECT_FLOAT_EQ(depth.at(0, 1), float((3.0 - double(0.3f)) / 4.0));
    EXPECT_EQ(depth.at(1, 1), 0.25f);
    EXPECT_EQ(depth.at(2, 1), 1.0f);  // empty: the bottom
}

TEST(PerPixelReliefMap, EightBitDepthIsTheFloatDepthQuantizedTo254Levels) {
    const ReliefTexture t = small_relief();
    const ImageF depth = perpixel_depth_map(t);
    const ImageRGBA8 relief = perpixel_relief_map(t);
    for (int row = 0; row < 2; ++row)
        for (int x = 0; x < 3; ++x) {
            // The shader reads alpha / 255 * 255 / 254 = alpha / 254; the quantizer rounds to the nearest level.
            const double eight_bit = relief.at(x, row).a / 254.0;
            EXPECT_LE(std::abs(eight_bit - double(depth.at(x, row))), 0.5 / 254.0 + 1e-7) << x << " " << row;
        }
}

}  // namespace
}  // namespace rtm
