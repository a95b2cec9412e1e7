// The Highway two-pass kernels (see hwy_two_pass.h). This file is compiled once per target by
// hwy/foreach_target.h, with an SSE4 baseline and -ffp-contract=off (warp/CMakeLists.txt): every float operation
// that decides a position or a weight is the one the reference performs, on every target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "warp/simd/hwy_two_pass.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "warp/line_warp.h"
#include "warp/simd/hwy_row-inl.h"
#include "warp/simd/hwy_two_pass.h"
#include "warp/simd/schedule.h"
#include "warp/tables.h"

HWY_BEFORE_NAMESPACE();
namespace rtm::simd::HWY_NAMESPACE {

// The horizontal pass of steps [s0, s1): for each, the reference's row_samples (lookup-table path) and
// warp_line_to (WarpRow, or WarpRowBackward for rows that fold over) into one band row (colour with alpha 255 where
// written, 0 elsewhere; the final row coordinate). Rows with discontinuity marks (job.breaks) go forwards, their
// marks breaking spans in WarpRow (the backward order needs one connected path of samples). With a discontinuity
// threshold the row also carries each texel's displacement (the reference's RowAttr::d) as a second attribute,
// interpolated with the same parameter as v, into band rows job.d_offset floats after the v rows.
uint32_t HorizontalSteps(const fast::TwoPassJob& job, int s0, int s1, uint32_t* band_c, float* band_v, size_t stride,
                         float* scratch) {
    const ReliefTexture& t = *job.relief;
    const int w = t.width, ow = job.out->width;
    const bool with_d = job.threshold > 0.0f;
    const RowScratch s{scratch, scratch + w, reinterpret_cast<uint32_t*>(scratch + 2 * size_t(w)),
                       with_d ? scratch + 3 * size_t(w) : nullptr};
    long long dropped = 0;
    uint32_t still_rows = 0;
    for (int st = s0; st < s1; ++st) {
        const int r = fast::step_row(job, st);
        if (st + 1 < t.height) prefetch_relief_row(t, fast::step_row(job, st + 1));
        const PreparedRow prep = PrepareRow(t, *job.tables, job.extent, r, s);
        dropped += prep.dropped;
        const uint8_t* marks = RowMarks(t, job.breaks, r);
        if (with_d) RowDisplacements(t, *job.ref_tables, r, s);
        uint32_t* rc = band_c + size_t(st - s0) * stride;
        float* rv = band_v + size_t(st - s0) * stride;
        RowOut out{rc, rv, job.copy_still && prep.still};
        out.blend = job.blend_stores;
        still_rows |= uint32_t(out.copy) << (st - s0);
        if (with_d) out.attr2 = rv + job.d_offset;
        std::memset(rc, 0, size_t(ow) * 4);
        // Rows that fold over: backwards, each pixel drawn once (WarpRowBackward). Bumps never folds over.
        bool backward = false;
        if (!marks && job.reverse != KernelChoice::never &&
            RowFoldsOver(s.pos, w, job.split_u, job.reverse == KernelChoice::always)) {
            RowOut back = out;
            back.copy = false;
            backward = WarpRowBackward(s.pos, s.color, s.v, s.d, w, job.split_u, ow, back) && !job.redo_forwards;
            if (!backward) std::memset(rc, 0, size_t(ow) * 4);  // only with redo_forwards (WarpRowBackward says why)
        }
        if (!backward) WarpRow(s.pos, s.color, s.v, s.d, w, job.split_u, ow, out, NoRange{}, marks);
    }
    if (dropped) *job.dropped += dropped;
    return still_rows;
}

// The vertical pass asks for the band's row kBandAhead steps ahead of the one it steps (PrefetchBandRow). With
// threads the horizontal pass writes a band on one core and the vertical pass reads it on the other (the pipeline of
// warp/simd/schedule.cpp), and the hardware prefetchers did not bring the rows in time: bumps 256^2 two-pass on two
// threads, `avx512`, median of 5 interleaved runs of 2,000 pre-warps, 0.251 -> 0.152 ms (ridges 0.352 -> 0.211;
// `avx2` bumps 0.170 -> 0.143), 55% of the vertical pass's samples on the two loads of each vector before; 1, 3 and
// 4 steps ahead within 3% of 2, 6 slower. One thread, bricks (whose still-step test reads the rows first) and 1024^2
// (rows of 4 KiB): within the noise (docs/perf-history.md, "The band rows prefetched").
constexpr int kBandAhead = 2;

// Columns [x0, x1) of one band row (colour and row coordinate) into the cache, a line (16 pixels) at a time.
HWY_INLINE void PrefetchBandRow(const uint32_t* rc, const float* rv, int x0, int x1) {
    for (int x = x0; x < x1; x += 16) {
        hwy::Prefetch(rc + x);
        hwy::Prefetch(rv + x);
    }
}

// The vertical pass over steps [s0, s1) for columns [x0, x1) (see hwy_two_pass.h's VerticalStepsFn).
void VerticalSteps(const fast::TwoPassJob& job, int s0, int s1, const uint32_t* band_c, const float* band_v,
                   size_t stride, int x0, int x1) {
    const int h = job.relief->height, ow = job.out->width, oh = job.out->height;
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    const bool with_d = job.threshold > 0.0f;
    const Columns cols{job.col_v, job.col_c, job.col_d};
    ColumnTarget target{out, ow, oh, 0, oh, job.blend_stores};
    if (s0 == 0) {
        for (int y = 0; y < oh; ++y) std::memset(out + size_t(y) * size_t(ow) + size_t(x0), 0, size_t(x1 - x0) * 4);
        std::fill(job.col_v + x0, job.col_v + x1, std::numeric_limits<float>::quiet_NaN());
    }
    for (int st = s0; st < s1; ++st) {
        if (st == job.split_v && st > 0) {
            // The bottom part ends: keep its last samples for the span across the epipole; the top part starts
            // afresh.
            for (int x = x0; x < x1; ++x) {
                job.seam_v[x] = job.col_v[x];
                job.seam_c[x] = std::isnan(job.col_v[x]) ? 0u : (job.col_c[x] | 0xFF000000u);
                job.col_v[x] = std::numeric_limits<float>::quiet_NaN();
            }
            if (with_d) std::copy(job.col_d + x0, job.col_d + x1, job.seam_d + x0);
        }
        target.ahead = OutputAhead(job.blend_stores, st < job.split_v ? 1 : -1);  // step_line's direction
        const uint32_t* rc = band_c + size_t(st - s0) * stride;
        const float* rv = band_v + size_t(st - s0) * stride;
        if (st + kBandAhead < s1) PrefetchBandRow(rc + kBandAhead * stride, rv + kBandAhead * stride, x0, x1);
        if (with_d)
            ColumnStep<true>(cols, target, rc, rv, x0, x1, rv + job.d_offset, job.threshold);
        else
            ColumnStep(cols, target, rc, rv, x0, x1);
    }
    if (s1 == h && job.split_v > 0 && job.split_v < h) {
        // The span across the epipole (warp_line_to's seam): the samples at split_v - 1 and split_v, where both
        // are there.
        for (int x = x0; x < x1; ++x) {
            if (!(job.seam_c[x] >> 24) || std::isnan(job.col_v[x])) continue;
            if (with_d && !displacements_joined(job.seam_d[x], job.col_d[x], job.threshold)) continue;
            raster_span(job.seam_v[x], unpack(job.seam_c[x]), 0.0f, job.col_v[x], unpack(job.col_c[x]), 0.0f, oh,
                        [&](int y, Rgba8 c, float) { job.out->at(x, oh - 1 - y) = c; });
        }
    }
}

// The still-step test (hwy_two_pass.h, StillStepsFn), a vector of columns at a time.
uint32_t StillSteps(const fast::TwoPassJob& job, int s0, int s1, uint32_t steps, const uint32_t* band_c,
                    const float* band_v, size_t stride, int gx0, int width) {
    const hn::ScalableTag<float> df;
    const hn::RebindToSigned<decltype(df)> di;
    const int N = int(hn::Lanes(df));
    uint32_t bits = 0;
    for (uint32_t left = steps & (s1 - s0 < 32 ? (1u << (s1 - s0)) - 1u : ~0u); left; left &= left - 1) {
        const int st = s0 + std::countr_zero(left);
        const auto centre = hn::Set(df, float(fast::step_line(job, st)) + 0.5f);
        const float* v = band_v + size_t(st - s0) * stride + gx0;
        const int32_t* c = reinterpret_cast<const int32_t*>(band_c + size_t(st - s0) * stride + gx0);
        bool all = true;
        for (int x = 0; x < width && all; x += N) {
            const auto in = hn::FirstN(df, size_t(width - x));
            const auto still = hn::And(hn::Eq(hn::LoadU(df, v + x), centre),
                                       hn::RebindMask(df, hn::Lt(hn::LoadU(di, c + x), hn::Zero(di))));
            all = hn::AllTrue(df, hn::Or(still, hn::Not(in)));
        }
        bits |= uint32_t(all) << (st - s0);
    }
    return bits;
}

}  // namespace rtm::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rtm::simd {

