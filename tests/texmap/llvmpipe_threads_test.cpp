// llvmpipe's rasterizer threads pinned one per CPU (texmap/llvmpipe_threads.h), read back from /proc.
#include <gtest/gtest.h>

#include <dirent.h>
#include <sched.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "texmap/gl_context.h"
#include "texmap/llvmpipe_threads.h"

namespace rtm {
namespace {

// The CPUs in a mask, in order.
std::vector<int> cpus_of(const cpu_set_t& s) {
    std::vector<int> v;
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &s)) v.push_back(c);
    return v;
}

// This process's llvmpipe threads: (thread id, k of "llvmpipe-<k>"), read from /proc independently of the code
// under test.
std::vector<std::pair<int, int>> llvmpipe_threads() {
    std::vector<std::pair<int, int>> v;
    DIR* dir = opendir("/proc/self/task");
    if (!dir) return v;
    while (const dirent* e = readdir(dir)) {
        if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
        std::ifstream f(std::string("/proc/self/task/") + e->d_name + "/comm");
        std::string comm;
        if (std::getline(f, comm) && comm.rfind("llvmpipe-", 0) == 0)
            v.emplace_back(std::atoi(e->d_name), std::atoi(comm.c_str() + 9));
    }
    closedir(dir);
    return v;
}

// The CPUs each llvmpipe thread may run on, by k.
std::multimap<int, std::vector<int>> llvmpipe_masks() {
    std::multimap<int, std::vector<int>> m;
    for (const auto& [tid, k] : llvmpipe_threads()) {
        cpu_set_t s;
        if (sched_getaffinity(tid, sizeof s, &s) == 0) m.emplace(k, cpus_of(s));
    }
    return m;
}

std::vector<int> process_cpus() {
    cpu_set_t s;
    EXPECT_EQ(sched_getaffinity(0, sizeof s, &s), 0);
    return cpus_of(s);
}

TEST(LlvmpipeThreads, OnePerCpuAfterAnOffscreenContextIsCreated) {
    const std::vector<int> cpus = process_cpus();
    if (cpus.size() < 2) GTEST_SKIP() << "the process may use one CPU only";
    auto ctx = GlContext::create_offscreen(64, 64);
    const auto masks = llvmpipe_masks();
    if (masks.empty()) GTEST_SKIP() << "no llvmpipe threads: " << ctx->describe();
    for (const auto& [k, m] : masks) {
        SCOPED_TRACE("llvmpipe-" + std::to_string(k));
        EXPECT_EQ(m, std::vector<int>{cpus[size_t(k) % cpus.size()]});
    }
    // Pinning again finds and pins the same threads.
    EXPECT_EQ(spread_llvmpipe_threads(), int(masks.size()));
    EXPECT_EQ(llvmpipe_masks(), masks);
}

TEST(LlvmpipeThreads, EnvironmentTurnsPinningOff) {
    const std::vector<int> cpus = process_cpus();
    if (cpus.size() < 2) GTEST_SKIP() << "the process may use one CPU only";
    auto ctx = GlContext::create_offscreen(64, 64);
    if (llvmpipe_masks().empty()) GTEST_SKIP() << "no llvmpipe threads: " << ctx->describe();
    // Unpin them by hand (they may be pinned by this context or an earlier test's), then pin with the variable
    // set, then without.
    cpu_set_t all;
    ASSERT_EQ(sched_getaffinity(0, sizeof all, &all), 0);
    for (const auto& [tid, k] : llvmpipe_threads()) ASSERT_EQ(sched_setaffinity(tid, sizeof all, &all), 0) << k;
    ASSERT_EQ(setenv("RTM_NO_LLVMPIPE_PINNING", "1", 1), 0);
    EXPECT_EQ(spread_llvmpipe_threads(), 0);
    const auto masks = llvmpipe_masks();
    for (const auto& [k, m] : masks) EXPECT_EQ(m, cpus) << "llvmpipe-" << k;
    ASSERT_EQ(unsetenv("RTM_NO_LLVMPIPE_PINNING"), 0);
    EXPECT_EQ(spread_llvmpipe_threads(), int(masks.size()));
    for (const auto& [k, m] : llvmpipe_masks()) EXPECT_EQ(m, std::vector<int>{cpus[size_t(k) % cpus.size()]});
}

}  // namespace
}  // namespace rtm
