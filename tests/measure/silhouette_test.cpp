// The silhouette error (measure/silhouette.h): a disc against itself, grown by k pixels and shifted by k pixels,
// the empty cases, and the fast distance transform against the brute-force one on random masks.
#include "measure/silhouette.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "common/seed.h"

namespace rtm {
namespace {

const Rgba8 kBg{0, 0, 0, 255};

ImageRGBA8 disc(int size, double cx, double cy, double r) {
    ImageRGBA8 img(size, size, kBg);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            if (std::hypot(x + 0.5 - cx, y + 0.5 - cy) <= r) img.at(x, y) = {200, 100, 50, 255};
    return img;
}

// The mean distance from a circle of radius r shifted by k to the unshifted one, over the angle: the continuous
// value the pixel measure approximates.
double shifted_circle_mean(double r, double k) {
    const int n = 100000;
    double s = 0;
    for (int i = 0; i < n; ++i) {
        const double t = 2 * std::numbers::pi * (i + 0.5) / n;
        s += std::abs(std::hypot(r * std::cos(t) + k, r * std::sin(t)) - r);
    }
    return s / n;
}

TEST(Silhouette, IdenticalIsZero) {
    const ImageRGBA8 a = disc(64, 32, 32, 20);
    EXPECT_EQ(silhouette_error(a, a), 0.0);
}

TEST(Silhouette, DiscShiftedByKPixels) {
    // Tolerance 0.35 px: both outlines are rasterized (pixel centres inside the circle), so each outline pixel sits
    // up to about half a pixel inside the true circle, differently on the two discs; the mean over ~120 outline
    // pixels moves by a fraction of that.
    const double r = 40;
    const ImageRGBA8 ref = disc(128, 64, 64, r);
    for (int k : {1, 2, 4, 8}) {
        const ImageRGBA8 test = disc(128, 64 + k, 64, r);
        const double want = shifted_circle_mean(r, k);  // about 2k/pi
        EXPECT_NEAR(silhouette_error(ref, test), want, 0.35) << "k = " << k;
        EXPECT_NEAR(silhouette_error(test, ref), want, 0.35) << "k = " << k;
    }
}

TEST(Silhouette, DiscGrownByKPixels) {
    // Every outline pixel of the larger disc is k from the smaller one's outline; same rasterization tolerance.
    const ImageRGBA8 ref = disc(128, 64, 64, 30);
    for (int k : {1, 3, 6}) EXPECT_NEAR(silhouette_error(ref, disc(128, 64, 64, 30 + k)), k, 0.35) << "k = " << k;
}

TEST(Silhouette, EmptyImages) {
    const ImageRGBA8 empty(16, 16, kBg);
    EXPECT_EQ(silhouette_error(empty, empty), 0.0);
    EXPECT_TRUE(std::isnan(silhouette_error(empty, disc(16, 8, 8, 4))));
    EXPECT_TRUE(std::isnan(silhouette_error(disc(16, 8, 8, 4), empty)));
    EXPECT_THROW(silhouette_error(empty, ImageRGBA8(8, 16, kBg)), std::invalid_argument);
}

TEST(Silhouette, MaskOfASquare) {
    // A 3x3 covered square: the ring of 8 is the outline, the centre is not; the image border counts as uncovered.
    ImageRGBA8 img(5, 5, kBg);
    for (int y = 1; y <= 3; ++y)
        for (int x = 1; x <= 3; ++x) img.at(x, y) = {9, 9, 9, 255};
    const auto m = silhouette_mask(img);
    int n = 0;
    for (unsigned char c : m) n += c;
    EXPECT_EQ(n, 8);
    EXPECT_EQ(m[2 * 5 + 2], 0);
    ImageRGBA8 full(3, 3, {9, 9, 9, 255});
    const auto mf = silhouette_mask(full);
    EXPECT_EQ(mf[4], 0);  // the centre of a full image
    EXPECT_EQ(mf[0], 1);  // its border
}

TEST(Silhouette, DistanceTransformMatchesBruteForce) {
    const uint64_t seed = test::test_seed(2222);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    for (int trial = 0; trial < 40; ++trial) {
        const int w = 1 + int(rng() % 23), h = 1 + int(rng() % 19);
        const double density = (trial % 4 == 0) ? 0.0 : 0.02 + 0.3 * double(rng() % 100) / 100.0;
        std::vector<unsigned char> mask(size_t(w) * size_t(h));
        for (auto& c : mask) c = double(rng() % 1000) / 1000.0 < density;
        const auto fast = squared_distance_transform(mask, w, h), slow = squared_distance_transform_naive(mask, w, h);
        ASSERT_EQ(fast, slow) << "trial " << trial << " (" << w << "x" << h << ")";  // exact: integer sums
    }
}

}  // namespace
}  // namespace rtm
