// A reader run in a child process, so that what it does on a hostile file (a crash, an abort, an allocation without
// end) ends the child and not rtm. assimp 5.2 reads dozens of formats by content, and random changes to its own test
// models crash it within seconds (segmentation faults in its MDL and LWS readers) or make it allocate without end (a
// 254-byte PLY file, which loops without end once it cannot): load_mesh (mesh/triangle_mesh.h) reads every mesh this
// way and turns each outcome into one line naming the file.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace rtm {

struct IsolatedOutcome {
    enum class Status {
        ok,             // `bytes` is what the work returned
        threw,          // the work threw; `bytes` is the exception's message
        out_of_memory,  // the work threw std::bad_alloc (its address space is capped: run_isolated)
        died,           // the child ended without a result: by signal `signal`, or exit status `exit_status`
    };
    Status status = Status::died;
    std::string bytes;
    int signal = 0;          // died: the signal that ended the child, 0 if none did
    int exit_status = 0;     // died without a signal: the child's exit status
    bool timed_out = false;  // died: killed by the parent after IsolationLimits::wall_seconds
    std::string log;         // what the child wrote on its standard error (which is not the parent's)
};

// What the child may use (0: no limit). address_space: bytes its address space may grow by beyond its size when it
// starts; past that an allocation fails (std::bad_alloc). cpu_seconds: processor time; past that the kernel ends it
// with SIGXCPU (a reader that loops without end: assimp's PLY reader did on a 254-byte file once allocation failed).
// wall_seconds: time; past that the parent kills it (SIGKILL) and says so (`timed_out`): a reader that waits without
// end on something it opened, such as a FIFO named by the file as its material library.
struct IsolationLimits {
    std::uint64_t address_space = 0;
    std::uint64_t cpu_seconds = 0;
    std::uint64_t wall_seconds = 0;
};

// Runs `work` in a child process (fork) and returns what it returned, or how it ended, and what it wrote on standard
// error (libraries' messages as they abort: assimp's failed assertions, an uncaught exception). The child ends with
// _exit, running no destructor or exit handler of the parent's objects. Throws std::runtime_error naming the call that
// failed when no child can be started.
IsolatedOutcome run_isolated(const std::function<std::string()>& work, const IsolationLimits& limits);

}  // namespace rtm
