// The Highway pipelined kernel (see hwy_pipelined.h). This file is compiled once per target by
// hwy/foreach_target.h, with an SSE4 baseline on x86-64 and -ffp-contract=off (warp/CMakeLists.txt).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "warp/simd/hwy_pipelined.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "warp/line_warp.h"
#include "warp/simd/hwy_pipelined.h"
#include "warp/simd/hwy_row-inl.h"
#include "warp/simd/schedule.h"
#include "warp/tables.h"

// Target-independent helpers, compiled on the first of foreach_target's passes (the per-target code below uses them).
#ifndef RTM_WARP_SIMD_HWY_PIPELINED_HELPERS_
#define RTM_WARP_SIMD_HWY_PIPELINED_HELPERS_
namespace rtm::simd {
namespace {

// The rows of part 0 (bottom up to the split) or 1 (top down to it): the first (v order), the step, how many, and
// the output v-rows [y0, y1) the part draws.
struct PartRows {
    int first, step, count, y0, y1;
};

PartRows part_rows(const fast::PipelinedJob& job, int part) {
    const int h = job.relief->height, s = job.split_v;
    if (part == 0) return {0, 1, s, 0, job.ysplit};
    return {h - 1, -1, h - s, job.ysplit, job.out->height};
}

// One task's buffers, carved out of its float vector in the workspace (PrewarpWorkspace::task_buffers; the task's
// index in the pre-warp, the same task in every pre-warp of the same views and threads, whichever thread runs it),
// which grows to the largest relief and output seen and never shrinks (steady state allocates nothing).
struct PipeBuffers {
    float* row;    // one row's samples: positions, row coordinates, colours, displacements (RowScratch)
    uint32_t* rc;  // one row of pixels: packed colour, final row coordinate and (with a threshold) displacement
    float *rv, *rd;
    // The column state: each column's last sample of the previous row (prev_*) and of the row being warped (cur_*),
    // ok -1 where the column has one and 0 elsewhere; d its displacement (with a threshold).
    uint32_t *prev_c, *cur_c;
    float *prev_v, *cur_v;
    int32_t *prev_ok, *cur_ok;
    float *prev_d, *cur_d;
};

PipeBuffers task_buffers(const fast::PipelinedJob& job, int task) {
    const int w = job.relief->width, ow = job.out->width;
    std::vector<float>& v = (*job.task_buffers)[size_t(task)];
    // Arrays are read and written (StoreOwned: on SSE4 and NEON, and AVX2 where it blends, a whole vector) up to a
    // whole vector past the output width: 64 lanes is SVE's most. Sizes are rounded up to 64, so that outputs a few
    // pixels wider (the next view's margins) fit.
    const size_t n = (size_t(ow) + 63) / 64 * 64 + 64, nr = 4 * ((size_t(w) + 63) / 64 * 64);
    if (v.size() < nr + 11 * n) v.resize(nr + 11 * n);
    float* p = v.data();
    PipeBuffers b;
    b.row = p;
    p += nr;
    auto take = [&](auto*& q) {
        q = reinterpret_cast<std::remove_reference_t<decltype(q)>>(p);
        p += n;
    };
    take(b.rc), take(b.rv), take(b.prev_c), take(b.cur_c), take(b.prev_v), take(b.cur_v);
    take(b.prev_ok), take(b.cur_ok), take(b.rd), take(b.prev_d), take(b.cur_d);
    return b;
}

// Reverse mode's buffers of task `task` (the workspace's: PrewarpWorkspace::reverse_buffers), made at its first use.
fast::ReverseBuffers& reverse_buffers(const fast::PipelinedJob& job, int task) {
    std::shared_ptr<fast::ReverseBuffers>& b = (*job.reverse_buffers)[size_t(task)];
    if (!b) b = std::make_shared<fast::ReverseBuffers>();
    return *b;
}

void clear_part(const fast::PipelinedJob& job, int part, int x0, int x1) {
    const int ow = job.out->width, oh = job.out->height;
    const PartRows p = part_rows(job, part);
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    for (int y = p.y0; y < p.y1; ++y)
        std::memset(out + size_t(oh - 1 - y) * size_t(ow) + size_t(x0), 0, size_t(x1 - x0) * 4);
}

}  // namespace
}  // namespace rtm::simd
#endif  // RTM_WARP_SIMD_HWY_PIPELINED_HELPERS_

