#include "warp/simd/schedule.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

#include "warp/simd/avx512_pipelined.h"
#include "warp/simd/avx512_two_pass.h"
#include "warp/simd/hwy_pipelined.h"
#include "warp/simd/hwy_two_pass.h"
#include "warp/simd/kernel_policy.h"
#include "warp/line_warp.h"
#include "warp/tables.h"

namespace rtm {

namespace {

// Largest output side the kernels accept: pixel indices and span ends stay exact in float far below 2^24.
constexpr int kMaxSide = 1 << 22;
// Largest output the kernels accept: the column kernels' scatter (store_rows, warp/simd/avx512_columns.h) addresses
// pixels by 32-bit offsets of up to the whole image from its last storage row. 2^31 - 16 pixels is 8 GiB of RGBA8.
constexpr long long kMaxPixels = (1ll << 31) - 16;

// One task arena per explicit thread count, created on first use: an arena created, used for one parallel_for and
// destroyed costs 8 to 150 us here, a cached one 1 us (a 256^2 pre-warp takes about 300 us).
tbb::task_arena& arena_for(int threads) {
    static std::mutex mu;
    static std::map<int, std::unique_ptr<tbb::task_arena>> arenas;
    std::lock_guard<std::mutex> lock(mu);
    auto& a = arenas[threads];
    if (!a) a = std::make_unique<tbb::task_arena>(threads);
    return *a;
}

// Runs body(begin, end) over [0, n) in chunks of at least `grain`: inline for one thread (no TBB overhead at all),
// in the caller's arena for threads == 0, in a cached arena otherwise.
template <class Body>
void run_ranges(int threads, int n, int grain, const Body& body) {
    if (threads == 1 || n <= grain) {
        body(0, n);
        return;
    }
    auto loop = [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, n, grain),
                          [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
    };
    if (threads > 0)
        arena_for(threads).execute(loop);
    else
        loop();
}

// Two-pass: rows per band (steps warped horizontally before the vertical pass takes them) and bands in flight.
// Two threads, bumps 1024^2: bands of 4 rows 3.08 ms, 8 rows 2.97, 16 rows 2.79, 32 rows 2.66, 64 rows 2.74 (the
// pipeline's cost per band); one thread: no difference between 1 and 64 rows.
constexpr int kBandRows = 32;
constexpr int kBandSlots = 4;

template <class T>
T* aligned64(T* p) {
    static_assert(sizeof(T) == 4);
    return p + ((64 - reinterpret_cast<uintptr_t>(p) % 64) % 64) / 4;
}

template <class T>
void ensure_size(Image2D<T>& img, int w, int h) {
    if (img.width != w || img.height != h) img.resize(w, h);
}

}  // namespace

namespace fast {

bool cpu_supported() {
#if RTM_AVX512_KERNELS
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("avx512vbmi") && __builtin_cpu_supports("avx512vnni") &&
           __builtin_cpu_supports("bmi2");
#else
    return false;  // not compiled (not x86-64: warp/CMakeLists.txt)
#endif
}

FastTables make_fast_tables(const PrewarpTables& tab) {
    FastTables t;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int q = 0; q < 256; ++q) {
        const bool ok = tab.valid[q] != 0;
        const float v[3] = {ok ? tab.k1d[q] : nan, tab.k2d[q], tab.rcp[q]};
        for (int i = 0; i < 3; ++i) {
            uint32_t bits;
            std::memcpy(&bits, &v[i], 4);
            for (int b = 0; b < 4; ++b) t.plane[i][b][q] = uint8_t(bits >> (8 * b));
        }
        t.dropped[q] = q != kEmptyIndex && !ok;
        t.any_dropped = t.any_dropped || t.dropped[q];
    }
    return t;
}

}  // namespace fast

namespace simd::testing {
namespace {
FastKernelPolicy g_policy;
}
const FastKernelPolicy& kernel_policy() { return g_policy; }
ScopedKernelPolicy::ScopedKernelPolicy(const FastKernelPolicy& policy) : saved_(g_policy) { g_policy = policy; }
ScopedKernelPolicy::~ScopedKernelPolicy() { g_policy = saved_; }
}  // namespace simd::testing

bool fast_prewarp_available() {
    static const bool ok = fast::cpu_supported();
    return ok;
}

