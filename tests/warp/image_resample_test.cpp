// warp/image_resample.h: the tent resampler of rtm bake --height --size.
#include "warp/image_resample.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "common/seed.h"

namespace rtm {
namespace {

ImageF random_image(int w, int h, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    ImageF img(w, h);
    for (float& v : img.pixels) v = u(rng);
    return img;
}

TEST(ImageResample, SameSizeIsTheIdentity) {
    const uint64_t seed = test::test_seed(11);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const ImageF img = random_image(7, 5, seed);
    EXPECT_EQ(resample_tent(img, 7, 5), img);  // one tap of weight 1: exact
    ImageRGBA8 c(3, 2);
    for (size_t i = 0; i < c.pixels.size(); ++i) c.pixels[i] = {uint8_t(i), uint8_t(40 * i), 7, uint8_t(255 - i)};
    EXPECT_EQ(resample_tent(c, 3, 2), c);
}

TEST(ImageResample, HalvingAveragesWithTheTentWeights) {
    // Shrinking by 2: output x centred at source 2x + 0.5, tent radius 2: weights 1/8, 3/8, 3/8, 1/8 on source
    // texels 2x - 1 .. 2x + 2 (clamped at the edges).
    ImageF row(4, 1);
    row.pixels = {0.0f, 1.0f, 0.0f, 0.0f};
    const ImageF out = resample_tent(row, 2, 1);
    ASSERT_EQ(out.width, 2);
    EXPECT_FLOAT_EQ(out.pixels[0], 3.0f / 8);  // texels -1 (clamped to 0: 0), 0, 1, 2
    EXPECT_FLOAT_EQ(out.pixels[1], 1.0f / 8);  // texels 1, 2, 3, 4 (clamped to 3)
}

TEST(ImageResample, DoublingIsBilinearWithClampedEdges) {
    ImageF row(2, 1);
    row.pixels = {0.0f, 1.0f};
    const ImageF out = resample_tent(row, 4, 1);
    // Output centres at source -0.25, 0.25, 0.75, 1.25.
    EXPECT_FLOAT_EQ(out.pixels[0], 0.0f);
    EXPECT_FLOAT_EQ(out.pixels[1], 0.25f);
    EXPECT_FLOAT_EQ(out.pixels[2], 0.75f);
    EXPECT_FLOAT_EQ(out.pixels[3], 1.0f);
}

TEST(ImageResample, ConstantStaysConstantAndValuesStayInRange) {
    const uint64_t seed = test::test_seed(12);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const ImageF flat(9, 13, 0.375f);
    for (auto [w, h] : {std::pair{3, 4}, {20, 31}, {1, 1}, {9, 2}}) {
        const ImageF out = resample_tent(flat, w, h);
        for (float v : out.pixels) EXPECT_NEAR(v, 0.375f, 1e-6f) << w << "x" << h;
    }
    const ImageF img = random_image(17, 11, seed);
    for (auto [w, h] : {std::pair{5, 3}, {40, 25}, {17, 1}}) {
        const ImageF out = resample_tent(img, w, h);
        ASSERT_EQ(out.width, w);
        ASSERT_EQ(out.height, h);
        for (float v : out.pixels) {
            EXPECT_GE(v, 0.0f);  // non-negative weights summing to one
            EXPECT_LE(v, 1.0f);
        }
    }
}

TEST(ImageResample, RefusesEmptySizes) {
    EXPECT_THROW(resample_tent(ImageF(2, 2), 0, 2), std::invalid_argument);
    EXPECT_THROW(resample_tent(ImageF(), 2, 2), std::invalid_argument);
}

}  // namespace
}  // namespace rtm