HWY_BEFORE_NAMESPACE();
namespace rtm::simd::HWY_NAMESPACE {

// The range of finite row coordinates of the samples a task warped (lo > hi: none).
struct RowRange {
    float lo, hi;
};

// What the reference's put() does for each pixel the row warp emits, for the pixels xa .. xb of one group (WarpRow's
// range) at once, clipped to columns [x0, x1): connect the column's sample of the previous row to the new one
// (raster_span along the column) or start a run with it (raster_point), drawing only the output rows of `o`, and
// make the new sample the column's current one. A column that receives several pixels from a row (a foldover along
// the row) is handed each of them in the row warp's order, each drawn from the previous row's sample, as the
// reference draws them. With `drawn`, adds the rows each span covers (at most oh a column) to it. With a `threshold`
// (> 0: the relief's discontinuity threshold), a column's sample of the previous row is joined to the new one only
// where their displacements (prev_d, rd) differ by at most the threshold (the reference's column_connected).
struct Emitter {
    static constexpr int kScalarRun = 2;  // runs of fewer pixels go column by column (One)
    PipeBuffers& b;
    ColumnTarget o;
    int x0, x1;
    float* drawn = nullptr;
    bool copy = false;  // PrewarpOptions::copy_still_runs: still steps are copies (ColumnDraw)
    float threshold = 0.0f;

    // Column x's pixel of the row, as the reference's put() draws it (raster_span from the column's sample of the
    // previous row, or raster_point), one column alone.
    void One(int x) const {
        const float v = b.rv[x];
        if (!std::isfinite(v)) return;
        const uint32_t c = b.rc[x];
        const float d = threshold > 0.0f ? b.rd[x] : 0.0f;
        const bool joined = b.prev_ok[x] && displacements_joined(b.prev_d[x], d, threshold);
        auto put = [&](int y, Rgba8 cc, float) {
            if (y >= o.y0 && y < o.y1) o.vline(y)[x] = pack(cc);
        };
        if (joined) {
            raster_span(b.prev_v[x], unpack(b.prev_c[x]), 0.0f, v, unpack(c), 0.0f, o.oh, put);
            if (drawn) *drawn += std::min(std::abs(v - b.prev_v[x]), float(o.oh));
        } else {
            raster_point(v, unpack(c), 0.0f, o.oh, put);
        }
        b.cur_v[x] = v;
        b.cur_c[x] = c;
        b.cur_ok[x] = -1;
        b.cur_d[x] = d;
    }

