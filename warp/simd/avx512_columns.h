// The vertical work of the fast kernels (AVX-512) with 16 adjacent output columns in the lanes of one register: for
// warp/simd/avx512_two_pass.cpp and warp/simd/avx512_pipelined.cpp only, included after warp/simd/avx512_line.h.
//
// Both reconstructions end the same way for every pixel a row warp produces: the column it lands in connects it to
// the last sample that column received from the previous row (raster_span along the column), or starts a new run
// with it (raster_point). Columns are independent, so 16 of them advance together; each lane computes exactly what
// raster_span / raster_point computes for its column, operation by operation (the weight of lerp8 straight from
// the span's reciprocal, span_weight). The lanes' pixels land on different output rows where the span lengths
// differ from column to column: store_rows writes them with two masked row stores or one scatter, without
// branching on the data in the usual cases, and long spans go row by row over the columns that share those rows.
#pragma once

#include "warp/simd/avx512_line.h"

namespace rtm {
namespace {

// The output image as the column kernels see it: output v-line y (0 = bottom) is storage row oh - 1 - y; only
// v-lines [y0, y1) are written (the pipelined reconstruction's parts own disjoint ranges of them).
struct ColumnOut {
    uint32_t* pixels = nullptr;
    int ow = 0, oh = 0;
    int y0 = 0, y1 = 0;
    int ahead = 0;  // prefetch the pixels this many v-lines ahead of the ones written (0: none)
    uint32_t* vline(int y) const { return pixels + size_t(oh - 1 - y) * size_t(ow); }
};

// Pixels ylo .. yhi of column x of raster_span(pa, ca, pb, cb) (inv8192 = 8192 / (pb - pa), see span_weight): 16
// rows at a time.
inline void column_long_span(const ColumnOut& o, int x, int ylo, int yhi, float pa, float inv8192, uint32_t ca,
                             uint32_t cb) {
    const __m512 half = _mm512_set1_ps(0.5f);
    const __m512 vpa = _mm512_set1_ps(pa), vinv = _mm512_set1_ps(inv8192);
    const Lerp8 lerp(_mm512_set1_epi32(int(ca)), _mm512_set1_epi32(int(cb)));
    alignas(64) uint32_t col[16];
    for (int y0 = ylo; y0 <= yhi; y0 += 16) {
        const __m512i y = _mm512_add_epi32(_mm512_set1_epi32(y0), iota16());
        _mm512_store_si512(col, lerp.at_n(span_weight(_mm512_add_ps(_mm512_cvtepi32_ps(y), half), vpa, vinv)));
        const int n = imin(16, yhi - y0 + 1);
        uint32_t* p = o.vline(y0) + x;
        for (int i = 0; i < n; ++i, p -= o.ow) *p = col[i];
    }
}

// Writes packed colours `col` to output pixels (x + lane, v-line y[lane]) for the lanes of `act`. Neighbouring
// columns mostly land on the same row or the next, but not always, and branches on the lanes' rows mispredict:
// writing every lane to its row with one masked store per distinct row (a loop) made bumps 1024^2 5.3 ms where a
// version writing the lanes only to rows y_0 and y_0 + 1 took 4.1 (wrong pixels, but the cost of the rest). So:
// two masked row stores, unconditionally, when every lane is on the first active lane's row y_f or the next; else
// one scatter instruction.
// History (Zen 4 guest): five masked stores on the rows around lane 8's, then a loop of scalar stores, measured
// best there (bumps 1024^2 5.2 -> 4.7 ms, ridges 11.4 -> 9.0), a 16-lane scatter costing about 35 TSC cycles. On
// the Zen 5 guest a scatter of 16 lanes to 16 rows takes 4.7 ns against 10.4 for the scalar loop (a loop of
// stores alone), and the scatter in place of both measured, one thread, median of 7 interleaved runs: ridges
// two-pass 256^2 0.258 -> 0.216 ms, 1024^2 4.33 -> 3.47; pipelined 0.496 -> 0.475, 7.93 -> 7.39; bumps and
// bricks 0 to 5% faster. Scatter only (no two-row stores) and the two-row test narrowed to one row were within the
// noise of it but for bricks pipelined (3 to 4% slower for the first) and bumps 1024^2 (9% faster for the first).
inline void store_rows(const ColumnOut& o, int x, __mmask16 act, __m512i y, __m512i col) {
    {
        const int yf = _mm512_cvtsi512_si32(_mm512_permutexvar_epi32(_mm512_set1_epi32(int(_tzcnt_u32(act))), y));
        // A prefetch for writing (prefetchw with the target's prfchw; the builtin, since clang declares _m_prefetchw
        // only in x86intrin.h).
        if (o.ahead) __builtin_prefetch(o.vline(imin(imax(yf + o.ahead, 0), o.oh - 1)) + x, 1);
        const __m512i d = _mm512_sub_epi32(y, _mm512_set1_epi32(yf));
        if (_mm512_mask_cmpgt_epu32_mask(act, d, _mm512_set1_epi32(1)) == 0) {
            _mm512_mask_storeu_epi32(o.vline(yf) + x, act & _mm512_cmpeq_epi32_mask(d, _mm512_setzero_si512()), col);
            _mm512_mask_storeu_epi32(o.vline(imin(yf + 1, o.oh - 1)) + x,
                                     act & _mm512_cmpeq_epi32_mask(d, _mm512_set1_epi32(1)), col);
            return;
        }
    }
    // Scatter: 32-bit offsets from v-line 0 of column x (fast_prewarp_covers keeps the image under 2^31 - 16
    // pixels).
    const __m512i off = _mm512_add_epi32(_mm512_mullo_epi32(y, _mm512_set1_epi32(-o.ow)), iota16());
    _mm512_mask_i32scatter_epi32(o.vline(0) + x, act, off, col, 4);
}

// Long spans (a column connected to a sample far away, common where rows fold over: ridges 1024^2 write 93
// pixels a texel this way in the pipelined reconstruction) go row by row over the rows they cover together, one
// masked store per row for all of them, so that each line of the output is touched once rather than once per
// column (ridges 1024^2: 310 ms with every lane waiting for the longest span, 489 ms column by column, 55 ms row
// by row). Spans far apart from the others go alone.
// Out of line: rare in smooth reliefs, and inlined it took registers from the common path.
__attribute__((noinline)) void column_long_spans(const ColumnOut& o, int x, __mmask16 lng, const __m512i& ylo,
                                                 const __m512i& yhi, const __m512& pv, const __m512& inv8192,
                                                 const __m512i& pc, const __m512i& c) {
    const Lerp8 lerp(pc, c);
    const int ymin = _mm512_mask_reduce_min_epi32(lng, ylo), ymax = _mm512_mask_reduce_max_epi32(lng, yhi);
    const long long total = _mm512_mask_reduce_add_epi32(lng, _mm512_add_epi32(_mm512_sub_epi32(yhi, ylo),
                                                                               _mm512_set1_epi32(1)));
    __mmask16 rowwise = lng;
    if ((long long)(ymax - ymin + 1) * _mm_popcnt_u32(lng) > 2 * total) {
        // Sparse: the lanes whose span is not within the range of the longest go alone.
        alignas(64) int32_t ilo[16], ihi[16];
        _mm512_store_si512(ilo, ylo);
        _mm512_store_si512(ihi, yhi);
        int best = 0, best_n = -1;
        for (__mmask16 l = lng; l; l &= __mmask16(l - 1)) {
            const int i = int(_tzcnt_u32(l));
            if (ihi[i] - ilo[i] > best_n) best_n = ihi[i] - ilo[i], best = i;
        }
        rowwise = lng & _mm512_cmpge_epi32_mask(ylo, _mm512_set1_epi32(ilo[best])) &
                  _mm512_cmple_epi32_mask(yhi, _mm512_set1_epi32(ihi[best]));
        const __mmask16 alone = lng & __mmask16(~rowwise);
        if (alone) {
            alignas(64) float fpa[16], finv[16];
            alignas(64) uint32_t fca[16], fcb[16];
            _mm512_store_ps(fpa, pv);
            _mm512_store_ps(finv, inv8192);
            _mm512_store_si512(fca, pc);
            _mm512_store_si512(fcb, c);
            for (__mmask16 l = alone; l; l &= __mmask16(l - 1)) {
                const int i = int(_tzcnt_u32(l));
                column_long_span(o, x + i, ilo[i], ihi[i], fpa[i], finv[i], fca[i], fcb[i]);
            }
        }
    }
    if (rowwise) {
        const int y_lo = _mm512_mask_reduce_min_epi32(rowwise, ylo);
        const int y_hi = _mm512_mask_reduce_max_epi32(rowwise, yhi);
        __m512 yc = _mm512_set1_ps(float(y_lo) + 0.5f);  // steps by 1 exactly
        for (int yy = y_lo; yy <= y_hi; ++yy) {
            const __m512i Y = _mm512_set1_epi32(yy);
            const __mmask16 on = rowwise & _mm512_cmple_epi32_mask(ylo, Y) & _mm512_cmpge_epi32_mask(yhi, Y);
            _mm512_mask_storeu_epi32(o.vline(yy) + x, on, lerp.at_n(span_weight(yc, pv, inv8192)));
            yc = _mm512_add_ps(yc, _mm512_set1_ps(1.0f));
        }
    }
}

// The pixels of 16 columns x .. x + 15: in lanes `span` raster_span(pv, pc, v, c) along the column, rows ylo .. yhi
// (already clamped to the image and to [y0, y1)); in lanes `point` raster_point(v, c), row ylo.
__attribute__((always_inline)) inline void column_pixels(const ColumnOut& o, int x, __mmask16 span, __mmask16 point,
                                                         __m512i ylo, __m512i yhi, __m512 pv, __m512i pc, __m512 v,
                                                         __m512i c) {
    const __mmask16 todo = span | point;
    const __m512 half = _mm512_set1_ps(0.5f), one = _mm512_set1_ps(1.0f);
    const __m512 inv8192 = _mm512_mul_ps(_mm512_div_ps(one, _mm512_sub_ps(v, pv)), _mm512_set1_ps(8192.0f));
    const Lerp8 lerp(pc, c);
    const __m512i cpoint = _mm512_or_si512(c, _mm512_set1_epi32(int(0xFF000000)));
    const __mmask16 lng = todo & span & _mm512_cmpge_epi32_mask(_mm512_sub_epi32(yhi, ylo), _mm512_set1_epi32(4));
    if (lng) [[unlikely]]
        column_long_spans(o, x, lng, ylo, yhi, pv, inv8192, pc, c);
    // The others (spans of 1 to 4 pixels, points) pixel by pixel: the first pixel of every lane, then the second of
    // those that have one, ...; the centre y + 0.5 steps by 1 exactly.
    __mmask16 act = todo & __mmask16(~lng);
    if (!act) return;
    __m512 yc = _mm512_add_ps(_mm512_cvtepi32_ps(ylo), half);
    __m512i y = ylo;
    store_rows(o, x, act, y, _mm512_mask_mov_epi32(lerp.at_n(span_weight(yc, pv, inv8192)), point, cpoint));
    act &= span & _mm512_cmplt_epi32_mask(y, yhi);
    while (act) {
        y = _mm512_add_epi32(y, _mm512_set1_epi32(1));
        yc = _mm512_add_ps(yc, one);
        store_rows(o, x, act, y, lerp.at_n(span_weight(yc, pv, inv8192)));
        act &= _mm512_cmplt_epi32_mask(y, yhi);
    }
}

// Columns x .. x + 15: in lanes `fin` a new sample (final row coordinate v, packed colour c) arrives; in lanes `pok`
// (a subset) the column's previous sample (pv, pc) is connected to it: raster_span(pv, pc, v, c) along the column;
// in the other lanes of `fin` the new sample starts a run: raster_point(v, c). Pixels outside [y0, y1) are dropped.
// The span's rows are computed in float as raster_span does.
// The output rows column_spans writes: lanes `span` (connected to the previous sample) and `point` (starting a
// run), each lane's rows ylo .. yhi clipped to [y0, y1) (none where ylo > yhi).
struct ColumnRows {
    __mmask16 span, point;
    __m512i ylo, yhi;
};

__attribute__((always_inline)) inline ColumnRows column_rows(const ColumnOut& o, __mmask16 fin, __mmask16 pok,
                                                             __m512 pv, __m512 v) {
    const __m512 half = _mm512_set1_ps(0.5f), one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
    const __m512 last = _mm512_set1_ps(float(o.oh - 1)), ohf = _mm512_set1_ps(float(o.oh));
    const __mmask16 inc = _mm512_mask_cmp_ps_mask(pok, v, pv, _CMP_GT_OQ);
    const __mmask16 dec = _mm512_mask_cmp_ps_mask(pok, v, pv, _CMP_LT_OQ);
    const __m512 pvh = _mm512_sub_ps(pv, half), vh = _mm512_sub_ps(v, half);
    __m512 lo = _mm512_mask_mov_ps(_mm512_roundscale_ps(vh, _MM_FROUND_TO_POS_INF), inc,
                                   _mm512_add_ps(_mm512_roundscale_ps(pvh, _MM_FROUND_TO_NEG_INF), one));
    __m512 hi = _mm512_mask_mov_ps(_mm512_sub_ps(_mm512_roundscale_ps(pvh, _MM_FROUND_TO_POS_INF), one), inc,
                                   _mm512_roundscale_ps(vh, _MM_FROUND_TO_NEG_INF));
    lo = _mm512_max_ps(lo, zero);  // std::max(lo, 0) and std::min(hi, n - 1) on finite values
    hi = _mm512_min_ps(hi, last);
    const __mmask16 span = (inc | dec) & _mm512_cmp_ps_mask(lo, hi, _CMP_LE_OQ);
    const __mmask16 point = fin & ~pok & _mm512_cmp_ps_mask(v, zero, _CMP_GE_OQ) &
                            _mm512_cmp_ps_mask(v, ohf, _CMP_LT_OQ);
    // Integer rows: a point's is int(v), a span's lo .. hi (integers in [0, oh - 1] as floats); then clipped.
    __m512i ylo = _mm512_cvttps_epi32(_mm512_mask_mov_ps(lo, point, v));
    __m512i yhi = _mm512_mask_mov_epi32(_mm512_cvttps_epi32(hi), point, ylo);
    ylo = _mm512_max_epi32(ylo, _mm512_set1_epi32(o.y0));
    yhi = _mm512_min_epi32(yhi, _mm512_set1_epi32(o.y1 - 1));
    return {span, point, ylo, yhi};
}

inline void column_spans(const ColumnOut& o, int x, __mmask16 fin, __mmask16 pok, __m512 pv, __m512i pc, __m512 v,
                         __m512i c) {
    const ColumnRows r = column_rows(o, fin, pok, pv, v);
    const __mmask16 in = _mm512_cmple_epi32_mask(r.ylo, r.yhi);
    if ((r.span | r.point) & in) column_pixels(o, x, r.span & in, r.point & in, r.ylo, r.yhi, pv, pc, v, c);
}

}  // namespace
}  // namespace rtm
