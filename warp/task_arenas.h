// The task arenas the pre-warper's parallel passes run in: one per explicit thread count, made on first use and
// kept. Every pass of a frame (a relief's two passes, an object's faces and their adjacent faces, the composites)
// runs in the one arena of its thread count, so a worker thread stays in it between passes: with one arena per
// module the worker left one arena and joined the other several times a frame (docs/perf-history.md, "Six-face
// objects").
#pragma once

#include <tbb/task_arena.h>

namespace rtm {

// The arena of `threads` threads (>= 1; the calling thread is one of them), at most arena_threads(threads).
// Thread-safe.
tbb::task_arena& task_arena_for(int threads);

// `threads` (>= 1) capped at the parallelism TBB allows (its global limit: the machine's hardware threads unless a
// tbb::global_control lowers it). An arena asking for more waits for workers that never come, TBB warns on stderr
// for each, and arenas of 70,000 slots made and dropped one after another crashed TBB's allocator (`rtm compare
// --threads 100000`). No output depends on the thread count.
int arena_threads(int threads);

}  // namespace rtm