    // Columns x .. x + N - 1 of a run that ends at xb: with kFull all of them in it (x + N - 1 <= xb), loaded whole
    // with no lane mask, and where every lane has a new sample the row's state stored whole, not blended with what it
    // held (`avx2` bumps 256^2 pipelined, instructions counted under qemu: 6.9% fewer in the Emitter, 3.3% in the
    // pre-warp); else the lanes up to xb, masked.
    template <bool kFull>
    HWY_INLINE void Vector(int x, int xb) const {
        const hn::ScalableTag<float> df;
        const hn::RebindToSigned<decltype(df)> di;
        using VF = hn::Vec<decltype(df)>;
        using VI = hn::Vec<decltype(di)>;
        const int N = int(hn::Lanes(df));
        const auto m = hn::FirstN(df, size_t(xb - x + 1));  // all lanes where kFull (not used there)
        const auto mi = hn::RebindMask(di, m);
        // (The rows are readable a whole vector past the run: SSE4's MaskedLoad needs alignment.)
        VF v = hn::LoadU(df, b.rv + x);
        VI c = hn::LoadU(di, reinterpret_cast<const int32_t*>(b.rc + x));
        if constexpr (!kFull) {
            v = hn::IfThenElseZero(m, v);
            c = hn::IfThenElseZero(mi, c);
        }
        auto fin = hn::IsFinite(v);  // the reference skips emissions with a non-finite row coordinate
        if constexpr (!kFull) fin = hn::And(m, fin);
        if (hn::AllFalse(df, fin)) return;
        const auto fini = hn::RebindMask(di, fin);
        const bool all = kFull && hn::AllTrue(df, fin);
        auto pok = hn::And(fin, hn::RebindMask(df, hn::Ne(hn::LoadU(di, b.prev_ok + x), hn::Zero(di))));
        if (threshold > 0.0f) {
            VF d = hn::LoadU(df, b.rd + x);
            if constexpr (!kFull) d = hn::IfThenElseZero(m, d);
            pok = hn::And(pok, WithinThreshold(df, hn::LoadU(df, b.prev_d + x), d, threshold));
            if (all)
                hn::StoreU(d, df, b.cur_d + x);
            else
                StoreOwned(d, fin, df, b.cur_d + x, o.blend);
        }
        const VF pv = hn::LoadU(df, b.prev_v + x);
        const VI pc = hn::LoadU(di, reinterpret_cast<const int32_t*>(b.prev_c + x));
        if (all) {
            hn::StoreU(v, df, b.cur_v + x);
            hn::StoreU(c, di, reinterpret_cast<int32_t*>(b.cur_c + x));
            hn::StoreU(hn::Set(di, -1), di, b.cur_ok + x);
        } else {
            StoreOwned(v, fin, df, b.cur_v + x, o.blend);
            StoreOwned(c, fini, di, reinterpret_cast<int32_t*>(b.cur_c + x), o.blend);
            StoreOwned(hn::Set(di, -1), fini, di, b.cur_ok + x, o.blend);
        }
        ColumnDraw(df, o, x, x + N <= x1, copy, fin, pok, pv, pc, v, c);
        if (drawn) [[unlikely]] {
            const VF d = hn::Min(hn::Abs(hn::Sub(v, pv)), hn::Set(df, float(o.oh)));
            *drawn += hn::GetLane(hn::SumOfLanes(df, hn::IfThenElseZero(pok, d)));
        }
    }

    void operator()(int xa, int xb) const {
        const int N = int(hn::Lanes(hn::ScalableTag<float>()));
        xa = std::max(xa, x0);
        xb = std::min(xb, x1 - 1);
        // Runs of one or two pixels (rows that marks or foldovers cut into pieces), column by column: a vector step
        // for them cost about 40 ns a pixel (ridges 256^2 marked at 5% of its range, avx2: 47,600 Emitter calls of
        // 1.2 pixels a pre-warp, 2.0 ms against the generic kernels' 1.2).
        if (xb - xa < kScalarRun) {
            for (int x = xa; x <= xb; ++x) One(x);
            return;
        }
        for (int x = xa; x <= xb; x += N) {
            if (x + N - 1 <= xb)
                Vector<true>(x, xb);
            else
                Vector<false>(x, xb);
        }
    }
};

// Reverse mode: the emissions of a row, as the Emitter receives them (columns [x0, x1)), into a log, and each
// column's last one into the reverse buffers' fin_* (with `with_d`, their displacements too).
struct Logger {
    PipeBuffers& b;
    fast::ReverseBuffers& r;
    fast::EmitLog& log;
    int x0, x1;
    bool with_d = false;
    bool blend = false;  // the job's blend_stores (StoreOwned)

