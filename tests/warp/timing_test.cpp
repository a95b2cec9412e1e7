// The one median every measuring command reports (warp/timing.h): exact on small sets.
#include "warp/timing.h"

#include <gtest/gtest.h>

namespace rtm {
namespace {

TEST(Median, OddCountIsTheMiddleValue) {
    EXPECT_EQ(median({5.0}), 5.0);
    EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
    EXPECT_EQ(median({9.0, 1.0, 7.0, 3.0, 5.0}), 5.0);
}

TEST(Median, EvenCountIsTheMeanOfTheTwoMiddleValues) {
    EXPECT_EQ(median({1.0, 2.0}), 1.5);
    EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
    EXPECT_EQ(median({10.0, 0.0, 0.0, 10.0}), 5.0);
    EXPECT_EQ(median({2.0, 2.0, 2.0, 8.0}), 2.0);
}

TEST(Median, EmptyIsZero) { EXPECT_EQ(median({}), 0.0); }

}  // namespace
}  // namespace rtm