void balance_row_chunks(std::vector<int>& bounds, const double* ms) {
    const int n = int(bounds.size()) - 1;
    if (n < 2 || n > 64) return;
    double total = 0.0;
    for (int i = 0; i < n; ++i) {
        if (!(std::isfinite(ms[i]) && ms[i] > 0.0)) return;
        total += ms[i];
    }
    int old[65];  // per frame: no allocation
    std::copy(bounds.begin(), bounds.end(), old);
    int chunk = 0;
    double before = 0.0;  // the time of the chunks before `chunk`
    for (int k = 1; k < n; ++k) {
        const double want = total * k / n;
        while (before + ms[chunk] < want && chunk + 1 < n) before += ms[chunk++];
        const double rows = old[chunk + 1] - old[chunk];
        const double target = old[chunk] + (want - before) / ms[chunk] * rows;
        const int moved = int(std::lround(0.5 * (old[k] + target)));
        bounds[size_t(k)] = std::clamp(moved, bounds[size_t(k) - 1] + 1, old[n] - (n - k));
    }
}

bool fast_prewarp_covers(Isa isa, const ReliefTexture& relief, const PrewarpCoefficients& k,
                         const PrewarpOptions& options, const PrewarpExtent& e, const Image2D<uint8_t>* displ_out) {
    if (options.exact || displ_out || options.filter != Filter::point) return false;
    if (isa == Isa::automatic || isa == Isa::generic) return false;
    if (isa != Isa::avx512 && !(options.method == Reconstruction::two_pass ? !!simd::hwy_two_pass_kernels(isa).vertical
                                                                           : !!simd::hwy_pipelined_kernels(isa).part))
        return false;
    if (!relief.breaks.empty() || relief.discontinuity_threshold > 0.0) return false;
    if (k.side == ViewSide::on_plane || relief.width <= 0 || relief.height <= 0) return false;
    const long long ow = (long long)relief.width + e.left + e.right, oh = (long long)relief.height + e.bottom + e.top;
    if (ow > kMaxSide || oh > kMaxSide || ow * oh > kMaxPixels) return false;
    return isa != Isa::avx512 || fast_prewarp_available();
}

namespace {

PrewarpStats fast_two_pass(const simd::TwoPassKernels& kernels, const ReliefTexture& relief,
                           const PrewarpCoefficients& k, const PrewarpOptions& options, const PrewarpExtent& e,
                           const PrewarpTables& ref_tables, const fast::FastTables& tables, PrewarpWorkspace& ws,
                           ImageRGBA8& out) {
    const int w = relief.width, h = relief.height;
    const int ow = w + e.left + e.right, oh = h + e.bottom + e.top;
    std::atomic<long long> dropped{0};
    ensure_size(out, ow, oh);
    // Rows of the workspace's intermediate images (width rounded up to 16, 64-byte aligned thanks to the spare
    // row): 0 the column state (v, colour), 1 the seam, 2 the columns' "has a sample" bits and floor, 3 ceil, then
    // the bands.
    const int stride = (ow + 15) / 16 * 16;
    const int band = kBandRows, slots = kBandSlots;
    ensure_size(ws.mid_color, stride, 4 + band * slots + 1);
    // After the bands: one row scratch (3 source widths of floats) per band slot, for the Highway kernels.
    const size_t scratch_rows = (3 * size_t(w) + size_t(stride) - 1) / size_t(stride);
    ensure_size(ws.mid_v, stride, 4 + band * slots + int(scratch_rows) * slots + 1);
    uint32_t* mc = aligned64(reinterpret_cast<uint32_t*>(ws.mid_color.pixels.data()));
    float* mv = aligned64(ws.mid_v.pixels.data());
    fast::TwoPassJob job;
    job.relief = &relief;
    job.tables = &tables;
    job.ref_tables = &ref_tables;
    job.extent = e;
    job.split_u = split_index(k.epipole_u, w);
    job.split_v = split_index(k.epipole_v, h);
    job.out = &out;
    job.col_v = mv;
    job.col_c = mc;
    job.seam_v = mv + stride;
    job.seam_c = mc + stride;
    job.col_ok = reinterpret_cast<uint16_t*>(mc + 2 * size_t(stride));
    job.copy_still = options.copy_still_runs;
    job.reverse = simd::testing::kernel_policy().two_pass_reverse;
    job.redo_forwards = simd::testing::kernel_policy().two_pass_redo_forwards;
    job.col_fl = reinterpret_cast<int32_t*>(mv + 2 * size_t(stride));
    job.col_ce = reinterpret_cast<int32_t*>(mv + 3 * size_t(stride));
    job.dropped = &dropped;
    auto band_c = [&](int slot) { return mc + size_t(4 + slot * band) * stride; };
    auto band_v = [&](int slot) { return mv + size_t(4 + slot * band) * stride; };
    const int bands = (h + band - 1) / band;
    auto horizontal = [&](int b) {
        kernels.horizontal(job, b * band, std::min(h, (b + 1) * band), band_c(b % slots), band_v(b % slots),
                           size_t(stride), mv + (size_t(4 + band * slots) + (b % slots) * scratch_rows) * stride);
    };
    auto vertical = [&](int b, int x0, int x1) {
        kernels.vertical(job, b * band, std::min(h, (b + 1) * band), band_c(b % slots), band_v(b % slots),
                         size_t(stride), x0, x1);
    };
    if (options.threads == 1 || bands < 2) {
        for (int b = 0; b < bands; ++b) {
            horizontal(b);
            vertical(b, 0, ow);
        }
        return {(long long)w * h, dropped.load(), e};
    }
    // Threads: a pipeline over the bands. The horizontal warps of different bands run in parallel; the vertical
    // pass takes the bands in order, in two column halves that are stages of their own, so that one half of band
    // b + 1 can proceed while the other half of band b does. At most `slots` bands are in flight: band b's
    // buffers (slot b % slots) are free again when band b + slots enters.
    const int mid = std::min(ow, (ow / 2 + 15) / 16 * 16);
    auto pipeline = [&] {
        int next = 0;
        tbb::parallel_pipeline(
            size_t(slots),
            tbb::make_filter<void, int>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) {
                if (next == bands) fc.stop();
                return next++;
            }) & tbb::make_filter<int, int>(tbb::filter_mode::parallel, [&](int b) {
                horizontal(b);
                return b;
            }) & tbb::make_filter<int, int>(tbb::filter_mode::serial_in_order, [&](int b) {
                vertical(b, 0, mid);
                return b;
            }) & tbb::make_filter<int, void>(tbb::filter_mode::serial_in_order, [&](int b) { vertical(b, mid, ow); }));
    };
    if (options.threads > 0)
        arena_for(options.threads).execute(pipeline);
    else
        pipeline();
    return {(long long)w * h, dropped.load(), e};
}