    void operator()(int xa, int xb) const {
        const hn::ScalableTag<float> df;
        const hn::RebindToSigned<decltype(df)> di;
        using VF = hn::Vec<decltype(df)>;
        using VI = hn::Vec<decltype(di)>;
        const int N = int(hn::Lanes(df));
        xa = std::max(xa, x0);
        xb = std::min(xb, x1 - 1);
        if (xa > xb) return;
        // Entries of N lanes: the buffers are the thread's, shared by the targets, whose N differ.
        const size_t want = log.n + size_t((xb - xa) / N + 1);
        if (want > log.x.size() || want * size_t(N) > log.v.size()) [[unlikely]] {
            const size_t cap = std::max(want, 2 * log.x.size());
            log.x.resize(cap);
            log.v.resize(cap * size_t(N));
            log.d.resize(cap * size_t(N));
            log.c.resize(cap * size_t(N));
        }
        const VF nan = hn::Set(df, std::numeric_limits<float>::quiet_NaN());
        for (int x = xa; x <= xb; x += N) {
            const auto m = hn::FirstN(df, size_t(xb - x + 1));
            const auto mi = hn::RebindMask(di, m);
            const VF v = hn::IfThenElseZero(m, hn::LoadU(df, b.rv + x));
            const auto fin = hn::And(m, hn::IsFinite(v));
            if (hn::AllFalse(df, fin)) continue;
            const auto fini = hn::RebindMask(di, fin);
            const VI c = hn::IfThenElseZero(mi, hn::LoadU(di, reinterpret_cast<const int32_t*>(b.rc + x)));
            log.x[log.n] = x;
            hn::StoreU(hn::IfThenElse(fin, v, nan), df, log.v.data() + log.n * size_t(N));
            hn::StoreU(c, di, reinterpret_cast<int32_t*>(log.c.data() + log.n * size_t(N)));
            ++log.n;
            StoreOwned(v, fin, df, r.fin_v.data() + x, blend);
            StoreOwned(c, fini, di, reinterpret_cast<int32_t*>(r.fin_c.data() + x), blend);
            StoreOwned(hn::Set(di, -1), fini, di, r.fin_ok.data() + x, blend);
            if (with_d) {
                const VF d = hn::IfThenElseZero(m, hn::LoadU(df, b.rd + x));
                hn::StoreU(d, df, log.d.data() + (log.n - 1) * size_t(N));
                StoreOwned(d, fin, df, r.fin_d.data() + x, blend);
            }
        }
    }
};

// WarpRow's range for the pipelined kernel: the groups of pixels of a row go to the Emitter (or Logger) in runs as
// long as possible. A group that extends the pending run (adjacent to it) joins it; any other (apart from it, or
// writing over its pixels: a foldover along the row) hands the pending run to the Emitter first, before the group's
// pixels are written. Each column of a run was written once since its run began, and the runs reach the Emitter in
// the row warp's order, so every pixel is drawn as the reference draws it, with one Emitter call for most rows in
// place of one per group (bumps 256^2 and 1024^2: 0.93 -> 0.80 ms and 16.8 -> 14.1 ms of CPU on avx2).
template <class E>
struct Coalescer {
    const E& emit;
    mutable int pa = 0, pb = -1;  // the pending run (pa > pb: none)

