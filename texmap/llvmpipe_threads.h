// llvmpipe's rasterizer threads, one per CPU.
//
// Mesa's llvmpipe (the OpenGL of OSMesa and of the viewer under Xvfb here) rasterizes with threads named
// "llvmpipe-0" .. "llvmpipe-<n-1>", n = the number of CPUs, woken by the thread that flushes. Left to the Linux
// scheduler, the wakees often start on the waker's CPU and stay there for the length of a frame (about a
// millisecond), so the two rasterizer threads of the 2-core machine shared one CPU while the other idled: a frame's
// texture mapping then took the time of one thread (ridges 256^2 pipelined at 512x512, median of a run: 1.24 ms
// instead of 0.69; per process, and even between the runs of one process, one or the other; LP_NUM_THREADS=1
// gave 1.24 every time). Pinning thread k to the k-th CPU the process may use (modulo their number) removed the
// slow runs: 6 processes of `rtm bench` each way, interleaved, pinned 0.68 to 0.72 ms every time, not pinned
// 0.69 to 0.76 in two and 1.24 to 1.26 in four.
#pragma once

#include <chrono>
#include <vector>

namespace rtm {

// The ids of this process's threads, ascending.
std::vector<int> process_threads();

// How long spread_llvmpipe_threads waits for new threads to name themselves.
constexpr std::chrono::milliseconds kWait{50};

// Pins every thread of this process named "llvmpipe-<k>" to the k-th CPU of the process's affinity mask (modulo
// their number). Does nothing when the process may use one CPU only, when no such thread exists (another OpenGL
// driver) or when the environment sets RTM_NO_LLVMPIPE_PINNING (to measure the difference). Returns the number of
// threads pinned. Best effort: a thread that cannot be pinned keeps its mask.
// `before`: process_threads() from before the context was created. llvmpipe names each thread from inside it, so
// right after the context is created a thread that has not run yet still has its creator's name and would be
// missed (seen on a busy host: llvmpipe-1 left unpinned); the threads started since `before` are given up to kWait
// to take their names first, while fewer llvmpipe threads than LP_NUM_THREADS or the online CPUs are found. Empty:
// no wait.
int spread_llvmpipe_threads(const std::vector<int>& before = {});

}  // namespace rtm
