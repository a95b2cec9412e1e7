#include "warp/simd/schedule.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>

#include "warp/simd/hwy_pipelined.h"
#include "warp/simd/hwy_two_pass.h"
#include "warp/simd/kernel_policy.h"
#include "warp/isa.h"
#include "warp/line_warp.h"
#include "warp/tables.h"
#include "warp/task_arenas.h"

namespace rtm {

namespace {

// Largest output side the kernels accept: pixel indices and span ends stay exact in float far below 2^24.
constexpr int kMaxSide = 1 << 22;
// Largest output the kernels accept: the column kernels' scatter (StoreRows, warp/simd/hwy_columns-inl.h) addresses
// pixels by 32-bit offsets of up to the whole image from its last storage row. 2^31 - 16 pixels is 8 GiB of RGBA8.
constexpr long long kMaxPixels = (1ll << 31) - 16;

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
        task_arena_for(threads).execute(loop);
    else
        loop();
}

// Two-pass: rows per band (steps warped horizontally before the vertical pass takes them) and bands in flight.
// Two threads, bumps 1024^2: bands of 4 rows 3.08 ms, 8 rows 2.97, 16 rows 2.79, 32 rows 2.66, 64 rows 2.74 (the
// pipeline's cost per band). One thread warps a band and steps the columns through it on one core, one band at a
// time: bands of 16 rows in one buffer, which the next band writes again while it is still in the core's caches.
// Against the pipeline's 32 rows in four buffers (a Zen 4 guest, one thread, medians of 9 interleaved rounds, `avx512`
// but where named): bumps 2048^2 two-pass 23.12 -> 22.86 ms, bricks 2048^2 13.50 -> 12.37, ridges 2048^2 25.50 ->
// 24.72, bumps 1024^2 5.06 -> 4.86, bricks 4096^2 48.2 -> 46.5, `avx2` bumps 2048^2 31.14 -> 28.42; 256^2 and below
// the same (docs/perf-history.md, session 36). Until then one thread took the pipeline's bands (measured before the
// Highway kernels: no difference between 1 and 64 rows).
constexpr int kBandRows = 32;
constexpr int kBandSlots = 4;
constexpr int kBandRowsOneThread = 16;

// Pixels the vertical pass copied as still pixels so far (simd::testing::vertical_still_copies).
std::atomic<long long> g_vertical_still_copies{0};

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
#if defined(__x86_64__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("avx512vbmi") && __builtin_cpu_supports("avx512vnni") &&
           __builtin_cpu_supports("bmi2");
#else
    return false;  // not x86-64
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
        const bool id = ok && tab.k1d[q] == 0.0f && tab.k2d[q] == 0.0f && tab.rcp[q] == 1.0f;
        t.identity[q] = id ? 0x80 : 0;
        t.level[q][0] = v[0], t.level[q][1] = v[1], t.level[q][2] = v[2], t.level[q][3] = 0.0f;
        if (id && !t.any_identity)
            t.identity_lo = t.identity_hi = q;
        else if (id && t.identity_hi == q - 1)
            t.identity_hi = q;
        t.any_identity = t.any_identity || id;
    }
    return t;
}

}  // namespace fast

namespace simd::testing {
namespace {
FastKernelPolicy g_policy;
}
const FastKernelPolicy& kernel_policy() { return g_policy; }
long long vertical_still_copies() { return g_vertical_still_copies.load(std::memory_order_relaxed); }
ScopedKernelPolicy::ScopedKernelPolicy(const FastKernelPolicy& policy) : saved_(g_policy) { g_policy = policy; }
ScopedKernelPolicy::~ScopedKernelPolicy() { g_policy = saved_; }
}  // namespace simd::testing

namespace {
// FastKernelPolicy::avx2_blend_stores resolved for this CPU.
bool blend_stores() {
    switch (simd::testing::kernel_policy().avx2_blend_stores) {
        case KernelChoice::always: return true;
        case KernelChoice::never: return false;
        case KernelChoice::automatic: break;
    }
    return avx2_masked_store_slow();
}
}  // namespace

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
    if (!(options.method == Reconstruction::two_pass ? !!simd::hwy_two_pass_kernels(isa).vertical
                                                     : !!simd::hwy_pipelined_kernels(isa).part))
        return false;
    if (!relief.breaks.empty() && relief.breaks.size() != relief.texels.size()) return false;
    if (k.side == ViewSide::on_plane || relief.width <= 0 || relief.height <= 0) return false;
    const long long ow = (long long)relief.width + e.left + e.right, oh = (long long)relief.height + e.bottom + e.top;
    return ow <= kMaxSide && oh <= kMaxSide && ow * oh <= kMaxPixels;
}

