#include "measure/pareto.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtm {

namespace {

bool finite(const ParetoPoint& p) { return std::isfinite(p.time) && std::isfinite(p.error); }

}  // namespace

std::vector<size_t> pareto_front(const std::vector<ParetoPoint>& points) {
    std::vector<size_t> order;
    for (size_t i = 0; i < points.size(); ++i)
        if (finite(points[i])) order.push_back(i);
    // By time, then error: a point is on the front when its error is below every error seen at a strictly smaller
    // time, and it is the smallest error of its own time (equal times: only the lowest error survives, with its
    // duplicates).
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        const ParetoPoint &p = points[a], &q = points[b];
        return p.time != q.time ? p.time < q.time : p.error != q.error ? p.error < q.error : a < b;
    });
    std::vector<size_t> front;
    double best = std::numeric_limits<double>::infinity();  // lowest error at a strictly smaller time
    for (size_t k = 0; k < order.size();) {
        size_t end = k;  // [k, end): one time
        while (end < order.size() && points[order[end]].time == points[order[k]].time) ++end;
        const double lowest = points[order[k]].error;
        if (lowest < best)
            for (size_t j = k; j < end && points[order[j]].error == lowest; ++j) front.push_back(order[j]);
        best = std::min(best, lowest);
        k = end;
    }
    std::sort(front.begin(), front.end());
    return front;
}

std::vector<size_t> pareto_front_naive(const std::vector<ParetoPoint>& points) {
    std::vector<size_t> front;
    for (size_t i = 0; i < points.size(); ++i) {
        if (!finite(points[i])) continue;
        bool beaten = false;
        for (size_t j = 0; j < points.size() && !beaten; ++j) {
            if (j == i || !finite(points[j])) continue;
            const ParetoPoint &p = points[i], &q = points[j];
            beaten = q.time <= p.time && q.error <= p.error && (q.time < p.time || q.error < p.error);
        }
        if (!beaten) front.push_back(i);
    }
    return front;
}

}  // namespace rtm
