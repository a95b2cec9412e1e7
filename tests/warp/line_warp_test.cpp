#include "warp/line_warp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace rtm {
namespace {

struct Line {
    std::vector<float> pos, attr;
    std::vector<Rgba8> color;
    std::vector<uint8_t> valid;
    explicit Line(int n) : pos(n), attr(n), color(n), valid(n, 1) {
        for (int k = 0; k < n; ++k) {
            pos[k] = k + 0.5f;
            attr[k] = float(k);
            color[k] = {uint8_t(10 * k), uint8_t(255 - 10 * k), uint8_t(k), 255};
        }
    }
    std::vector<Rgba8> warp(int split, int nout = -1, std::vector<float>* attr_out = nullptr) {
        const int n = int(pos.size());
        if (nout < 0) nout = n;
        std::vector<Rgba8> out(nout);
        std::vector<float> a(nout, -1);
        warp_line<float>({n, pos.data(), color.data(), attr.data(), valid.data()}, split,
                         {nout, out.data(), 1, a.data(), 1});
        if (attr_out) *attr_out = a;
        return out;
    }
};

TEST(SplitIndex, CentresBelowTheSplitGoFirst) {
    EXPECT_EQ(split_index(-3.0, 10), 0);
    EXPECT_EQ(split_index(0.5, 10), 0);  // on centre 0: sample 0 is in the second part
    EXPECT_EQ(split_index(0.51, 10), 1);
    EXPECT_EQ(split_index(1.0, 10), 1);  // on the boundary between 0 and 1
    EXPECT_EQ(split_index(5.5, 10), 5);
    EXPECT_EQ(split_index(10.0, 10), 10);
    EXPECT_EQ(split_index(1e30, 10), 10);
    EXPECT_EQ(split_index(std::nan(""), 10), 0);
}

TEST(WarpLine, IdentityCopiesEveryColourExactlyForEverySplit) {
    for (int split = 0; split <= 12; ++split) {
        Line l(12);
        std::vector<float> a;
        const auto out = l.warp(split, -1, &a);
        for (int k = 0; k < 12; ++k) {
            Rgba8 c = l.color[k];
            EXPECT_EQ(out[k], c) << "split " << split << " k " << k;
            EXPECT_EQ(a[k], float(k));
        }
    }
}

TEST(WarpLine, SpanInterpolatesAtPixelCentres) {
    Line l(2);
    l.pos = {0.5f, 4.5f};  // stretched over 4 pixels
    l.color = {{0, 0, 0, 255}, {200, 100, 40, 255}};
    const auto out = l.warp(2, 6);
    EXPECT_EQ(out[0], (Rgba8{0, 0, 0, 255}));
    EXPECT_EQ(out[1], (Rgba8{50, 25, 10, 255}));
    EXPECT_EQ(out[2], (Rgba8{100, 50, 20, 255}));
    EXPECT_EQ(out[3], (Rgba8{150, 75, 30, 255}));
    EXPECT_EQ(out[4], (Rgba8{200, 100, 40, 255}));
    EXPECT_EQ(out[5].a, 0);
}

TEST(WarpLine, SeamAtTheSplitIsFilled) {
    // Two halves moving apart around the split (as texels standing out do around the epipole).
    Line l(4);
    l.pos = {0.5f, 1.0f, 5.0f, 5.5f};
    const auto out = l.warp(2, 6);
    for (int x = 0; x < 6; ++x) EXPECT_EQ(out[x].a, 255) << x;
}

TEST(WarpLine, NoSpanAcrossInvalidSamples) {
    Line l(5);
    l.pos = {0.5f, 2.5f, 4.5f, 6.5f, 8.5f};
    l.valid[2] = 0;
    const auto out = l.warp(5, 10);
    EXPECT_EQ(out[3].a, 0);  // between 2.5 and 6.5 nothing, the middle sample is empty
    EXPECT_EQ(out[5].a, 0);
    EXPECT_EQ(out[6], l.color[3]);  // sample 3 starts a new run: written at floor(6.5)
}

TEST(WarpLine, LaterSamplesOverwriteEarlierOnes) {
    // Left part folds back: sample 2 lands on top of sample 0; it is nearer the split, so it wins.
    Line l(3);
    l.pos = {0.5f, 1.5f, 0.5f};
    const auto out = l.warp(3, 3);
    EXPECT_EQ(out[0], l.color[2]);
}

TEST(WarpLine, OutOfRangeAndHugePositionsAreClipped) {
    Line l(3);
    l.pos = {-1e30f, 1.5f, 1e30f};
    const auto out = l.warp(1, 3);
    for (int x = 0; x < 3; ++x) EXPECT_EQ(out[x].a, 255) << x;
    Line m(2);
    m.pos = {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
    const auto o2 = m.warp(1, 3);  // must not crash or hang
    (void)o2;
}

TEST(WarpLine, NegativeStrideWritesBackwards) {
    Line l(3);
    std::vector<Rgba8> out(3);
    warp_line<float>({3, l.pos.data(), l.color.data(), nullptr, l.valid.data()}, 1, {3, &out[2], -1, nullptr, 0});
    EXPECT_EQ(out[2], l.color[0]);
    EXPECT_EQ(out[0], l.color[2]);
}

}  // namespace
}  // namespace rtm
