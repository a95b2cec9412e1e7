// The fast two-pass pre-warp kernels (see simd/avx512_two_pass.h). Compiled with -ffp-contract=off
// (warp/CMakeLists.txt): the pixel identity with the reference rests on every float operation being the one the
// reference performs.
//
// Measurements that shaped this file (one thread, thread CPU time, best of 100 to 3000 runs, bumps, the view of
// `rtm bench`, AMD EPYC Zen 4 guest; docs/BENCHMARKS.md has the whole story):
// - the previous design wrote the whole intermediate image in 16-column tiles, read it back column by column with
//   16 x 16 transposes, warped each column with the row kernel and transposed the result into the output: 1024^2
//   7.4 ms (horizontal 3.4, vertical 4.0, the vertical pass slowed by the 8 MB intermediate image: 2.2 ns a texel at
//   256^2, 3.8 at 1024^2), 256^2 0.33 ms. Interleaving the passes band by band with the columns in SIMD lanes (the
//   pipelined kernel's vertical step, warp/simd/avx512_columns.h), no intermediate image and no transposes: 5.75 and
// 0.29
//   ms before any other change;
// - keeping floor and ceil of each column's last v - 0.5 (integer span ends, no float rounding of the previous
//   sample again) and the rare first sample of a column out of the common path: 256^2 0.256 -> 0.254, 1024^2
//   5.24 -> 5.14 ms.
#include "warp/simd/avx512_two_pass.h"

#include <immintrin.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "warp/line_warp.h"
#include "warp/simd/schedule.h"

#include "warp/simd/avx512_target_begin.h"
#include "warp/simd/avx512_line.h"
#include "warp/simd/avx512_row.h"
#include "warp/simd/avx512_columns.h"

