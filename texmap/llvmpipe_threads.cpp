// llvmpipe's rasterizer threads, one per CPU (see llvmpipe_threads.h).
#include "texmap/llvmpipe_threads.h"

#include <dirent.h>
#include <sched.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace rtm {

int spread_llvmpipe_threads() {
    if (std::getenv("RTM_NO_LLVMPIPE_PINNING")) return 0;
    cpu_set_t allowed;
    if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return 0;
    std::vector<int> cpus;
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
    if (cpus.size() < 2) return 0;
    DIR* dir = opendir("/proc/self/task");
    if (!dir) return 0;
    const std::string prefix = "llvmpipe-";
    int pinned = 0;
    while (const dirent* e = readdir(dir)) {
        if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
        std::ifstream f(std::string("/proc/self/task/") + e->d_name + "/comm");
        std::string comm;
        if (!std::getline(f, comm) || comm.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string k = comm.substr(prefix.size());
        if (k.empty() || k.find_first_not_of("0123456789") != std::string::npos || k.size() > 6) continue;
        cpu_set_t one;
        CPU_ZERO(&one);
        CPU_SET(cpus[size_t(std::stoi(k)) % cpus.size()], &one);
        pinned += sched_setaffinity(pid_t(std::atoi(e->d_name)), sizeof one, &one) == 0;
    }
    closedir(dir);
    return pinned;
}

}  // namespace rtm
