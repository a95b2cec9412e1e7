// run_isolated (formats/isolated_call.h): the work's result, its exception, its crash, its runaway allocation and its
// endless loop each come back to the parent, which goes on.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "formats/isolated_call.h"

namespace rtm {
namespace {

using Status = IsolatedOutcome::Status;

int g_touched = 0;  // changed by the work in the child only

TEST(IsolatedCall, ReturnsWhatTheWorkReturnsFromAnotherProcess) {
    const IsolatedOutcome r = run_isolated(
        [] {
            g_touched = 1;
            return std::to_string(::getpid());
        },
        {});
    EXPECT_EQ(r.status, Status::ok);
    EXPECT_NE(r.bytes, std::to_string(::getpid()));
    EXPECT_EQ(g_touched, 0);
}

TEST(IsolatedCall, ResultsLargerThanAPipeArriveWhole) {
    // 48 MiB of a pattern with every byte value, zeros included: the pipe holds 64 KiB, so the parent must read while
    // the child writes.
    std::string want(size_t(48) << 20, '\0');
    for (size_t i = 0; i < want.size(); ++i) want[i] = char((i * 7919u) >> 3);
    const IsolatedOutcome r = run_isolated([&] { return want; }, {});
    EXPECT_EQ(r.status, Status::ok);
    EXPECT_TRUE(r.bytes == want) << r.bytes.size() << " bytes";
    EXPECT_EQ(run_isolated([] { return std::string(); }, {}).status, Status::ok);  // an empty result is a result
}

TEST(IsolatedCall, AnExceptionComesBackAsItsMessage) {
    const IsolatedOutcome r = run_isolated([]() -> std::string { throw std::runtime_error("file.obj: bad face"); }, {});
    EXPECT_EQ(r.status, Status::threw);
    EXPECT_EQ(r.bytes, "file.obj: bad face");
}

TEST(IsolatedCall, ACrashEndsTheChildOnly) {
    const IsolatedOutcome r = run_isolated([]() -> std::string { std::abort(); }, {});
    EXPECT_EQ(r.status, Status::died);
    EXPECT_EQ(r.signal, SIGABRT);
    // A write through a null pointer: SIGSEGV, or under AddressSanitizer its report and then exit status 1 or, with
    // abort_on_error (scripts/test.sh), SIGABRT.
    const IsolatedOutcome s = run_isolated(
        []() -> std::string {
            volatile int* p = nullptr;
            *p = 1;
            return "written";
        },
        {});
    EXPECT_EQ(s.status, Status::died);
    EXPECT_TRUE(s.signal != 0 || s.exit_status != 0) << s.signal << " " << s.exit_status;
#if !defined(__SANITIZE_ADDRESS__)
    EXPECT_EQ(s.signal, SIGSEGV);
#endif
    // Exiting without a result.
    const IsolatedOutcome e = run_isolated([]() -> std::string { ::_exit(3); }, {});
    EXPECT_EQ(e.status, Status::died);
    EXPECT_EQ(e.signal, 0);
    EXPECT_EQ(e.exit_status, 3);
}

// The work writes its result in pieces; a child that ends while writing, or throws after writing part, leaves no
// result (the tag byte goes in last), and the result outlives the outcome it came in through copies of it.
TEST(IsolatedCall, PiecesArriveInOrderAndAPartResultIsNone) {
    IsolatedOutcome kept;
    {
        const IsolatedOutcome r = run_isolated(
            [](const ResultWriter& out) {
                out.write("ab", 2);
                out.write("", 0);
                out.write("cde", 3);
            },
            IsolationLimits{});
        EXPECT_EQ(r.status, Status::ok);
        EXPECT_EQ(r.bytes, "abcde");
        kept = r;
    }
    EXPECT_EQ(kept.bytes, "abcde");
    const IsolatedOutcome ended = run_isolated(
        [](const ResultWriter& out) {
            out.write("part of it", 10);
            ::_exit(0);
        },
        IsolationLimits{});
    EXPECT_EQ(ended.status, Status::died);
    EXPECT_EQ(ended.exit_status, 0);
    EXPECT_TRUE(ended.bytes.empty());
    const IsolatedOutcome threw = run_isolated(
        [](const ResultWriter& out) {
            out.write("part of it", 10);
            throw std::runtime_error("x.png: bad row");
        },
        IsolationLimits{});
    EXPECT_EQ(threw.status, Status::threw);
    EXPECT_EQ(threw.bytes, "x.png: bad row");
}

TEST(IsolatedCall, ProcessorTimeIsCapped) {
    IsolationLimits limits;
    limits.cpu_seconds = 1;
    const IsolatedOutcome r = run_isolated(
        []() -> std::string {
            volatile unsigned long n = 0;
            for (;;) n = n + 1;
        },
        limits);
    EXPECT_EQ(r.status, Status::died);
    EXPECT_EQ(r.signal, SIGXCPU);
}

// A child that sleeps for 30 s and one that returns at once, each with 1 s of time.
struct SleeperAndQuick {
    IsolatedOutcome sleeper, quick;
};
SleeperAndQuick run_sleeper_and_quick() {
    IsolationLimits limits;
    limits.wall_seconds = 1;
    SleeperAndQuick o;
    o.sleeper = run_isolated(
        []() -> std::string {
            ::sleep(30);
            return "woke";
        },
        limits);
    o.quick = run_isolated([] { return std::string("quick"); }, limits);
    return o;
}
// The sleeper uses no processor time: the parent kills it when its time is up. The quick one is not marked.
void expect_sleeper_killed_and_quick_kept(const SleeperAndQuick& o) {
    EXPECT_EQ(o.sleeper.status, Status::died);  // not "woke": killed in its sleep
    EXPECT_TRUE(o.sleeper.timed_out);
    EXPECT_EQ(o.sleeper.signal, SIGKILL);
    EXPECT_EQ(o.quick.status, Status::ok);
    EXPECT_EQ(o.quick.bytes, "quick");
    EXPECT_FALSE(o.quick.timed_out);
}

TEST(IsolatedCall, TimeIsCapped) { expect_sleeper_killed_and_quick_kept(run_sleeper_and_quick()); }

// Without a process file descriptor (Linux before 5.3, or none left to open) the parent polls for the child's end:
// the same outcomes. Here the descriptors run out: all but two (the result's and the log's memory files) of those
// below a lowered limit are taken. Not in the sanitizer build: UBSan's check of an object's dynamic type opens a pipe
// to test that its memory is readable, and with no descriptor left it reports every object it checks as invalid.
#if defined(__SANITIZE_ADDRESS__)
TEST(IsolatedCall, DISABLED_TimeIsCappedWithoutAProcessDescriptor) {}
#else
TEST(IsolatedCall, TimeIsCappedWithoutAProcessDescriptor) {
    rlimit saved{};
    ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &saved), 0);
    std::vector<int> taken;
    for (;;) {  // the lowest free descriptors, up to some above the highest open one
        const int fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
        ASSERT_GE(fd, 0);
        taken.push_back(fd);
        if (taken.size() >= 8) break;
    }
    rlimit low = saved;
    low.rlim_cur = rlim_t(taken.back() + 1);
    ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &low), 0);
    ::close(taken.back());
    taken.pop_back();
    ::close(taken.back());
    taken.pop_back();
    {  // once the two memory files are open, no descriptor is left for the process's
        const int a = ::open("/dev/null", O_RDONLY | O_CLOEXEC), b = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
        EXPECT_GE(a, 0);
        EXPECT_GE(b, 0);
        EXPECT_LT(::syscall(SYS_pidfd_open, ::getpid(), 0), 0);
        ::close(a);
        ::close(b);
    }
    const SleeperAndQuick o = run_sleeper_and_quick();
    ::setrlimit(RLIMIT_NOFILE, &saved);
    for (int fd : taken) ::close(fd);
    expect_sleeper_killed_and_quick_kept(o);
}
#endif

#if defined(__SANITIZE_ADDRESS__)
// AddressSanitizer maps its allocator's whole space at start, so the cap on the address space does not bound it.
TEST(IsolatedCall, DISABLED_AddressSpaceIsCapped) {}
#else
TEST(IsolatedCall, AddressSpaceIsCapped) {
    IsolationLimits limits;
    limits.address_space = uint64_t(256) << 20;
    const IsolatedOutcome r = run_isolated(
        [] {
            std::vector<char> big(size_t(1) << 30, 1);  // 1 GiB: over the cap
            return std::string(1, big[12345]);
        },
        limits);
    EXPECT_EQ(r.status, Status::out_of_memory);
    // Under the cap the same work succeeds.
    const IsolatedOutcome s = run_isolated(
        [] {
            std::vector<char> small(size_t(64) << 20, 1);
            return std::string(1, small[12345]);
        },
        limits);
    EXPECT_EQ(s.status, Status::ok);
    EXPECT_EQ(s.bytes, std::string(1, '\1'));
}
#endif

}  // namespace
}  // namespace rtm
