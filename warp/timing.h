// Wall-clock timing and the summary the measuring commands report: one definition of each.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace rtm {

using Clock = std::chrono::steady_clock;

inline double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The middle value; for an even count the mean of the two middle values; 0 for none.
inline double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const size_t n = v.size();
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(n / 2), v.end());
    const double upper = v[n / 2];
    if (n % 2) return upper;
    return 0.5 * (*std::max_element(v.begin(), v.begin() + std::ptrdiff_t(n / 2)) + upper);
}

}  // namespace rtm
