// A reader run in a child process, so that what it does on a hostile file (a crash, an abort, an allocation without
// end) ends the child and not rtm. assimp 5.2 reads dozens of formats by content, and random changes to its own test
// models crash it within seconds (segmentation faults in its MDL and LWS readers) or make it allocate without end (a
// 254-byte PLY file, which loops without end once it cannot); OpenImageIO 2.4's readers, changed the same way from
// images it writes, corrupt the heap (IFF) or loop (RLA). load_mesh (mesh/triangle_mesh.h) reads every mesh this way,
// formats/image_io.h every image that libpng does not read when the image module reads it (rtm's own programs: see
// image_io.cpp), and read_isolated turns each outcome into one line naming the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace rtm {

// Where the work writes its result in the child: pieces, in order, into a file in memory that the parent maps once
// the child has ended (no copy through a pipe or a string on either side: an image of 64 MiB goes across in a
// copy, formats/image_io.cpp).
class ResultWriter {
public:
    explicit ResultWriter(int fd) : fd_(fd) {}
    // Throws std::bad_alloc when the memory file cannot grow (the child's memory is capped: IsolationLimits).
    void write(const void* data, std::size_t bytes) const;

private:
    int fd_;
};

struct IsolatedOutcome {
    enum class Status {
        ok,             // `bytes` is what the work wrote (or returned)
        threw,          // the work threw; `bytes` is the exception's message
        out_of_memory,  // the work threw std::bad_alloc (its address space is capped: run_isolated)
        died,           // the child ended without a result: by signal `signal`, or exit status `exit_status`
    };
    Status status = Status::died;
    std::string_view bytes;               // points into `storage`: valid while this outcome (or a copy) lives
    int signal = 0;                       // died: the signal that ended the child, 0 if none did
    int exit_status = 0;                  // died without a signal: the child's exit status
    bool timed_out = false;               // died: killed by the parent after IsolationLimits::wall_seconds
    std::string log;                      // what the child wrote on its standard error (which is not the parent's)
    std::shared_ptr<const void> storage;  // the child's result file, mapped read-only
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

// Runs `work` in a child process (fork) and returns what it wrote, or how it ended, and what it wrote on standard error
// (libraries' messages as they abort: assimp's failed assertions, an uncaught exception). The child ends with _exit,
// running no destructor or exit handler of the parent's objects. Throws std::runtime_error naming the call that failed
// when no child can be started.
IsolatedOutcome run_isolated(const std::function<void(const ResultWriter&)>& work, const IsolationLimits& limits);
// The same for work that returns its result.
IsolatedOutcome run_isolated(const std::function<std::string()>& work, const IsolationLimits& limits);

// A reader of one kind of file, as read_isolated runs it: how its messages name it and which environment variables
// set its limits.
struct IsolatedReader {
    const char* failure;           // what a message says after the file's name: "cannot read mesh"
    const char* name;              // "the mesh reader (assimp)"
    const char* memory_variable;   // MiB of address space: "RTM_MESH_READER_MB"
    const char* seconds_variable;  // seconds of processor time: "RTM_MESH_READER_SECONDS"
};

// What the reader's child may use for a file of `file_bytes`: `memory_variable` MiB of address space beyond its size at
// the start if set, else 4 GiB or 64 times the file's size, whichever is more, but at most this machine's memory;
// `seconds_variable` seconds of processor time if set, else 60 s and 2 s more per MiB of the file; twice that and 2 s
// of time (a reader waiting on a FIFO uses no processor time). A variable that is not a whole number from 1 up: IoError
// naming the file, the variable and its value.
IsolationLimits reader_limits(const std::string& path, std::uint64_t file_bytes, const IsolatedReader& reader);

// Runs `read` on the file `path` (`file_bytes` long) in a child with reader_limits, and returns the outcome, whose
// status is ok; what the child wrote on its standard error goes to ours when `forward_log` (as if it had read here).
// Otherwise throws IoError (formats/image_io.h), one line: the exception's message if `read` threw (which names the
// file), else "<path>: <failure>: <name> " and how it ended: crashed (the signal and the last line it wrote), ran out
// of the memory or the processor time it may use, was stopped after the time it may take, or ended without a result.
IsolatedOutcome read_isolated(const std::string& path, std::uint64_t file_bytes, const IsolatedReader& reader,
                              const std::function<void(const ResultWriter&)>& read, bool forward_log = true);

}  // namespace rtm