// Whether fast_pipelined splits its parts into row chunks rather than column ranges (see below): with threads and
// one part (the epipole outside the relief's rows, the benchmark's view). Column ranges repeat every row's
// horizontal warp in every range; row chunks repeat one row per chunk and add the composite (0.03 to 0.06 ms of
// 1.7 to 3.9 at 1024^2). Measured (2 threads, median ms of 5 interleaved rounds of `rtm bench --no-exact
// --no-reference`, column ranges -> row chunks): bumps 256^2 0.095 -> 0.081, 1024^2 2.05 -> 1.72; bricks 0.199 ->
// 0.166, 2.36 -> 1.83; ridges 0.329 -> 0.273, 4.75 -> 3.94 (1 thread, unchanged: 3.21 / 3.54 / 8.19 -> within the
// noise); 2 rounds, bumps 2048^2 18.3 -> 13.7, 4096^2 110 -> 80, ridges 23.5 -> 21.6, 96.9 -> 92.9. Small images
// too (3 rounds, 32^2 to 128^2: equal or faster, ridges 64^2 0.054 -> 0.033), so no size limit. The chunks' rows
// are balanced by time (pipelined_in_row_chunks). Two parts keep the column ranges: not measured (the benchmark's view
// has one part, and more threads than parts needs more than this machine's 2 cores).
bool pipelined_row_chunks(KernelChoice choice, int threads, int np) {
    if (choice != KernelChoice::automatic) return choice == KernelChoice::always;
    return threads > 1 && np == 1;
}

// Each part (bottom, top) that has rows split into column ranges, so that all threads have work even when the
// epipole is outside the relief and one part holds every row. A range repeats the horizontal warp of every row of
// its part but rasterizes only its columns.
void pipelined_in_column_ranges(const simd::PipelinedKernels& kernels, const fast::PipelinedJob& job,
                                int threads_option, int threads) {
    const int h = job.relief->height, ow = job.out->width;
    const bool parts[2] = {job.split_v > 0, job.split_v < h};
    const int np = int(parts[0]) + int(parts[1]);
    const int cols = std::max(1, std::min(threads / std::max(np, 1), ow / 64));
    struct Task {
        int part, x0, x1;
    };
    Task tasks[2 * 64];
    int nt = 0;
    for (int p = 0; p < 2; ++p) {
        if (!parts[p]) continue;
        const int n = std::min(cols, 64);
        for (int i = 0; i < n; ++i) {
            const int x0 = int((long long)ow * i / n) / 16 * 16;
            const int x1 = i + 1 == n ? ow : int((long long)ow * (i + 1) / n) / 16 * 16;
            if (x0 < x1) tasks[nt++] = {p, x0, x1};
        }
    }
    run_ranges(threads_option, nt, 1, [&](int t0, int t1) {
        for (int t = t0; t < t1; ++t) kernels.part(job, tasks[t].part, tasks[t].x0, tasks[t].x1);
    });
}