namespace rtm {
namespace {

LineStorage& thread_line() {
    static thread_local LineStorage s;
    return s;
}

struct NoRange {
    void operator()(int, int) const {}
};

// The vertical step of one intermediate row for columns [x0, x1): every column whose pixel in this row was written
// (alpha != 0) with a finite row coordinate connects its previous sample to it, as the reference's warp_line_to
// does along the column, and keeps it as its last sample; the others lose theirs (the run ends). The column state
// also keeps floor and ceil of v - 0.5 (clamped to [-1, oh]), from which a span's first and last rows follow in
// integers: raster_span's floor(pa - 0.5) + 1 .. floor(pb - 0.5) or ceil(pb - 0.5) .. ceil(pa - 0.5) - 1 (clamping
// to integers commutes with floor and ceil).
//
// With kThreshold (the relief's discontinuity threshold, TwoPassJob::threshold) a column connects its previous sample
// to the new one only where |d_prev - d| <= threshold, d being the displacement carried along the row (band rows
// job.d_offset floats after rv): elsewhere the new sample starts a run, as in the reference's DisplConnected.
template <bool kThreshold>
inline void vertical_step(const fast::TwoPassJob& job, const ColumnOut& o, const uint32_t* rc, const float* rv, int x0,
                          int x1) {
    const __m512 half = _mm512_set1_ps(0.5f);
    const __m512 thr = _mm512_set1_ps(job.threshold);
    const __m512 lo_clamp = _mm512_set1_ps(-1.0f), hi_clamp = _mm512_set1_ps(float(o.oh));
    const __m512i one = _mm512_set1_epi32(1), last = _mm512_set1_epi32(o.oh - 1);
    for (int x = x0; x < x1; x += 16) {
        const __mmask16 m = first_lanes(x1 - x);
        const __m512 v = _mm512_maskz_loadu_ps(m, rv + x);
        const __m512i c = _mm512_maskz_loadu_epi32(m, rc + x);
        const __mmask16 fin = m & _mm512_test_epi32_mask(c, _mm512_set1_epi32(int(0xFF000000))) & ~nonfinite(v);
        __mmask16 pok = fin & job.col_ok[x >> 4];
        job.col_ok[x >> 4] = fin;
        if (!fin) continue;
        if constexpr (kThreshold) {
            // std::abs(d[a] - d[b]) <= threshold, operation by operation (the sign bit cleared).
            const __m512 d = _mm512_maskz_loadu_ps(m, rv + job.d_offset + x);
            const __m512 pd = _mm512_load_ps(job.col_d + x);
            pok = _mm512_mask_cmp_ps_mask(pok, _mm512_abs_ps(_mm512_sub_ps(pd, d)), thr, _CMP_LE_OQ);
            _mm512_mask_store_ps(job.col_d + x, fin, d);
        }
        const __m512 pv = _mm512_load_ps(job.col_v + x);
        const __m512i pc = _mm512_load_si512(job.col_c + x);
        const __m512i pf = _mm512_load_si512(job.col_fl + x), pe = _mm512_load_si512(job.col_ce + x);
        const __m512 cl = _mm512_max_ps(lo_clamp, _mm512_min_ps(hi_clamp, _mm512_sub_ps(v, half)));
        const __m512i f = _mm512_cvt_roundps_epi32(cl, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
        const __m512i e = _mm512_cvt_roundps_epi32(cl, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
        _mm512_mask_store_ps(job.col_v + x, fin, v);
        _mm512_mask_store_epi32(job.col_c + x, fin, c);
        _mm512_mask_store_epi32(job.col_fl + x, fin, f);
        _mm512_mask_store_epi32(job.col_ce + x, fin, e);
        const __mmask16 inc = _mm512_mask_cmp_ps_mask(pok, v, pv, _CMP_GT_OQ);
        const __mmask16 dec = _mm512_mask_cmp_ps_mask(pok, v, pv, _CMP_LT_OQ);
        const __m512i ylo = _mm512_max_epi32(_mm512_mask_mov_epi32(e, inc, _mm512_add_epi32(pf, one)),
                                             _mm512_setzero_si512());
        const __m512i yhi = _mm512_min_epi32(_mm512_mask_mov_epi32(_mm512_sub_epi32(pe, one), inc, f), last);
        const __mmask16 span = (inc | dec) & _mm512_cmple_epi32_mask(ylo, yhi);
        // A column that had no sample starts a run: raster_point(v, c), row int(v) if 0 <= v < oh. Rare (the first
        // row of a part, holes), so apart.
        const __mmask16 point = fin & ~pok;
        if (point) [[unlikely]] {
            const __mmask16 pin = point & _mm512_cmp_ps_mask(v, _mm512_setzero_ps(), _CMP_GE_OQ) &
                                  _mm512_cmp_ps_mask(v, _mm512_set1_ps(float(o.oh)), _CMP_LT_OQ);
            const __m512i vi = _mm512_cvttps_epi32(v);
            if (span | pin)
                column_pixels(o, x, span, pin, _mm512_mask_mov_epi32(ylo, pin, vi), _mm512_mask_mov_epi32(yhi, pin, vi),
                              pv, pc, v, c);
            continue;
        }
        if (span) column_pixels(o, x, span, 0, ylo, yhi, pv, pc, v, c);
    }
}

inline bool ok_bit(const fast::TwoPassJob& job, int x) { return (job.col_ok[x >> 4] >> (x & 15)) & 1; }

}  // namespace

namespace fast {

void horizontal_steps(const TwoPassJob& job, int s0, int s1, uint32_t* band_c, float* band_v, size_t stride, float*) {
    const ReliefTexture& t = *job.relief;
    const int ow = job.out->width;
    LineStorage& ls = thread_line();
    ls.reserve(t.width);
    LineSoA& s = ls.soa;
    long long dropped = 0;
    for (int st = s0; st < s1; ++st) {
        uint32_t* rc = band_c + size_t(st - s0) * stride;
        float* rv = band_v + size_t(st - s0) * stride;
        const int r = step_row(job, st);
        if (st + 1 < t.height) prefetch_relief_row(t, step_row(job, st + 1));
        dropped += prepare_row(t, *job.tables, job.extent, ow, r, s);
        // Marked discontinuities: a row with marks loses the spans across them, and its samples are no longer one
        // connected path, which the backward order requires (warp_line_reverse): such rows go forwards.
        const bool marked = job.breaks && apply_row_breaks(s, job.breaks + size_t(r) * size_t(t.width));
        std::memset(rc, 0, size_t(ow) * 4);
        LineOut lo{rc, rv, ow};
        lo.copy = job.copy_still;
        // With a discontinuity threshold the row also carries each texel's displacement (the reference's
        // RowAttr::d) for the vertical pass's test, as a second attribute interpolated with the same parameter as v
        // (kAttr 2): one walk of the row, where a second walk carrying d had shaded every span again (about 0.1 ms
        // of a 256^2 marked face's pre-warp, one thread; docs/perf-history.md, "Six-face objects").
        const bool with_d = job.threshold > 0.0f;
        if (with_d) {
            row_displacements(t, *job.ref_tables, r, s);
            lo.attr2 = rv + job.d_offset;
        }
        // Rows that fold over: backwards, each pixel shaded once (warp_line_reverse). Bumps never folds over and
        // takes the forward order as before.
        bool backward = false;
        if (!marked && job.reverse != KernelChoice::never &&
            line_folds_over(s, job.split_u, job.reverse == KernelChoice::always)) {
            backward = (with_d ? warp_line_reverse<2>(s, job.split_u, lo) : warp_line_reverse<1>(s, job.split_u, lo)) &&
                       !job.redo_forwards;
            if (!backward) std::memset(rc, 0, size_t(ow) * 4);  // only with redo_forwards (warp_line_reverse says why)
        }
        if (!backward) {
            if (with_d)
                warp_line_fast<2>(s, job.split_u, lo, NoRange{});
            else
                warp_line_fast<1>(s, job.split_u, lo, NoRange{});
        }
    }
    if (dropped) *job.dropped += dropped;
}

void vertical_steps(const TwoPassJob& job, int s0, int s1, const uint32_t* band_c, const float* band_v, size_t stride,
                    int x0, int x1) {
    const int h = job.relief->height, ow = job.out->width, oh = job.out->height;
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    ColumnOut o{out, ow, oh, 0, oh};
    if (s0 == 0) {
        // Clearing rows just before the first band that may write them (from the row coordinates each band
        // brings) measured 3% slower at 1024^2 than clearing them all here, and not clearing at all no faster:
        // the first write to a line costs the same either way.
        for (int y = 0; y < oh; ++y) std::memset(out + size_t(y) * size_t(ow) + size_t(x0), 0, size_t(x1 - x0) * 4);
        for (int x = x0; x < x1; x += 16) job.col_ok[x >> 4] = 0;
    }
    for (int st = s0; st < s1; ++st) {
        if (st == job.split_v && st > 0) {
            // The bottom part ends: keep its last samples for the span across the epipole; the top part starts
            // afresh.
            for (int x = x0; x < x1; ++x) {
                job.seam_v[x] = job.col_v[x];
                job.seam_c[x] = ok_bit(job, x) ? (job.col_c[x] | 0xFF000000u) : 0u;
            }
            if (job.threshold > 0.0f)
                for (int x = x0; x < x1; ++x) job.seam_d[x] = job.col_d[x];
            for (int x = x0; x < x1; x += 16) job.col_ok[x >> 4] = 0;
        }
        // The output lines a band ahead, in the direction the part moves (bumps 1024^2: 5.4 -> 5.2 ms; 4 and 16
        // rows ahead measured in between). (Processing the columns in strips of 128 or 256, so that the output
        // lines being written stay in L1, made no difference.)
        o.ahead = st < job.split_v ? 8 : -8;
        if (job.threshold > 0.0f)
            vertical_step<true>(job, o, band_c + size_t(st - s0) * stride, band_v + size_t(st - s0) * stride, x0, x1);
        else
            vertical_step<false>(job, o, band_c + size_t(st - s0) * stride, band_v + size_t(st - s0) * stride, x0, x1);
    }
    if (s1 == h && job.split_v > 0 && job.split_v < h) {
        // The span across the epipole (warp_line_to's seam): the samples at split_v - 1 and split_v, where both
        // are there.
        auto rgba = [](uint32_t c) { return Rgba8{uint8_t(c), uint8_t(c >> 8), uint8_t(c >> 16), uint8_t(c >> 24)}; };
        for (int x = x0; x < x1; ++x) {
            if (!(job.seam_c[x] >> 24) || !ok_bit(job, x)) continue;
            if (job.threshold > 0.0f && !displacements_joined(job.seam_d[x], job.col_d[x], job.threshold)) continue;
            raster_span(job.seam_v[x], rgba(job.seam_c[x]), 0.0f, job.col_v[x], rgba(job.col_c[x]), 0.0f, oh,
                        [&](int y, Rgba8 c, float) { job.out->at(x, oh - 1 - y) = c; });
        }
    }
}

}  // namespace fast
}  // namespace rtm

#include "warp/simd/avx512_target_end.h"
