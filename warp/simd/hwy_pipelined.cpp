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
#include <type_traits>
#include <vector>

#include "warp/line_warp.h"
#include "warp/simd/hwy_pipelined.h"
#include "warp/simd/hwy_row-inl.h"
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

// One task's buffers, carved out of its float vector in the workspace (PrewarpWorkspace::task_buffers), which grows
// to the largest relief and output seen and never shrinks (steady state allocates nothing).
struct PipeBuffers {
    float* row;  // one row's samples: positions, row coordinates, colours (RowScratch)
    uint32_t *rc, *col_c, *m_c;
    float *rv, *col_v, *m_v;
    int32_t *col_ok, *m_ok, *multi_flag;
    int32_t* multi;  // the columns that received more than one pixel from the row, n_multi of them
    int n_multi = 0;
};

PipeBuffers task_buffers(const fast::PipelinedJob& job) {
    const int w = job.relief->width, ow = job.out->width;
    std::vector<float>& v = (*job.task_buffers)[size_t(job.next_task->fetch_add(1))];
    // Arrays are read up to a whole vector past the output width (ColumnStep): 64 lanes is SVE's most. Sizes are
    // rounded up to 64, so that outputs a few pixels wider (the next view's margins) fit.
    const size_t n = (size_t(ow) + 63) / 64 * 64 + 64, nr = 3 * ((size_t(w) + 63) / 64 * 64);
    if (v.size() < nr + 10 * n) v.resize(nr + 10 * n);
    float* p = v.data();
    PipeBuffers b;
    b.row = p;
    p += nr;
    auto take = [&](auto*& q) {
        q = reinterpret_cast<std::remove_reference_t<decltype(q)>>(p);
        p += n;
    };
    take(b.rc), take(b.col_c), take(b.m_c), take(b.rv), take(b.col_v), take(b.m_v);
    take(b.col_ok), take(b.m_ok), take(b.multi_flag), take(b.multi);
    std::fill(b.multi_flag, b.multi_flag + n, 0);
    return b;
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

// Rows [r0, r1) of part `part` (counted in the part's order), columns [x0, x1), drawn into `pixels` (an image of
// the output's size; only the part's output rows). A task that does not start at its part's first row starts from
// the row before it, warped without drawing: the column state after it is the one the reference carries into the
// task's first row. Returns the range of the row coordinates of the samples warped (with `track`).
RowRange RunRows(const fast::PipelinedJob& job, int part, int r0, int r1, int x0, int x1, uint32_t* pixels,
                 bool track) {
    const ReliefTexture& t = *job.relief;
    const PrewarpTables& tab = *job.ref_tables;
    const int w = t.width, h = t.height, ow = job.out->width, oh = job.out->height;
    const PartRows p = part_rows(job, part);
    PipeBuffers b = task_buffers(job);
    const RowScratch s{b.row, b.row + w, reinterpret_cast<uint32_t*>(b.row + 2 * size_t(w))};
    const Columns col{b.col_v, b.col_ok, b.col_c};
    uint32_t* rc = b.rc;
    float* rv = b.rv;
    int32_t* flag = b.multi_flag;
    std::fill(col.ok + x0, col.ok + x1, 0);
    RowRange range{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
    // Row j, drawing into v-rows [ya, yb); returns the texels dropped.
    auto row = [&](int j, int ya, int yb) {
        const long long dropped = PrepareRow(t, tab, job.extent, h - 1 - j, s);
        if (track)
            for (int x = 0; x < w; ++x)
                if (std::isfinite(s.pos[x]) && std::isfinite(s.v[x])) {
                    range.lo = std::min(range.lo, s.v[x]);
                    range.hi = std::max(range.hi, s.v[x]);
                }
        std::memset(rc, 0, size_t(ow) * 4);
        b.n_multi = 0;
        // Every pixel written has alpha 255: one written before in this row marks a column with more than one.
        WarpRow(s.pos, s.color, s.v, w, job.split_u, ow, [&](int x, uint32_t c, float v) {
            if ((rc[x] >> 24) && !flag[x]) {
                flag[x] = 1;
                b.multi[b.n_multi++] = x;
            }
            rc[x] = c;
            rv[x] = v;
        });
        ColumnStep<true>(col, ColumnTarget{pixels, ow, oh, ya, yb}, rc, rv, flag, x0, x1);
        if (b.n_multi == 0) return dropped;
        // The columns with more than one pixel: every pixel in the row warp's order, each from the column's
        // sample of the previous row (the reference's row_put); the column keeps the last finite one.
        for (int i = 0; i < b.n_multi; ++i) b.m_ok[b.multi[i]] = 0;
        WarpRow(s.pos, s.color, s.v, w, job.split_u, ow, [&](int x, uint32_t c, float v) {
            if (!flag[x] || x < x0 || x >= x1 || !std::isfinite(v)) return;
            auto put = [&](int y, Rgba8 cc, float) {
                if (y >= ya && y < yb) pixels[size_t(oh - 1 - y) * size_t(ow) + size_t(x)] = pack(cc);
            };
            if (col.ok[x])
                raster_span(col.v[x], unpack(col.c[x]), 0.0f, v, unpack(c), 0.0f, oh, put);
            else
                raster_point(v, unpack(c), 0.0f, oh, put);
            b.m_v[x] = v;
            b.m_c[x] = c;
            b.m_ok[x] = -1;
        });
        for (int i = 0; i < b.n_multi; ++i) {
            const int x = b.multi[i];
            flag[x] = 0;
            if (x < x0 || x >= x1) continue;
            col.v[x] = b.m_v[x];
            col.c[x] = b.m_c[x];
            col.ok[x] = b.m_ok[x];
        }
        return dropped;
    };
    const int ja = p.first + p.step * r0, jb = p.first + p.step * r1;
    if (r0 > 0) row(ja - p.step, p.y0, p.y0);  // the row before: no output rows
    long long dropped = 0;
    for (int j = ja; j != jb; j += p.step) {
        const long long d = row(j, p.y0, p.y1);
        if (x0 == 0) dropped += d;  // column ranges warp every row: counted once
    }
    if (r1 == p.count)
        for (int x = x0; x < x1; ++x) {
            job.seam_v[part][x] = col.v[x];
            job.seam_c[part][x] = col.ok[x] ? (col.c[x] | 0xFF000000u) : 0u;
        }
    if (dropped) *job.dropped += dropped;
    return range;
}

void PipelinedPart(const fast::PipelinedJob& job, int part, int x0, int x1) {
    clear_part(job, part, x0, x1);
    RunRows(job, part, 0, part_rows(job, part).count, x0, x1, reinterpret_cast<uint32_t*>(job.out->pixels.data()),
            false);
}

void PipelinedChunk(const fast::PipelinedJob& job, fast::PipelinedChunk& c) {
    const int ow = job.out->width;
    if (c.r0 == 0) {
        clear_part(job, c.part, 0, ow);
        RunRows(job, c.part, c.r0, c.r1, 0, ow, reinterpret_cast<uint32_t*>(job.out->pixels.data()), false);
        c.ylo = c.yhi = 0;
        return;
    }
    const RowRange r = RunRows(job, c.part, c.r0, c.r1, 0, ow, reinterpret_cast<uint32_t*>(c.scratch->pixels.data()),
                               true);
    // Every pixel drawn lies in v-rows floor(lo) .. floor(hi) (a span's rows lie between its ends, which are
    // interpolated between samples, a point's is int(v)); one row more on each side for the rounding.
    const PartRows p = part_rows(job, c.part);
    auto clamp_row = [&](double y) { return int(std::clamp(y, double(p.y0), double(p.y1))); };
    c.ylo = r.lo <= r.hi ? clamp_row(std::floor(double(r.lo)) - 1.0) : p.y0;
    c.yhi = r.lo <= r.hi ? clamp_row(std::floor(double(r.hi)) + 2.0) : p.y0;
}

}  // namespace rtm::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rtm::simd {
namespace {

// The same for every target: plain loops.
void composite(const fast::PipelinedJob& job, const fast::PipelinedChunk* chunks, int n, int y0, int y1) {
    const int ow = job.out->width, oh = job.out->height;
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    for (int i = 0; i < n; ++i) {
        const fast::PipelinedChunk& c = chunks[i];
        if (c.r0 == 0) continue;
        uint32_t* scratch = reinterpret_cast<uint32_t*>(c.scratch->pixels.data());
        for (int y = std::max(y0, c.ylo); y < std::min(y1, c.yhi); ++y) {
            uint32_t* o = out + size_t(oh - 1 - y) * size_t(ow);
            uint32_t* q = scratch + size_t(oh - 1 - y) * size_t(ow);
            for (int x = 0; x < ow; ++x)
                if (q[x] >> 24) {
                    o[x] = q[x];
                    q[x] = 0;
                }
        }
    }
}

void seam(const fast::PipelinedJob& job) {
    const int h = job.relief->height, ow = job.out->width, oh = job.out->height;
    if (!(job.split_v > 0 && job.split_v < h)) return;
    auto rgba = [](uint32_t c) { return Rgba8{uint8_t(c), uint8_t(c >> 8), uint8_t(c >> 16), uint8_t(c >> 24)}; };
    for (int x = 0; x < ow; ++x) {
        const uint32_t ca = job.seam_c[0][x], cb = job.seam_c[1][x];
        if (!(ca >> 24) || !(cb >> 24)) continue;
        raster_span(job.seam_v[0][x], rgba(ca), 0.0f, job.seam_v[1][x], rgba(cb), 0.0f, oh,
                    [&](int y, Rgba8 c, float) { job.out->at(x, oh - 1 - y) = c; });
    }
}

}  // namespace

PipelinedKernels hwy_pipelined_kernels(Isa isa) {
#define RTM_HWY_PIPELINED(NS) \
    { &NS::PipelinedPart, &NS::PipelinedChunk, &composite, &seam }
    switch (isa) {
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
            if (hwy::SupportedTargets() & HWY_SVE2) return RTM_HWY_PIPELINED(N_SVE2);
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