TwoPassKernels hwy_two_pass_kernels(Isa isa) {
    switch (isa) {
#if HWY_TARGETS & HWY_AVX3_DL
        case Isa::avx512: return {&N_AVX3_DL::HorizontalSteps, &N_AVX3_DL::VerticalSteps, &N_AVX3_DL::StillSteps};
#endif
#if HWY_TARGETS & HWY_AVX3
        case Isa::avx3: return {&N_AVX3::HorizontalSteps, &N_AVX3::VerticalSteps, &N_AVX3::StillSteps};
#endif
#if HWY_TARGETS & HWY_AVX2
        case Isa::avx2: return {&N_AVX2::HorizontalSteps, &N_AVX2::VerticalSteps, &N_AVX2::StillSteps};
#endif
#if HWY_TARGETS & HWY_SSE4
        case Isa::sse4: return {&N_SSE4::HorizontalSteps, &N_SSE4::VerticalSteps, &N_SSE4::StillSteps};
#endif
#if HWY_TARGETS & HWY_NEON
        case Isa::neon: return {&N_NEON::HorizontalSteps, &N_NEON::VerticalSteps, &N_NEON::StillSteps};
#endif
#if HWY_TARGETS & HWY_SVE2
        case Isa::sve:
            if (hwy_supported_targets() & HWY_SVE2)
                return {&N_SVE2::HorizontalSteps, &N_SVE2::VerticalSteps, &N_SVE2::StillSteps};
#if HWY_TARGETS & HWY_SVE
            return {&N_SVE::HorizontalSteps, &N_SVE::VerticalSteps, &N_SVE::StillSteps};
#else
            return {};
#endif
#elif HWY_TARGETS & HWY_SVE
        case Isa::sve: return {&N_SVE::HorizontalSteps, &N_SVE::VerticalSteps, &N_SVE::StillSteps};
#endif
        default: return {};
    }
}

int64_t hwy_compiled_targets() { return HWY_TARGETS; }

}  // namespace rtm::simd
#endif  // HWY_ONCE
