#include "warp/task_arenas.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

namespace rtm {

// Made once: an arena created, used for one parallel_for and destroyed costs 8 to 150 us here, a cached one 1 us (a
// 256^2 pre-warp takes about 300 us).
int arena_threads(int threads) {
    const auto limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    return int(std::clamp<size_t>(size_t(std::max(threads, 1)), 1, std::max<size_t>(limit, 1)));
}

tbb::task_arena& task_arena_for(int threads) {
    threads = arena_threads(threads);
    static std::mutex mu;
    static std::map<int, std::unique_ptr<tbb::task_arena>> arenas;
    const std::lock_guard<std::mutex> lock(mu);
    std::unique_ptr<tbb::task_arena>& a = arenas[threads];
    if (!a) a = std::make_unique<tbb::task_arena>(threads);
    return *a;
}

}  // namespace rtm