// Each part that has rows split into chunks of consecutive rows, one per thread (fewer where the part has fewer
// rows): every chunk warps only its own rows (and the one before them, for its starting state), the first draws
// into the output and the others into scratch images (the workspace's, shared by the parts, whose output rows are
// disjoint), composited over the output afterwards in row order. The first chunk clears its part's output rows
// itself: clearing the whole output in parallel first measured the same (bumps 1024^2, 2 threads, 5 interleaved
// rounds: 1.726 ms against 1.718).
// The chunks' rows are balanced by their times in the last pre-warp (balance_row_chunks): equal rows took unequal
// times (2 threads, 1024^2: bumps 1.64 ms for the first half against 1.50 for the second, ridges 3.6 against
// 3.8; 256^2: bumps 0.076 against 0.096, ridges 0.243 against 0.290: the second chunk also warps the row before
// it and draws into a scratch image). Measured (2 threads, `rtm bench --methods pipelined --no-exact
// --no-reference`, median ms of interleaved rounds, equal rows -> balanced; a busy host, 1024^2 7 rounds, 256^2 9):
// 1024^2 bumps 1.89 -> 1.65, bricks 1.96 -> 1.95, ridges 4.40 -> 4.09; 256^2 bumps 0.078 either way, bricks 0.161
// -> 0.149, ridges 0.263 -> 0.255.
void pipelined_in_row_chunks(const simd::PipelinedKernels& kernels, const fast::PipelinedJob& job, int threads_option,
                             int threads, PrewarpWorkspace& ws) {
    const int h = job.relief->height, ow = job.out->width, oh = job.out->height;
    const int rows[2] = {job.split_v, h - job.split_v};
    int per_part[2], scratch = 0;
    for (int p = 0; p < 2; ++p) {
        per_part[p] = std::min({threads, rows[p], 64});
        scratch = std::max(scratch, per_part[p] - 1);
    }
    if (int(ws.chunk_scratch.size()) < scratch) ws.chunk_scratch.resize(size_t(scratch));
    for (int i = 0; i < scratch; ++i) ensure_size(ws.chunk_scratch[size_t(i)], ow, oh);
    // The composite leaves the scratch images all 0; a pre-warp interrupted before it (an exception out of a
    // chunk) may not have, and then they are cleared here.
    if (ws.chunk_scratch_dirty)
        for (ImageRGBA8& img : ws.chunk_scratch) std::fill(img.pixels.begin(), img.pixels.end(), Rgba8{});
    ws.chunk_scratch_dirty = true;
    fast::PipelinedChunk chunks[2 * 64];
    double chunk_ms[2 * 64];
    int nc = 0, first_chunk[2] = {0, 0};
    for (int p = 0; p < 2; ++p) {
        std::vector<int>& b = ws.chunk_bounds[size_t(p)];
        const int n = per_part[p];
        bool valid = int(b.size()) == n + 1 && b[0] == 0 && b[size_t(n)] == rows[p];
        for (int i = 0; valid && i < n; ++i) valid = b[size_t(i)] < b[size_t(i) + 1];
        if (!valid) {
            b.resize(size_t(std::max(n, 0)) + 1);
            for (int i = 0; i <= n; ++i) b[size_t(i)] = int((long long)rows[p] * i / std::max(n, 1));
        }
        first_chunk[p] = nc;
        for (int i = 0; i < n; ++i) {
            fast::PipelinedChunk& c = chunks[nc++];
            c.part = p;
            c.r0 = b[size_t(i)];
            c.r1 = b[size_t(i) + 1];
            c.scratch = i ? &ws.chunk_scratch[size_t(i - 1)] : nullptr;
        }
    }
    run_ranges(threads_option, nc, 1, [&](int t0, int t1) {
        for (int t = t0; t < t1; ++t) {
            const auto start = std::chrono::steady_clock::now();
            kernels.chunk(job, chunks[t]);
            chunk_ms[t] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        }
    });
    for (int p = 0; p < 2; ++p)
        if (per_part[p] > 1) balance_row_chunks(ws.chunk_bounds[size_t(p)], chunk_ms + first_chunk[p]);
    int y0 = oh, y1 = 0;
    for (int i = 0; i < nc; ++i)
        if (chunks[i].ylo < chunks[i].yhi) y0 = std::min(y0, chunks[i].ylo), y1 = std::max(y1, chunks[i].yhi);
    if (y0 < y1)
        run_ranges(threads_option, y1 - y0, 16,
                   [&](int a, int b) { kernels.composite(job, chunks, nc, y0 + a, y0 + b); });
    ws.chunk_scratch_dirty = false;
}

