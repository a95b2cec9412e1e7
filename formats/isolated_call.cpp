// run_isolated: fork, the work in the child, its result and its standard error through two files in memory.
#include "formats/isolated_call.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <utility>

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "formats/image_io.h"

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

    // The whole file, mapped read-only (its pages already in memory: mapped at once); an empty view if it is empty
    // or cannot be mapped.
    std::pair<std::shared_ptr<const void>, std::string_view> map() const {
        const off_t size = ::lseek(fd, 0, SEEK_END);
        if (size <= 0) return {};
        void* p = ::mmap(nullptr, size_t(size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (p == MAP_FAILED) return {};
        std::shared_ptr<const void> owner(p, [n = size_t(size)](const void* q) { ::munmap(const_cast<void*>(q), n); });
        return {std::move(owner), std::string_view(static_cast<const char*>(p), size_t(size))};
    }
};

// False when the file cannot grow (out of space: the child's memory cap reached).
bool write_all(int fd, const char* p, size_t n) {
    while (n > 0) {
        const ssize_t k = ::write(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return false;
        p += k;
        n -= size_t(k);
    }
    return true;
}

[[noreturn]] void child(pid_t parent, int out_fd, int log_fd, const std::function<void(const ResultWriter&)>& work,
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
    // The result file: a tag byte (O ok, E threw, M out of memory), then what the work wrote or the message. The tag
    // is written last, over a placeholder: a child that dies meanwhile leaves none of the three.
    char tag = 'E';
    std::string message;
    if (!write_all(out_fd, "?", 1)) ::_exit(1);
    try {
        work(ResultWriter(out_fd));
        tag = 'O';
    } catch (const std::bad_alloc&) {
        tag = 'M';
    } catch (const std::exception& e) {
        message = e.what();
    } catch (...) {
        message = "unknown exception";
    }
    if (tag != 'O') {
        if (::ftruncate(out_fd, 1) != 0 || ::lseek(out_fd, 1, SEEK_SET) != 1) ::_exit(1);
        write_all(out_fd, message.data(), message.size());
    }
    if (::pwrite(out_fd, &tag, 1, 0) != 1) ::_exit(1);
    ::_exit(0);
}

}  // namespace

void ResultWriter::write(const void* data, std::size_t bytes) const {
    if (!write_all(fd_, static_cast<const char*>(data), bytes)) throw std::bad_alloc();
}

IsolatedOutcome run_isolated(const std::function<std::string()>& work, const IsolationLimits& limits) {
    return run_isolated(
        [&](const ResultWriter& out) {
            const std::string s = work();
            out.write(s.data(), s.size());
        },
        limits);
}

IsolatedOutcome run_isolated(const std::function<void(const ResultWriter&)>& work, const IsolationLimits& limits) {
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
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(limits.wall_seconds);
        const auto kill_and_reap = [&] {
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            r.timed_out = true;
        };
        // A process file descriptor becomes readable when the child ends: the wait ends then, not at a polling step.
        // Without one (Linux before 5.3), polled from 0.1 ms apart up to 20 ms.
        if (const int pidfd = int(::syscall(SYS_pidfd_open, pid, 0)); pidfd >= 0) {
            for (;;) {
                const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                    deadline - std::chrono::steady_clock::now());
                pollfd p{pidfd, POLLIN, 0};
                const int ready = left.count() > 0 ? ::poll(&p, 1, int(std::min<long long>(left.count(), 1 << 30))) : 0;
                if (ready < 0 && errno == EINTR) continue;
                if (ready > 0 || ready < 0) {
                    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
                    }
                } else {
                    kill_and_reap();
                }
                break;
            }
            ::close(pidfd);
        } else {
            auto nap = std::chrono::microseconds(100);
            for (;;) {
                const pid_t w = ::waitpid(pid, &status, WNOHANG);
                if (w == pid || (w < 0 && errno != EINTR)) break;
                if (std::chrono::steady_clock::now() >= deadline) {
                    kill_and_reap();
                    break;
                }
                std::this_thread::sleep_for(nap);
                nap = std::min(nap * 2, std::chrono::microseconds(20000));
            }
        }
    }
    r.log = log.read_all();
    if (WIFSIGNALED(status)) {
        r.signal = WTERMSIG(status);
        return r;
    }
    r.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    auto [storage, got] = out.map();
    if (r.exit_status != 0 || got.empty() || got[0] == '?') return r;
    r.status = got[0] == 'O'   ? IsolatedOutcome::Status::ok
               : got[0] == 'M' ? IsolatedOutcome::Status::out_of_memory
                               : IsolatedOutcome::Status::threw;
    r.bytes = got.substr(1);
    r.storage = std::move(storage);
    return r;
}