    // Inlined into the row warp's loops: most groups extend the pending run (a call each cost bricks 1024^2 pipelined
    // 7% of its time in the function's entry and exit alone, avx512).
    HWY_INLINE void before(int xa, int xb) const {
        if (xb == pa - 1 && pa <= pb) {
            pa = xa;
        } else if (xa == pb + 1 && pa <= pb) {
            pb = xb;
        } else {
            restart(xa, xb);
        }
    }
    // Hands the pending run (if any) to the emitter and starts one with xa .. xb.
    HWY_NOINLINE void restart(int xa, int xb) const {
        if (pa <= pb) emit(pa, pb);
        pa = xa, pb = xb;
    }
    void done() const {
        if (pa <= pb) emit(pa, pb);
        pa = 0, pb = -1;
    }
};

// Widens `range` by the row coordinates of the row's samples that take part (position and row coordinate finite):
// the rows a scratch chunk may have drawn, so that the composite reads only those. A vector at a time (the scalar
// loop took 0.3 to 0.6 ms of a 3.4 ms chunk, bricks 1024^2 on avx2: the second chunk's rows, measured against the
// first's, ran 1.5 times slower).
HWY_INLINE void TrackRange(const RowScratch& s, int w, RowRange& range) {
    const hn::ScalableTag<float> df;
    using VF = hn::Vec<decltype(df)>;
    const int N = int(hn::Lanes(df));
    const VF inf = hn::Set(df, std::numeric_limits<float>::infinity()), ninf = hn::Neg(inf);
    VF lo = inf, hi = ninf;
    int x = 0;
    for (; x + N <= w; x += N) {
        const VF v = hn::LoadU(df, s.v + x);
        const auto take = hn::And(hn::IsFinite(hn::LoadU(df, s.pos + x)), hn::IsFinite(v));
        lo = hn::Min(lo, hn::IfThenElse(take, v, inf));
        hi = hn::Max(hi, hn::IfThenElse(take, v, ninf));
    }
    range.lo = std::min(range.lo, hn::GetLane(hn::MinOfLanes(df, lo)));
    range.hi = std::max(range.hi, hn::GetLane(hn::MaxOfLanes(df, hi)));
    for (; x < w; ++x)
        if (std::isfinite(s.pos[x]) && std::isfinite(s.v[x])) {
            range.lo = std::min(range.lo, s.v[x]);
            range.hi = std::max(range.hi, s.v[x]);
        }
}

// A row whose spans cover more than this many rows per column switches the rest of the part to reverse mode
// (RunRows; the threshold of the hand-written AVX-512 kernel it replaced).
constexpr float kReverseDrawn = 3.0f;

// Rows [r0, r1) of part `part` (counted in the part's order), columns [x0, x1), drawn into `pixels` (an image of
// the output's size; only the part's output rows). A task that does not start at its part's first row starts from
// the row before it, warped without drawing: the column state after it is the one the reference carries into the
// task's first row, forwards or in reverse mode. Returns the range of the row coordinates of the samples warped
// (with `track`).
//
// Reverse mode (the hand-written AVX-512 kernel's reverse_rows before it; FastKernelPolicy::
// pipelined_reverse): the rest of the part's rows with the painter's algorithm run backwards. Row j's emissions are
// logged, then replayed from the last to the first once row j - step has been warped (its final samples are the
// ones row j's spans start from), the rows from the part's last back to the first in reverse mode (whose spans
// start from the samples the forward rows before it left), and each pixel is written only by the first emission
// that reaches it, the last in the forward order: the same image, each pixel written once where the forward order
// writes it again and again (ridges: long column spans that later rows overwrite). Each column keeps the interval
// of rows written so far, or a bitmask where they are not one interval (ColumnDrawRev). Automatic: every 4th row
// measures the rows its spans cover per column, and more than kReverseDrawn switches.
//
// Discontinuity marks (PipelinedJob::breaks) break the row warp's spans (WarpRow's marks); a threshold carries each
// texel's displacement through the row warp (RowOut::attr2) into the Emitter, or the log and the replay.
RowRange RunRows(const fast::PipelinedJob& job, int task, int part, int r0, int r1, int x0, int x1, uint32_t* pixels,
                 bool track) {
    const ReliefTexture& t = *job.relief;
    const int w = t.width, h = t.height, ow = job.out->width, oh = job.out->height;
    const PartRows p = part_rows(job, part);
    PipeBuffers b = task_buffers(job, task);
    const bool with_d = job.threshold > 0.0f;
    const RowScratch s{b.row, b.row + w, reinterpret_cast<uint32_t*>(b.row + 2 * size_t(w)),
                       with_d ? b.row + 3 * size_t(w) : nullptr};
    uint32_t* rc = b.rc;
    float* rv = b.rv;
    RowOut out{rc, rv, job.copy_still};
    out.blend = job.blend_stores;
    if (with_d) out.attr2 = b.rd;
    std::fill(b.prev_ok + x0, b.prev_ok + x1, 0);
    RowRange range{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
    // Row j set up, row `next` (the one set up after it) prefetched; returns the texels dropped and whether the row
    // has still texels. `marks`: the row's.
    const uint8_t* marks = nullptr;
    auto prepare = [&](int j, int next) {
        prefetch_relief_row(t, h - 1 - next);
        const PreparedRow prep = PrepareRow(t, *job.tables, job.extent, h - 1 - j, s);
        marks = RowMarks(t, job.breaks, h - 1 - j);
        if (with_d) RowDisplacements(t, *job.ref_tables, h - 1 - j, s);
        if (track) TrackRange(s, w, range);
        return prep;
    };
    // Row j, drawing into v-rows [ya, yb); returns the texels dropped. The copies of still spans and still column
    // steps are looked for only in rows with still texels (a row of bumps has none: no test a vector).
    auto row = [&](int j, int ya, int yb, float* drawn) {
        const PreparedRow prep = prepare(j, j + p.step);
        std::fill(b.cur_ok + x0, b.cur_ok + x1, 0);
        const bool copy = job.copy_still && prep.still;
        out.copy = copy;
        const ColumnTarget o{pixels, ow, oh, ya, yb, job.blend_stores, OutputAhead(job.blend_stores, p.step)};
        const Emitter emit{b, o, x0, x1, drawn, copy, job.threshold};
        WarpRow(s.pos, s.color, s.v, s.d, w, job.split_u, ow, out, Coalescer<Emitter>{emit}, marks);
        std::swap(b.prev_c, b.cur_c);
        std::swap(b.prev_v, b.cur_v);
        std::swap(b.prev_ok, b.cur_ok);
        std::swap(b.prev_d, b.cur_d);
        return prep.dropped;
    };
    const int ja = p.first + p.step * r0, jb = p.first + p.step * r1;
    if (r0 > 0) row(ja - p.step, p.y0, p.y0, nullptr);  // the row before: no output rows
    long long dropped = 0;
    int from = jb;  // the first row in reverse mode (jb: none)
    if (job.reverse == KernelChoice::always) from = ja;
    for (int j = ja; j != from; j += p.step) {
        float drawn = 0.0f;
        const bool measure = job.reverse == KernelChoice::automatic && (j & 3) == 0 && j + p.step != jb;
        const long long d = row(j, p.y0, p.y1, measure ? &drawn : nullptr);
        if (x0 == 0) dropped += d;  // column ranges warp every row: counted once
        if (measure && drawn > kReverseDrawn * float(x1 - x0)) from = j + p.step;
    }
    const bool seam = r1 == p.count;
    if (from != jb) {
        fast::ReverseBuffers& r = reverse_buffers(job, task);
        r.reserve(ow, oh);
        std::fill(r.lo.data() + x0, r.lo.data() + x1, 1 << 30);
        std::fill(r.hi.data() + x0, r.hi.data() + x1, -(1 << 30));
        std::fill(r.bits_on.data() + x0, r.bits_on.data() + x1, 0);
        const ColumnsWritten cw{r.lo.data(), r.hi.data(), r.bits_on.data(), r.bits.data(), r.nw};
        // The rows replayed from the last back: the prefetch goes the other way.
        const ColumnTarget o{pixels, ow, oh, p.y0, p.y1, job.blend_stores, OutputAhead(job.blend_stores, -p.step)};
        auto warp = [&](int j, fast::EmitLog& log) {
            const PreparedRow prep = prepare(j, j - p.step);
            out.copy = job.copy_still && prep.still;
            if (x0 == 0) dropped += prep.dropped;
            std::fill(r.fin_ok.data() + x0, r.fin_ok.data() + x1, 0);
            log.n = 0;
            const Logger logger{b, r, log, x0, x1, with_d, job.blend_stores};
            WarpRow(s.pos, s.color, s.v, s.d, w, job.split_u, ow, out, Coalescer<Logger>{logger}, marks);
        };
        const hn::ScalableTag<float> df;
        const hn::RebindToSigned<decltype(df)> di;
        const size_t N = hn::Lanes(df);
        const int last = jb - p.step;
        int cur = 0;
        warp(last, r.log[0]);
        if (seam)
            for (int x = x0; x < x1; ++x) {
                job.seam_v[part][x] = r.fin_v[size_t(x)];
                job.seam_c[part][x] = r.fin_ok[size_t(x)] ? (r.fin_c[size_t(x)] | 0xFF000000u) : 0u;
            }
        if (seam && with_d) std::copy(r.fin_d.data() + x0, r.fin_d.data() + x1, job.seam_d[part] + x0);
        for (int j = last;; j -= p.step) {
            const float* pv = b.prev_v;
            const float* pd = b.prev_d;
            const uint32_t* pc = b.prev_c;
            const int32_t* pok = b.prev_ok;
            if (j != from) {
                warp(j - p.step, r.log[cur ^ 1]);
                pv = r.fin_v.data(), pd = r.fin_d.data(), pc = r.fin_c.data(), pok = r.fin_ok.data();
            }
            // The log's arrays as locals: read through `r` (the thread-local buffers), GCC computed the thread-local's
            // address again for every entry, as a call (vector registers spilled, vzeroupper): bricks 1024^2
            // pipelined 5% slower.
            const fast::EmitLog& log = r.log[cur];
            const int32_t* lx = log.x.data();
            const float *lv = log.v.data(), *ld = log.d.data();
            const int32_t* lc = reinterpret_cast<const int32_t*>(log.c.data());
            for (size_t i = log.n; i-- > 0;) {
                const int x = lx[i];
                const auto v = hn::LoadU(df, lv + i * N);
                const auto fin = hn::IsFinite(v);
                auto ok = hn::And(fin, hn::RebindMask(df, hn::Ne(hn::LoadU(di, pok + x), hn::Zero(di))));
                if (with_d) {  // the Emitter's threshold test
                    const auto d = hn::LoadU(df, ld + i * N);
                    ok = hn::And(ok, WithinThreshold(df, hn::LoadU(df, pd + x), d, job.threshold));
                }
                ColumnDrawRev(df, o, cw, x, x + int(N) <= x1, job.copy_still, fin, ok, hn::LoadU(df, pv + x),
                              hn::LoadU(di, reinterpret_cast<const int32_t*>(pc + x)), v, hn::LoadU(di, lc + i * N));
            }
            if (j == from) break;
            cur ^= 1;
        }
    } else if (seam) {
        for (int x = x0; x < x1; ++x) {
            job.seam_v[part][x] = b.prev_v[x];
            job.seam_c[part][x] = b.prev_ok[x] ? (b.prev_c[x] | 0xFF000000u) : 0u;
        }
        if (with_d) std::copy(b.prev_d + x0, b.prev_d + x1, job.seam_d[part] + x0);
    }
    if (dropped) *job.dropped += dropped;
    return range;
}

void PipelinedPart(const fast::PipelinedJob& job, int task, int part, int x0, int x1) {
    clear_part(job, part, x0, x1);
    RunRows(job, task, part, 0, part_rows(job, part).count, x0, x1, reinterpret_cast<uint32_t*>(job.out->pixels.data()),
            false);
}

void PipelinedChunk(const fast::PipelinedJob& job, fast::PipelinedChunk& c) {
    const int ow = job.out->width;
    if (c.r0 == 0) {
        clear_part(job, c.part, 0, ow);
        RunRows(job, c.task, c.part, c.r0, c.r1, 0, ow, reinterpret_cast<uint32_t*>(job.out->pixels.data()), false);
        c.ylo = c.yhi = 0;
        return;
    }
    const RowRange r = RunRows(job, c.task, c.part, c.r0, c.r1, 0, ow,
                               reinterpret_cast<uint32_t*>(c.scratch->pixels.data()), true);
    // Every pixel drawn lies in v-rows floor(lo) .. floor(hi) (a span's rows lie between its ends, which are
    // interpolated between samples, a point's is int(v)); one row more on each side for the rounding.
    const PartRows p = part_rows(job, c.part);
    auto clamp_row = [&](double y) { return int(std::clamp(y, double(p.y0), double(p.y1))); };
    c.ylo = r.lo <= r.hi ? clamp_row(std::floor(double(r.lo)) - 1.0) : p.y0;
    c.yhi = r.lo <= r.hi ? clamp_row(std::floor(double(r.hi)) + 2.0) : p.y0;
}

// The scratch images of chunks (every one but each part's first) over the output, v-rows [y0, y1) of each chunk's
// ylo .. yhi: the pixels a chunk wrote (alpha set) replace the output's and are cleared in its scratch, which is left
// all 0 for the next pre-warp. A vector at a time (the scalar loop took 0.12 to 0.27 ms, bricks 1024^2 on two
// threads, where the hand-written AVX-512 kernels' took 0.03); the output's vector is stored only where a pixel of it
// changes.
void Composite(const fast::PipelinedJob& job, const fast::PipelinedChunk* chunks, int n, int y0, int y1) {
    const hn::ScalableTag<int32_t> di;
    const int N = int(hn::Lanes(di));
    const int ow = job.out->width, oh = job.out->height;
    int32_t* out = reinterpret_cast<int32_t*>(job.out->pixels.data());
    const auto alpha = hn::Set(di, int32_t(0xFF000000u)), zero = hn::Zero(di);
    for (int i = 0; i < n; ++i) {
        const fast::PipelinedChunk& c = chunks[i];
        if (c.r0 == 0) continue;
        int32_t* scratch = reinterpret_cast<int32_t*>(c.scratch->pixels.data());
        for (int y = std::max(y0, c.ylo); y < std::min(y1, c.yhi); ++y) {
            int32_t* o = out + size_t(oh - 1 - y) * size_t(ow);
            int32_t* q = scratch + size_t(oh - 1 - y) * size_t(ow);
            int x = 0;
            for (; x + N <= ow; x += N) {
                const auto p = hn::LoadU(di, q + x);
                const auto written = hn::Ne(hn::And(p, alpha), zero);
                if (hn::AllFalse(di, written)) continue;
                hn::StoreU(hn::IfThenElse(written, p, hn::LoadU(di, o + x)), di, o + x);
                hn::StoreU(zero, di, q + x);
            }
            for (; x < ow; ++x)
                if (uint32_t(q[x]) >> 24) {
                    o[x] = q[x];
                    q[x] = 0;
                }
        }
    }
}

}  // namespace rtm::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rtm::simd {
namespace {

void seam(const fast::PipelinedJob& job) {
    const int h = job.relief->height, ow = job.out->width, oh = job.out->height;
    if (!(job.split_v > 0 && job.split_v < h)) return;
    auto rgba = [](uint32_t c) { return Rgba8{uint8_t(c), uint8_t(c >> 8), uint8_t(c >> 16), uint8_t(c >> 24)}; };
    for (int x = 0; x < ow; ++x) {
        const uint32_t ca = job.seam_c[0][x], cb = job.seam_c[1][x];
        if (!(ca >> 24) || !(cb >> 24)) continue;
        if (job.threshold > 0.0f && !displacements_joined(job.seam_d[0][x], job.seam_d[1][x], job.threshold)) continue;
        raster_span(job.seam_v[0][x], rgba(ca), 0.0f, job.seam_v[1][x], rgba(cb), 0.0f, oh,
                    [&](int y, Rgba8 c, float) { job.out->at(x, oh - 1 - y) = c; });
    }
}

}  // namespace

PipelinedKernels hwy_pipelined_kernels(Isa isa) {
#define RTM_HWY_PIPELINED(NS) \
    { &NS::PipelinedPart, &NS::PipelinedChunk, &NS::Composite, &seam }
    switch (isa) {
#if HWY_TARGETS & HWY_AVX3_DL
        case Isa::avx512: return RTM_HWY_PIPELINED(N_AVX3_DL);
#endif
#if HWY_TARGETS & HWY_AVX3
        case Isa::avx3: return RTM_HWY_PIPELINED(N_AVX3);
#endif
#if HWY_TARGETS & HWY_AVX2
        case Isa::avx2: return RTM_HWY_PIPELINED(N_AVX2);
#endif
#if HWY_TARGETS & HWY_SSE4
        case Isa::sse4: return RTM_HWY_PIPELINED(N_SSE4);
#endif
#if HWY_TARGETS & HWY_NEON
        case Isa::neon: return RTM_HWY_PIPELINED(N_NEON);
#endif
#if HWY_TARGETS & HWY_SVE2
        case Isa::sve:
            if (hwy_supported_targets() & HWY_SVE2) return RTM_HWY_PIPELINED(N_SVE2);
#if HWY_TARGETS & HWY_SVE
            return RTM_HWY_PIPELINED(N_SVE);
#else
            return {};
#endif
#elif HWY_TARGETS & HWY_SVE
        case Isa::sve: return RTM_HWY_PIPELINED(N_SVE);
#endif
        default: return {};
    }
#undef RTM_HWY_PIPELINED
}

}  // namespace rtm::simd
#endif  // HWY_ONCE
