// The task arenas the pre-warper's parallel passes run in: one per explicit thread count, made on first use and
// kept. Every pass of a frame (a relief's two passes, an object's faces and their adjacent faces, the composites)
// runs in the one arena of its thread count, so a worker thread stays in it between passes: with one arena per
// module the worker left one arena and joined the other several times a frame (docs/perf-history.md, "Six-face
// objects").
#pragma once

#include <tbb/task_arena.h>

namespace rtm {

// The arena of `threads` threads (>= 1; the calling thread is one of them). Thread-safe.
tbb::task_arena& task_arena_for(int threads);

}  // namespace rtm
