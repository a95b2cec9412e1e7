// llvmpipe's rasterizer threads, one per CPU (see llvmpipe_threads.h).
#include "texmap/llvmpipe_threads.h"

#include <dirent.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace rtm {

namespace {

// Each thread of this process with its name (/proc/self/task/<tid>/comm).
std::vector<std::pair<int, std::string>> named_threads() {
    std::vector<std::pair<int, std::string>> v;
    DIR* dir = opendir("/proc/self/task");
    if (!dir) return v;
    while (const dirent* e = readdir(dir)) {
        if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
        std::ifstream f(std::string("/proc/self/task/") + e->d_name + "/comm");
        std::string comm;
        if (std::getline(f, comm)) v.emplace_back(std::atoi(e->d_name), comm);
    }
    closedir(dir);
    return v;
}

}  // namespace

std::vector<int> process_threads() {
    std::vector<int> ids;
    for (const auto& [tid, comm] : named_threads()) ids.push_back(tid);
    std::sort(ids.begin(), ids.end());
    return ids;
}

int spread_llvmpipe_threads(const std::vector<int>& before) {
    if (std::getenv("RTM_NO_LLVMPIPE_PINNING")) return 0;
    cpu_set_t allowed;
    if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return 0;
    std::vector<int> cpus;
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
    if (cpus.size() < 2) return 0;
    const std::string prefix = "llvmpipe-";
    std::vector<std::pair<int, std::string>> threads = named_threads();
    if (!before.empty()) {
        // A thread started since `before` carries its creator's (this thread's) name until it has run far enough
        // to name itself; wait for that, up to kWait, unless llvmpipe's threads are all there already (llvmpipe
        // starts one per online CPU, or LP_NUM_THREADS; Mesa also starts two threads that keep their creator's
        // name for good, with the first context).
        const char* env = std::getenv("LP_NUM_THREADS");
        const long expected = env ? std::atol(env) : sysconf(_SC_NPROCESSORS_ONLN);
        auto found = [&] {
            long n = 0;
            for (const auto& [tid, comm] : threads) n += comm.compare(0, prefix.size(), prefix) == 0;
            return n;
        };
        std::string self;
        std::getline(std::ifstream("/proc/thread-self/comm"), self);
        std::vector<int> sorted = before;
        std::sort(sorted.begin(), sorted.end());
        const auto deadline = std::chrono::steady_clock::now() + kWait;
        auto unnamed = [&] {
            for (const auto& [tid, comm] : threads)
                if (comm == self && !std::binary_search(sorted.begin(), sorted.end(), tid)) return true;
            return false;
        };
        while (found() < expected && unnamed() && std::chrono::steady_clock::now() < deadline) {
            std::this_thread::sleep_for(std::chrono::microseconds(100));
            threads = named_threads();
        }
    }
    int pinned = 0;
    for (const auto& [tid, comm] : threads) {
        if (comm.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string k = comm.substr(prefix.size());
        if (k.empty() || k.find_first_not_of("0123456789") != std::string::npos || k.size() > 6) continue;
        cpu_set_t one;
        CPU_ZERO(&one);
        CPU_SET(cpus[size_t(std::stoi(k)) % cpus.size()], &one);
        pinned += sched_setaffinity(pid_t(tid), sizeof one, &one) == 0;
    }
    return pinned;
}

}  // namespace rtm
