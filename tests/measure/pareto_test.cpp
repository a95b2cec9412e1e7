// The Pareto front (measure/pareto.h): a synthetic set with a known front (duplicates, equal times, equal errors,
// non-finite points), and a random sweep of the fast path against the pair-by-pair definition.
#include "measure/pareto.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/seed.h"

namespace rtm {
namespace {

using Front = std::vector<size_t>;

TEST(Pareto, KnownFront) {
    const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
    const std::vector<ParetoPoint> p = {
        {1.0, 10.0},  // 0: fastest: on the front
        {2.0, 5.0},   // 1: on
        {2.0, 6.0},   // 2: same time as 1, worse error: off
        {3.0, 5.0},   // 3: same error as 1, slower: off
        {4.0, 1.0},   // 4: on
        {4.0, 1.0},   // 5: duplicate of 4: on too
        {5.0, 2.0},   // 6: beaten by 4: off
        {6.0, 0.0},   // 7: exact and slowest: on
        {0.5, inf},   // 8: non-finite error: never on, beats nothing
        {nan, 0.0},   // 9: non-finite time: never on
        {1.0, 10.0},  // 10: duplicate of 0: on
        {7.0, 0.0},   // 11: same error as 7, slower: off
    };
    const Front want = {0, 1, 4, 5, 7, 10};
    EXPECT_EQ(pareto_front(p), want);
    EXPECT_EQ(pareto_front_naive(p), want);
}

TEST(Pareto, EdgeCases) {
    EXPECT_TRUE(pareto_front({}).empty());
    EXPECT_EQ(pareto_front({{3.0, 4.0}}), Front{0});
    // All equal: every point is on the front.
    EXPECT_EQ(pareto_front({{1, 1}, {1, 1}, {1, 1}}), (Front{0, 1, 2}));
    // Equal times only: the lowest error (both copies).
    EXPECT_EQ(pareto_front({{2, 3}, {2, 1}, {2, 2}, {2, 1}}), (Front{1, 3}));
    // Equal errors only: the fastest.
    EXPECT_EQ(pareto_front({{3, 1}, {2, 1}, {5, 1}}), Front{1});
}

TEST(Pareto, MatchesDefinitionOnRandomSets) {
    const uint64_t seed = test::test_seed(22);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> coord(0, 9);  // few distinct values: many ties and duplicates
    for (int trial = 0; trial < 500; ++trial) {
        std::vector<ParetoPoint> p(size_t(1 + trial % 40));
        for (ParetoPoint& q : p) q = {double(coord(rng)), double(coord(rng))};
        ASSERT_EQ(pareto_front(p), pareto_front_naive(p)) << "trial " << trial;
    }
}

}  // namespace
}  // namespace rtm
