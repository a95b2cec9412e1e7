// run_isolated: fork, the work in the child, its result and its standard error through two files in memory.
#include "mesh/isolated_call.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>
#include <stdexcept>
#include <thread>
#include <utility>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace rtm {
namespace {

// Bytes of address space this process has mapped (the first field of /proc/self/statm, in pages); 0 if unknown.
std::uint64_t mapped_bytes() {
    long pages = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
        std::fclose(f);
    }
    return std::uint64_t(pages) * std::uint64_t(sysconf(_SC_PAGESIZE));
}

// A file in memory that the child writes and the parent reads once the child has ended. (Through a pipe the two
// took turns a pipe's 64 KiB at a time: a 64 MiB result took 0.4 s on a busy 2-core machine.)
struct MemoryFile {
    int fd = -1;
    explicit MemoryFile(const char* name) {
        fd = ::memfd_create(name, MFD_CLOEXEC);
        if (fd < 0) throw std::runtime_error(std::string("memfd_create: ") + std::strerror(errno));
    }
    ~MemoryFile() { ::close(fd); }
    MemoryFile(const MemoryFile&) = delete;
    MemoryFile& operator=(const MemoryFile&) = delete;

    std::string read_all() const {
        std::string s;
        const off_t size = ::lseek(fd, 0, SEEK_END);
        if (size <= 0) return s;
        s.resize(size_t(size));
        size_t at = 0;
        while (at < s.size()) {
            const ssize_t k = ::pread(fd, s.data() + at, s.size() - at, off_t(at));
            if (k < 0 && errno == EINTR) continue;
            if (k <= 0) break;
            at += size_t(k);
        }
        s.resize(at);
        return s;
    }
};

void write_all(int fd, const char* p, size_t n) {
    while (n > 0) {
        const ssize_t k = ::write(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return;  // out of space: the parent finds the result short of its tag's promise or missing
        p += k;
        n -= size_t(k);
    }
}

[[noreturn]] void child(pid_t parent, int out_fd, int log_fd, const std::function<std::string()>& work,
                        const IsolationLimits& limits) {
    // Ends with the parent: a parent killed while its child loops must not leave the loop running.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(1);  // the parent ended before the line above
    ::dup2(log_fd, 2);
    if (limits.address_space > 0) {
        rlimit lim{};
        lim.rlim_cur = lim.rlim_max = rlim_t(mapped_bytes() + limits.address_space);
        setrlimit(RLIMIT_AS, &lim);
    }
    if (limits.cpu_seconds > 0) {
        // The soft limit sends SIGXCPU (which ends the process); the hard one, a second later, SIGKILL. (A child's
        // processor time starts at zero.)
        rlimit lim{};
        lim.rlim_cur = rlim_t(limits.cpu_seconds);
        lim.rlim_max = lim.rlim_cur + 1;
        setrlimit(RLIMIT_CPU, &lim);
    }
    char tag = 'E';
    std::string out;
    try {
        out = work();
        tag = 'O';
    } catch (const std::bad_alloc&) {
        tag = 'M';
        out.clear();
    } catch (const std::exception& e) {
        out = e.what();
    } catch (...) {
        out = "unknown exception";
    }
    write_all(out_fd, &tag, 1);
    write_all(out_fd, out.data(), out.size());
    ::_exit(0);
}

}  // namespace

IsolatedOutcome run_isolated(const std::function<std::string()>& work, const IsolationLimits& limits) {
    const MemoryFile out("rtm-isolated-result"), log("rtm-isolated-stderr");
    std::fflush(nullptr);  // nothing buffered here is written twice (the child ends with _exit, which flushes nothing)
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid == 0) child(parent, out.fd, log.fd, work, limits);
    IsolatedOutcome r;
    int status = 0;
    if (limits.wall_seconds == 0) {
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
    } else {
        // Polled, from 0.1 ms apart up to 20 ms: a short read waits little longer than it takes.
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(limits.wall_seconds);
        auto nap = std::chrono::microseconds(100);
        for (;;) {
            const pid_t w = ::waitpid(pid, &status, WNOHANG);
            if (w == pid || (w < 0 && errno != EINTR)) break;
            if (std::chrono::steady_clock::now() >= deadline) {
                ::kill(pid, SIGKILL);
                while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
                }
                r.timed_out = true;
                break;
            }
            std::this_thread::sleep_for(nap);
            nap = std::min(nap * 2, std::chrono::microseconds(20000));
        }
    }
    r.log = log.read_all();
    if (WIFSIGNALED(status)) {
        r.signal = WTERMSIG(status);
        return r;
    }
    r.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::string got = out.read_all();
    if (r.exit_status != 0 || got.empty()) return r;
    r.status = got[0] == 'O'   ? IsolatedOutcome::Status::ok
               : got[0] == 'M' ? IsolatedOutcome::Status::out_of_memory
                               : IsolatedOutcome::Status::threw;
    got.erase(0, 1);
    r.bytes = std::move(got);
    return r;
}

}  // namespace rtm