namespace {

// A limit of the reader's child from the environment variable `name` (a whole number from 1 to `most`), else
// `otherwise`.
std::uint64_t limit_from_env(const std::string& path, const IsolatedReader& reader, const char* name,
                             std::uint64_t most, std::uint64_t otherwise) {
    const char* env = std::getenv(name);
    if (!env || !*env) return otherwise;
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(env, &end, 10);
    if (errno || *end || v == 0 || v > most || !std::isdigit(static_cast<unsigned char>(env[0])))
        throw_io_error(path, std::string(reader.failure) + ": " + name + " \"" + env +
                                 "\" is not a whole number from 1 to " + std::to_string(most));
    return std::uint64_t(v);
}

// "4 GiB", "512 MiB" (RTM_MESH_READER_MB=1 read "0.000977 GiB").
std::string gib(std::uint64_t bytes) {
    std::ostringstream os;
    os.precision(3);
    if (bytes >= (std::uint64_t(1) << 30))
        os << double(bytes) / double(std::uint64_t(1) << 30) << " GiB";
    else
        os << double(bytes) / double(std::uint64_t(1) << 20) << " MiB";
    return os.str();
}

}  // namespace

IsolationLimits reader_limits(const std::string& path, std::uint64_t file_bytes, const IsolatedReader& reader) {
    const std::uint64_t want = std::max<std::uint64_t>(std::uint64_t(4) << 30, file_bytes * 64);
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    const std::uint64_t ram = pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : want;
    IsolationLimits l;
    l.address_space = limit_from_env(path, reader, reader.memory_variable, std::uint64_t(1) << 40,
                                     std::min(want, ram) >> 20)
                      << 20;
    l.cpu_seconds = limit_from_env(path, reader, reader.seconds_variable, std::uint64_t(1) << 31,
                                   60 + 2 * (file_bytes >> 20));
    l.wall_seconds = 2 * l.cpu_seconds + 2;  // a reader that waits (on a FIFO it opened) uses no processor time
    return l;
}

IsolatedOutcome read_isolated(const std::string& path, std::uint64_t file_bytes, const IsolatedReader& reader,
                              const std::function<void(const ResultWriter&)>& read, bool forward_log) {
    const IsolationLimits limits = reader_limits(path, file_bytes, reader);
    const std::string failed = std::string(reader.failure) + ": " + reader.name + " ";
    const std::string for_file = " for a file of " + std::to_string(file_bytes) + " bytes";
    IsolatedOutcome r;
    try {
        r = run_isolated(read, limits);
    } catch (const std::runtime_error& e) {
        throw_io_error(path, std::string(reader.failure) + ": no process to read it in (" + e.what() + ")");
    }
    if (r.status == IsolatedOutcome::Status::ok) {
        if (forward_log) std::fwrite(r.log.data(), 1, r.log.size(), stderr);
        return r;
    }
    if (r.status == IsolatedOutcome::Status::threw) throw IoError(std::string(r.bytes));  // already names the file
    if (r.status == IsolatedOutcome::Status::out_of_memory)
        throw_io_error(path, failed + "ran out of the " + gib(limits.address_space) + " it may use" + for_file + " (" +
                                 reader.memory_variable + " sets more)");
    if (r.timed_out)
        throw_io_error(path, failed + "was stopped after the " + std::to_string(limits.wall_seconds) +
                                 " s it may take" + for_file +
                                 ": it waited on something the file names, a FIFO or a device perhaps (" +
                                 reader.seconds_variable + " sets more)");
    if (r.signal == SIGXCPU)
        throw_io_error(path, failed + "was stopped after the " + std::to_string(limits.cpu_seconds) +
                                 " s of processor time it may use" + for_file + " (" + strsignal(r.signal) + "; " +
                                 reader.seconds_variable + " sets more)");
    // The last line the reader wrote as it ended (a failed assertion, an uncaught exception), if any, says where.
    std::string said;
    std::istringstream lines(r.log);
    for (std::string line; std::getline(lines, line);)
        if (line.find_first_not_of(" \t\r") != std::string::npos) said = line;
    if (said.size() > 200) said = said.substr(0, 200) + "...";
    if (!said.empty()) said = "; it said \"" + said + "\"";
    if (r.signal)
        throw_io_error(path, failed + "crashed on it (signal " + std::to_string(r.signal) + ", " + strsignal(r.signal) +
                                 said + ")");
    throw_io_error(path, failed + "ended without a result (exit status " + std::to_string(r.exit_status) + said + ")");
}

}  // namespace rtm
