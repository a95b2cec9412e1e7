// SharedArray (warp/shared_array.h): copies read one allocation until one of them is edited, and an edit never
// shows in another copy; and ReliefTexture's copies share their texels the same way.
#include "warp/shared_array.h"

#include <gtest/gtest.h>

#include <vector>

#include "test_util.h"
#include "warp/relief_texture.h"

namespace rtm {
namespace {

TEST(SharedArray, CopiesShareUntilOneIsEdited) {
    SharedArray<int> a(std::vector<int>{1, 2, 3});
    SharedArray<int> b = a;
    EXPECT_TRUE(b.shares_storage_with(a));
    EXPECT_EQ(b.data(), a.data());
    b.edit()[1] = 20;  // b gets its own array first
    EXPECT_FALSE(b.shares_storage_with(a));
    EXPECT_EQ(a.vector(), (std::vector<int>{1, 2, 3}));
    EXPECT_EQ(b.vector(), (std::vector<int>{1, 20, 3}));
    // The only holder edits in place.
    const int* before = a.data();
    a.edit()[0] = 10;
    EXPECT_EQ(a.data(), before);
    EXPECT_EQ(a[0], 10);
}

TEST(SharedArray, EmptyAndComparison) {
    SharedArray<float> e;
    EXPECT_TRUE(e.empty());
    EXPECT_EQ(e.size(), 0u);
    EXPECT_EQ(e.begin(), e.end());
    EXPECT_FALSE(e.shares_storage_with(SharedArray<float>()));  // two empty arrays share nothing
    EXPECT_EQ(e, SharedArray<float>(std::vector<float>{}));
    SharedArray<float> x(std::vector<float>{1.5f}), y(std::vector<float>{1.5f});
    EXPECT_EQ(x, y);  // equal contents, separate allocations
    EXPECT_FALSE(x.shares_storage_with(y));
    y.edit().push_back(2.0f);
    EXPECT_NE(x, y);
    y.clear();
    EXPECT_TRUE(y.empty());
    e.edit().push_back(4.0f);  // an empty array edits into a fresh one
    EXPECT_EQ(e.size(), 1u);
}

TEST(SharedArray, ReliefCopiesShareTexelsUntilChanged) {
    const ReliefTexture t = test::make_test_relief(9, 7, 0.0, 1.0, [](int x, int r) { return (x * r) / 60.0; });
    ReliefTexture c = t;
    EXPECT_TRUE(c.texels.shares_storage_with(t.texels));
    EXPECT_TRUE(c.displacement.shares_storage_with(t.displacement));
    mark_discontinuities(c, 0.05);  // new marks: the texels stay shared
    EXPECT_TRUE(c.texels.shares_storage_with(t.texels));
    EXPECT_TRUE(t.breaks.empty());
    c.texels.edit()[0].q = kEmptyIndex;
    EXPECT_FALSE(c.texels.shares_storage_with(t.texels));
    EXPECT_NE(t.texel(0, 0).q, kEmptyIndex);
    EXPECT_TRUE(c.displacement.shares_storage_with(t.displacement));
}

}  // namespace
}  // namespace rtm
