// llvmpipe's rasterizer threads pinned one per CPU (texmap/llvmpipe_threads.h) when a context asks for it
// (ContextOptions), read back from /proc.
#include <gtest/gtest.h>

#include <dirent.h>
#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <thread>
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

TEST(LlvmpipeThreads, OnePerCpuAfterAnOffscreenContextAskingForIt) {
    const std::vector<int> cpus = process_cpus();
    if (cpus.size() < 2) GTEST_SKIP() << "the process may use one CPU only";
    auto ctx = GlContext::create_offscreen(64, 64, {.pin_llvmpipe_threads = true});
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

// Pinning changes the whole process: a context pins only when asked to (ContextOptions).
TEST(LlvmpipeThreads, NotPinnedByAContextThatDoesNotAsk) {
    const std::vector<int> cpus = process_cpus();
    if (cpus.size() < 2) GTEST_SKIP() << "the process may use one CPU only";
    auto first = GlContext::create_offscreen(64, 64);
    if (llvmpipe_masks().empty()) GTEST_SKIP() << "no llvmpipe threads: " << first->describe();
    // Unpin them by hand (an earlier test's context may have pinned them), then make contexts of both kinds.
    cpu_set_t all;
    ASSERT_EQ(sched_getaffinity(0, sizeof all, &all), 0);
    for (const auto& [tid, k] : llvmpipe_threads()) ASSERT_EQ(sched_setaffinity(tid, sizeof all, &all), 0) << k;
    first.reset();
    auto plain = GlContext::create_offscreen(32, 32);
    for (const auto& [k, m] : llvmpipe_masks()) EXPECT_EQ(m, cpus) << "llvmpipe-" << k;
    plain.reset();
    auto pinned = GlContext::create_offscreen(32, 32, {.pin_llvmpipe_threads = true});
    for (const auto& [k, m] : llvmpipe_masks())
        EXPECT_EQ(m, std::vector<int>{cpus[size_t(k) % cpus.size()]}) << "llvmpipe-" << k;
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

// The race the wait closes: a thread started after `before` that names itself "llvmpipe-<k>" only some
// milliseconds later (as llvmpipe's threads do from inside, late when the host is busy) is still pinned. Without the
// wait it is missed: spread returns at once, the thread still bearing this thread's name. LP_NUM_THREADS (read by
// the wait, and by Mesa only when its first context is made) says more llvmpipe threads are due than an earlier
// test's context may have left.
TEST(LlvmpipeThreads, WaitsForNewThreadsToNameThemselves) {
    const std::vector<int> cpus = process_cpus();
    if (cpus.size() < 2) GTEST_SKIP() << "the process may use one CPU only";
    const char* had = std::getenv("LP_NUM_THREADS");
    const std::string saved = had ? had : "";
    ASSERT_EQ(setenv("LP_NUM_THREADS", "64", 1), 0);
    const std::vector<int> before = process_threads();
    std::atomic<bool> named{false}, done{false};
    std::atomic<int> tid{0};
    std::thread t([&] {
        tid = int(gettid());
        std::this_thread::sleep_for(std::chrono::milliseconds(10));  // a fifth of kWait
        pthread_setname_np(pthread_self(), "llvmpipe-7");
        named = true;
        while (!done) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    });
    while (tid == 0) std::this_thread::yield();
    const int pinned = spread_llvmpipe_threads(before);
    if (had)
        setenv("LP_NUM_THREADS", saved.c_str(), 1);
    else
        unsetenv("LP_NUM_THREADS");
    EXPECT_TRUE(named);
    EXPECT_GE(pinned, 1);
    cpu_set_t s;
    ASSERT_EQ(sched_getaffinity(pid_t(tid.load()), sizeof s, &s), 0);
    EXPECT_EQ(cpus_of(s), std::vector<int>{cpus[7 % cpus.size()]});
    done = true;
    t.join();
}

}  // namespace
}  // namespace rtm
