// The Pareto front of (time, error) points, both minimised: the points no other point beats in one coordinate
// without losing in the other. Used by `rtm compare` to mark the methods worth their cost.
#pragma once

#include <cstddef>
#include <vector>

namespace rtm {

struct ParetoPoint {
    double time = 0, error = 0;
};

// Indices (ascending) of the points on the front. A point is on it when no other point has time <= its time and
// error <= its error with at least one of them strictly smaller. Duplicates of a front point are all on it (none
// beats the other). Points with a non-finite coordinate are never on the front and beat nothing. O(n log n).
std::vector<size_t> pareto_front(const std::vector<ParetoPoint>& points);

// The definition applied pair by pair, O(n^2): the reference the fast path is tested against.
std::vector<size_t> pareto_front_naive(const std::vector<ParetoPoint>& points);

}  // namespace rtm