namespace {

// ---- Still pixels in the vertical pass (paper section 5: the brick wall) ----
//
// The row warps copy runs of still texels (zero displacement) already; this copies them in the vertical pass too
// (brick wall 1024^2 against the same wall lifted off zero, 1 thread, CPU time, `rtm bench-skips --wall-only`:
// 0.99x -> 1.16x to 1.24x AVX-512, 1.03x -> 1.20x to 1.24x AVX2; docs/BENCHMARKS.md says why not more). A pixel
// of the intermediate image on the centre of its own output line (v == y + 0.5: a still texel that no later
// sample of its row overwrote) whose column's last sample is the previous step's pixel on the centre of its own
// line (y - 1 + 0.5 in the bottom part, y + 1 + 0.5 in the top part) is drawn by the column kernels as a span one
// pixel long holding the one centre y + 0.5 at t = (y + 0.5 - pa) * (1 / (pb - pa)) = +-1 * (1 / +-1) = 1
// exactly: the pixel gets its own colour with alpha 255 (lerp8 gives b at t = 1), and the column keeps the pixel
// as its last sample; nothing else is written or changes. So where all columns of a group of 16 (the kernels'
// column granularity) hold such pixels in consecutive steps, those steps are a copy of the band's colours into
// their own output lines, at memory speed, and the columns' state becomes the last copied step's pixel; the
// kernels run on the other steps only, in step order per group as they require. Exact by construction for any
// relief and view (the test is on the intermediate pixels themselves); the first step of each part is never
// copied (a column starts afresh there, and the kernels keep the bottom part's last samples for the seam).

using fast::step_line;

struct StillColumns {
    const simd::TwoPassKernels* kernels = nullptr;
    const fast::TwoPassJob* job = nullptr;
    // Per group of 16 columns: whether the last step handed to the vertical pass held still pixels in all its
    // columns (a band's first step continues the previous band's last).
    uint8_t* group_still = nullptr;
};

// The vertical pass of steps [s0, s1) (one band, at most 32 steps) for columns [x0, x1), x0 a multiple of 16: the
// kernels' vertical_steps, with the still steps of each group copied (see above). Neighbouring groups with the same
// steps to copy (a brick's width) go together: one kernel call per run of steps for all of them. Only the steps of
// `still_rows` (the horizontal pass's: rows with a texel at zero displacement) are tested: elsewhere a pixel on its
// own line's centre is rare (the kernels draw it the same), and a band without such rows (a relief or a view without
// still texels) is the kernels' alone, the test's reads of the band saved.
void vertical_with_still(const StillColumns& sc, int s0, int s1, uint32_t still_rows, const uint32_t* band_c,
                         const float* band_v, size_t stride, int x0, int x1) {
    const fast::TwoPassJob& job = *sc.job;
    const simd::TwoPassKernels& k = *sc.kernels;
    if (!job.copy_still || !still_rows) {
        // No step of this band is copied, and so none of the next band's first step (a group's flag says whether
        // the last step handed to the vertical pass was still in all its columns).
        if (job.copy_still) std::fill(sc.group_still + (x0 >> 4), sc.group_still + ((x1 + 15) >> 4), uint8_t(0));
        k.vertical(job, s0, s1, band_c, band_v, stride, x0, x1);
        return;
    }
    const int h = job.relief->height, ow = job.out->width, oh = job.out->height;
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    // The kernels on steps [a, b) of this band for columns [c0, c1).
    auto kernel_steps = [&](int a, int b, int c0, int c1) {
        if (a < b)
            k.vertical(job, a, b, band_c + size_t(a - s0) * stride, band_v + size_t(a - s0) * stride, stride, c0, c1);
    };
    // The first band: the call that takes step 0 clears the columns' output, all lines; for all groups at once
    // (group by group, 64-byte pieces of every line, it cost 1.3 ms at 1024^2).
    int first = s0;
    if (s0 == 0) {
        k.vertical(job, 0, 1, band_c, band_v, stride, x0, x1);
        first = 1;
    }
    // Steps a column starts afresh at (step 0, and split_v where the top part starts, also on a band's first step):
    // never copied.
    uint32_t fresh = s0 == 0 ? 1u : 0u;
    if (job.split_v >= s0 && job.split_v < s1) fresh |= 1u << (job.split_v - s0);
    const uint32_t first_bits = ~fresh;
    long long copied = 0;
    int gx0 = x0;
    uint32_t copy = 0;
    auto group_copy = [&](int g0) {
        const int width = std::min(16, x1 - g0);
        const uint32_t still = k.still(job, s0, s1, still_rows, band_c, band_v, stride, g0, width);
        uint8_t& prev = sc.group_still[g0 >> 4];
        const uint32_t c = still & ((still << 1) | prev) & first_bits;
        prev = uint8_t((still >> (s1 - 1 - s0)) & 1u);
        return c;
    };
    if (x0 < x1) copy = group_copy(x0);
    while (gx0 < x1) {
        // The run of groups [gx0, gx1) with the same steps to copy.
        int gx1 = std::min(gx0 + 16, x1);
        uint32_t next = 0;
        while (gx1 < x1 && (next = group_copy(gx1)) == copy) gx1 = std::min(gx1 + 16, x1);
        if (!copy) {
            kernel_steps(first, s1, gx0, gx1);
        } else {
            for (int st = first; st < s1;) {
                const bool copy_here = (copy >> (st - s0)) & 1u;
                int e = st;
                while (e < s1 && bool((copy >> (e - s0)) & 1u) == copy_here) ++e;
                if (!copy_here) {
                    kernel_steps(st, e, gx0, gx1);
                } else {
                    for (int i = st; i < e; ++i) {
                        const uint32_t* c = band_c + size_t(i - s0) * stride;
                        uint32_t* o = out + size_t(oh - 1 - step_line(job, i)) * size_t(ow);
                        for (int x = gx0; x < gx1; ++x) o[x] = c[x] | 0xFF000000u;
                    }
                    copied += (long long)(e - st) * (gx1 - gx0);
                    // The columns' last sample: step e - 1's pixel (each column had one already: step st - 1's
                    // pixels were still too).
                    const int y = step_line(job, e - 1);
                    const uint32_t* c = band_c + size_t(e - 1 - s0) * stride;
                    for (int x = gx0; x < gx1; ++x) {
                        job.col_v[x] = float(y) + 0.5f;
                        job.col_c[x] = c[x];
                    }
                    // And its carried displacement (a copied pixel is the same whether or not it was connected to
                    // the one before: a one-pixel span at t = 1 or a point on the same pixel).
                    if (job.threshold > 0.0f) {
                        const float* d = band_v + size_t(e - 1 - s0) * stride + job.d_offset;
                        for (int x = gx0; x < gx1; ++x) job.col_d[x] = d[x];
                    }
                    // The span across the epipole, drawn by the call that reaches step h.
                    if (e == h) k.vertical(job, h, h, band_c, band_v, stride, gx0, gx1);
                }
                st = e;
            }
        }
        gx0 = gx1;
        copy = next;
    }
    if (copied) g_vertical_still_copies.fetch_add(copied, std::memory_order_relaxed);
}

PrewarpStats fast_two_pass(const simd::TwoPassKernels& kernels, const ReliefTexture& relief,
                           const PrewarpCoefficients& k, const PrewarpOptions& options, const PrewarpExtent& e,
                           const PrewarpTables& ref_tables, const fast::FastTables& tables, PrewarpWorkspace& ws,
                           ImageRGBA8& out) {
    const int w = relief.width, h = relief.height;
    const int ow = w + e.left + e.right, oh = h + e.bottom + e.top;
    std::atomic<long long> dropped{0};
    ensure_size(out, ow, oh);
    static_assert(kBandRows <= 32 && kBandRowsOneThread <= 32, "vertical_with_still keeps a band's steps in 32 bits");
    // Rows of the workspace's intermediate images (width rounded up to 16, 64-byte aligned thanks to the spare
    // row): 0 the column state (v, colour), 1 the seam, then (from kStateRows) the bands.
    constexpr int kStateRows = 2;
    const int stride = (ow + 15) / 16 * 16;
    const bool one_thread = options.threads == 1;
    const int band = one_thread ? kBandRowsOneThread : kBandRows, slots = one_thread ? 1 : kBandSlots;
    // One more row: the groups' still flags (vertical_with_still).
    ensure_size(ws.mid_color, stride, kStateRows + band * slots + 2);
    // With a discontinuity threshold the columns carry each sample's displacement (TwoPassJob::threshold).
    const float threshold = float(relief.discontinuity_threshold);
    const bool carry_d = threshold > 0.0f;
    // After the bands: one row scratch per band slot for the Highway kernels (3 source widths of floats, 4 with a
    // threshold: hwy_two_pass.h).
    const size_t scratch_rows = ((carry_d ? 4 : 3) * size_t(w) + size_t(stride) - 1) / size_t(stride);
    // With a threshold, then: the columns' carried displacement, the seam's, and the bands' (each band's d rows
    // d_offset floats after its v rows).
    const int d_rows = carry_d ? 2 + band * slots : 0;
    const size_t d_base = kStateRows + size_t(band * slots) + scratch_rows * size_t(slots);
    ensure_size(ws.mid_v, stride, int(d_base) + d_rows + 1);
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
    job.copy_still = options.copy_still_runs;
    job.reverse = simd::testing::kernel_policy().two_pass_reverse;
    job.redo_forwards = simd::testing::kernel_policy().two_pass_redo_forwards;
    job.blend_stores = blend_stores();
    job.dropped = &dropped;
    job.breaks = relief.breaks.empty() ? nullptr : relief.breaks.data();
    if (carry_d) {
        job.threshold = threshold;
        job.col_d = mv + d_base * size_t(stride);
        job.seam_d = job.col_d + stride;
        job.d_offset = std::ptrdiff_t(d_base + 2 - kStateRows) * stride;  // band_v(slot) + d_offset: band_d(slot)
    }
    auto band_c = [&](int slot) { return mc + size_t(kStateRows + slot * band) * stride; };
    auto band_v = [&](int slot) { return mv + size_t(kStateRows + slot * band) * stride; };
    const int bands = (h + band - 1) / band;
    // Per band slot: the rows of its band that may hold still pixels (HorizontalStepsFn), written by its horizontal
    // pass, read by its vertical pass (after it, in the pipeline too).
    uint32_t still_rows[kBandSlots] = {};
    auto horizontal = [&](int b) {
        still_rows[b % slots] = kernels.horizontal(
            job, b * band, std::min(h, (b + 1) * band), band_c(b % slots), band_v(b % slots), size_t(stride),
            mv + (size_t(kStateRows + band * slots) + (b % slots) * scratch_rows) * stride);
    };
    StillColumns still;
    still.kernels = &kernels;
    still.job = &job;
    still.group_still = reinterpret_cast<uint8_t*>(mc + size_t(kStateRows + band * slots) * stride);
    auto vertical = [&](int b, int x0, int x1) {
        vertical_with_still(still, b * band, std::min(h, (b + 1) * band), still_rows[b % slots], band_c(b % slots),
                            band_v(b % slots), size_t(stride), x0, x1);
    };
    if (one_thread || bands < 2) {
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
        task_arena_for(options.threads).execute(pipeline);
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
        for (int t = t0; t < t1; ++t) kernels.part(job, t, tasks[t].part, tasks[t].x0, tasks[t].x1);
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
            fast::PipelinedChunk& c = chunks[nc];
            c.task = nc++;
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
    // The seam rows (the last sample of each part per column; rows 2 and 3 its displacement, with a threshold) live in
    // the intermediate images, unused otherwise.
    ensure_size(ws.mid_color, ow, 2);
    ensure_size(ws.mid_v, ow, 4);
    fast::PipelinedJob job;
    job.relief = &relief;
    job.copy_still = options.copy_still_runs;
    job.reverse = simd::testing::kernel_policy().pipelined_reverse;
    job.blend_stores = blend_stores();
    job.tables = &tables;
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
    job.breaks = relief.breaks.empty() ? nullptr : relief.breaks.data();
    job.threshold = float(relief.discontinuity_threshold);
    job.ref_tables = &ref_tables;
    job.seam_d[0] = ws.mid_v.row(2);
    job.seam_d[1] = ws.mid_v.row(3);
    if (ws.task_buffers.size() < 2 * 64) ws.task_buffers.resize(2 * 64);  // the most tasks (two parts of 64)
    if (ws.reverse_buffers.size() < 2 * 64) ws.reverse_buffers.resize(2 * 64);
    job.task_buffers = &ws.task_buffers;
    job.reverse_buffers = &ws.reverse_buffers;
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

void prefetch_relief_row(const ReliefTexture& relief, int r) {
    if (r < 0 || r >= relief.height) return;
    const char* p = reinterpret_cast<const char*>(relief.texels.data() + size_t(r) * size_t(relief.width));
    const size_t bytes = size_t(relief.width) * sizeof(ReliefTexel);
    for (size_t b = 0; b < bytes; b += 64) __builtin_prefetch(p + b, 0, 3);  // 64: a cache line
}

PrewarpStats fast_prewarp(Isa isa, const ReliefTexture& relief, const PrewarpCoefficients& k,
                          const PrewarpOptions& options, const PrewarpExtent& e, PrewarpWorkspace& ws,
                          ImageRGBA8& out) {
    const PrewarpTables ref_tables = PrewarpTables::build(k, relief.quant);
    const fast::FastTables tables = fast::make_fast_tables(ref_tables);
    PrewarpStats stats;
    if (options.method == Reconstruction::pipelined) {
        stats = fast_pipelined(simd::hwy_pipelined_kernels(isa), relief, k, options, e, ref_tables, tables, ws, out);
    } else {
        stats = fast_two_pass(simd::hwy_two_pass_kernels(isa), relief, k, options, e, ref_tables, tables, ws, out);
    }
    stats.isa = isa;
    return stats;
}

}  // namespace rtm
