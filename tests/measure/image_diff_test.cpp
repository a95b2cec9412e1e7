// Error measurement (measure/image_diff.h): exact figures on small images, coverage, heat map colours.
#include "measure/image_diff.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rtm {
namespace {

const Rgba8 kBg{0, 0, 0, 255};

TEST(ImageDiff, IdenticalImages) {
    ImageRGBA8 a(5, 4, kBg);
    a.at(1, 1) = {10, 20, 30, 255};
    a.at(4, 3) = {255, 255, 255, 255};
    a.at(2, 0) = {0, 0, 1, 255};
    ImageRGBA8 heat;
    const DiffResult d = diff_images(a, a, &heat);
    EXPECT_EQ(d.rmse, 0.0);
    EXPECT_TRUE(std::isinf(d.psnr) && d.psnr > 0) << d.to_string();
    EXPECT_EQ(d.iou, 1.0);
    EXPECT_EQ(d.both, 3);
    EXPECT_EQ(d.either, 3);
    EXPECT_EQ(d.only_ref + d.only_test, 0);
    EXPECT_EQ(d.max_error, 0.0);
    EXPECT_EQ(heat.at(1, 1), (Rgba8{64, 64, 64, 255}));  // error 0: dark grey
    EXPECT_EQ(heat.at(0, 0), kBg);                       // neither covered: black
}

TEST(ImageDiff, KnownDifferences) {
    // Pixel 0: both covered, error (3, 4, 0) -> 5. Pixel 1: only the test. Pixel 2: only the reference.
    // Pixel 3: both, equal. Pixel 4: both, error (0, 0, 100) -> 100. Pixel 5: neither.
    ImageRGBA8 ref(3, 2, kBg), test(3, 2, kBg);
    ref.pixels = {{10, 20, 30, 255}, kBg, {100, 100, 100, 255}, {50, 50, 50, 255}, {0, 0, 200, 255}, kBg};
    test.pixels = {{13, 24, 30, 255}, {5, 5, 5, 255}, kBg, {50, 50, 50, 255}, {0, 0, 100, 255}, kBg};
    ImageRGBA8 heat;
    const DiffResult d = diff_images(ref, test, &heat);
    EXPECT_EQ(d.both, 3);
    EXPECT_EQ(d.either, 5);
    EXPECT_EQ(d.only_ref, 1);
    EXPECT_EQ(d.only_test, 1);
    EXPECT_EQ(d.iou, 3.0 / 5.0);
    const double rmse = std::sqrt((25.0 + 0.0 + 10000.0) / (3.0 * 3.0));
    EXPECT_EQ(d.rmse, rmse);
    // Within 4 ulps: the compiler folds the expected log10 at compile time (correctly rounded), the library's
    // log10 at run time may differ in the last bit.
    EXPECT_DOUBLE_EQ(d.psnr, 20.0 * std::log10(255.0 / rmse));
    EXPECT_EQ(d.max_error, 100.0);
    // Heat: error 5 -> 64 + 191*5/64 = 78.9 -> 79 for red and green, 64 - 64*5/64 = 59 for blue.
    EXPECT_EQ(heat.at(0, 0), (Rgba8{79, 79, 59, 255}));
    EXPECT_EQ(heat.at(1, 0), (Rgba8{255, 0, 0, 255}));  // only the test: red
    EXPECT_EQ(heat.at(2, 0), (Rgba8{0, 0, 255, 255}));  // only the reference: blue
    EXPECT_EQ(heat.at(0, 1), (Rgba8{64, 64, 64, 255}));
    EXPECT_EQ(heat.at(1, 1), (Rgba8{255, 255, 0, 255}));  // error >= 64: bright yellow
    EXPECT_EQ(heat.at(2, 1), kBg);
}

TEST(ImageDiff, CoverageIgnoresAlphaOfCoveredPixelsButNotTransparency) {
    EXPECT_FALSE(covered(kBg));
    EXPECT_FALSE(covered({10, 20, 30, 0}));  // transparent (an empty texel of a pre-warped texture)
    EXPECT_TRUE(covered({0, 0, 0, 128}));    // not the opaque-black background
    EXPECT_TRUE(covered({1, 0, 0, 255}));
    ImageRGBA8 ref(2, 1, kBg), test(2, 1, kBg);
    ref.pixels = {{10, 10, 10, 255}, {20, 20, 20, 255}};
    test.pixels = {{10, 10, 10, 7}, {20, 20, 20, 0}};
    const DiffResult d = diff_images(ref, test);
    EXPECT_EQ(d.both, 1);
    EXPECT_EQ(d.only_ref, 1);
    EXPECT_EQ(d.rmse, 0.0);  // alpha is not part of the error
}

TEST(ImageDiff, EmptyAndDisjointCoverage) {
    const ImageRGBA8 empty(4, 4, kBg);
    const DiffResult e = diff_images(empty, empty);
    EXPECT_EQ(e.iou, 1.0);
    EXPECT_EQ(e.rmse, 0.0);
    EXPECT_TRUE(std::isinf(e.psnr));
    ImageRGBA8 a = empty, b = empty;
    a.at(0, 0) = {9, 9, 9, 255};
    b.at(3, 3) = {9, 9, 9, 255};
    const DiffResult d = diff_images(a, b);
    EXPECT_EQ(d.iou, 0.0);
    EXPECT_EQ(d.either, 2);
    EXPECT_TRUE(std::isnan(d.rmse));  // nothing to compare colours over
    EXPECT_TRUE(std::isnan(d.psnr));
    EXPECT_FALSE(d.psnr > 30.0);
}

TEST(ImageDiff, SizeMismatchNamesBothSizes) {
    try {
        diff_images(ImageRGBA8(3, 2), ImageRGBA8(2, 3));
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("3x2"), std::string::npos) << msg;
        EXPECT_NE(msg.find("2x3"), std::string::npos) << msg;
    }
}

}  // namespace
}  // namespace rtm