PrewarpStats fast_pipelined(const simd::PipelinedKernels& kernels, const ReliefTexture& relief,
                            const PrewarpCoefficients& k, const PrewarpOptions& options, const PrewarpExtent& e,
                            const PrewarpTables& ref_tables, const fast::FastTables& tables, PrewarpWorkspace& ws,
                            ImageRGBA8& out) {
    const int w = relief.width, h = relief.height;
    const int ow = w + e.left + e.right, oh = h + e.bottom + e.top;
    std::atomic<long long> dropped{0};
    ensure_size(out, ow, oh);
    // The seam rows (the last sample of each part per column) live in the intermediate images, unused otherwise.
    ensure_size(ws.mid_color, ow, 2);
    ensure_size(ws.mid_v, ow, 2);
    fast::PipelinedJob job;
    job.relief = &relief;
    job.copy_still = options.copy_still_runs;
    job.reverse = simd::testing::kernel_policy().pipelined_reverse;
    job.tables = &tables;
    job.ref_tables = &ref_tables;
    job.extent = e;
    job.split_u = split_index(k.epipole_u, w);
    job.split_v = split_index(k.epipole_v, h);
    job.ysplit = split_index(k.epipole_v + e.bottom, oh);
    job.out = &out;
    for (int p = 0; p < 2; ++p) {
        job.seam_v[p] = ws.mid_v.row(p);
        job.seam_c[p] = reinterpret_cast<uint32_t*>(ws.mid_color.row(p));
    }
    job.dropped = &dropped;
    std::atomic<int> next_task{0};
    if (ws.task_buffers.size() < 2 * 64) ws.task_buffers.resize(2 * 64);  // the most tasks (two parts of 64)
    job.task_buffers = &ws.task_buffers;
    job.next_task = &next_task;
    const bool parts[2] = {job.split_v > 0, job.split_v < h};
    for (int p = 0; p < 2; ++p)
        if (!parts[p]) std::fill(job.seam_c[p], job.seam_c[p] + ow, 0u);  // no rows: nothing received
    const int np = int(parts[0]) + int(parts[1]);
    const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
    if (pipelined_row_chunks(simd::testing::kernel_policy().pipelined_row_chunks, threads, np))
        pipelined_in_row_chunks(kernels, job, options.threads, threads, ws);
    else
        pipelined_in_column_ranges(kernels, job, options.threads, threads);
    kernels.seam(job);
    return {(long long)w * h, dropped.load(), e};
}

}  // namespace

PrewarpStats fast_prewarp(Isa isa, const ReliefTexture& relief, const PrewarpCoefficients& k,
                          const PrewarpOptions& options, const PrewarpExtent& e, PrewarpWorkspace& ws,
                          ImageRGBA8& out) {
    const PrewarpTables ref_tables = PrewarpTables::build(k, relief.quant);
    PrewarpStats stats;
    if (isa == Isa::avx512) {
#if RTM_AVX512_KERNELS
        const fast::FastTables tables = fast::make_fast_tables(ref_tables);
        if (options.method == Reconstruction::pipelined)
            stats = fast_pipelined({&fast::pipelined_part, &fast::pipelined_chunk, &fast::pipelined_composite,
                                    &fast::pipelined_seam},
                                   relief, k, options, e, ref_tables, tables, ws, out);
        else
            stats = fast_two_pass({&fast::horizontal_steps, &fast::vertical_steps}, relief, k, options, e, ref_tables,
                                  tables, ws, out);
#endif
    } else if (options.method == Reconstruction::pipelined) {
        stats = fast_pipelined(simd::hwy_pipelined_kernels(isa), relief, k, options, e, ref_tables, fast::FastTables{},
                               ws, out);
    } else {
        stats = fast_two_pass(simd::hwy_two_pass_kernels(isa), relief, k, options, e, ref_tables, fast::FastTables{},
                              ws, out);
    }
    stats.isa = isa;
    return stats;
}

}  // namespace rtm
