// Preparing one row of a relief for the fast line kernel (AVX-512): for simd/avx512_two_pass.cpp and
// simd/avx512_pipelined.cpp only, included after warp/simd/avx512_target_begin.h like warp/simd/avx512_line.h.
#pragma once

#include "warp/simd/avx512_line.h"
#include "warp/simd/fast_tables.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm {
namespace {

// ---- Table lookups for 64 texels with byte permutes ----
//
// The 64 levels are arranged in a permuted order qp so that, after the byte planes are looked up and interleaved
// with unpacks (which work within 128-bit lanes), vector m holds texels 16m .. 16m + 15 in order:
// qp[16L + 4m + i] = q[16m + 4L + i]. (Gathers of the three tables took 40% of the horizontal pass: 4.4 cycles a
// texel; these permutes take about 1.)
struct LookupConstants {
    alignas(64) uint8_t from01[64] = {};  // byte index into texels 0..31 (two registers) of each qp lane
    alignas(64) uint8_t from23[64] = {};  // the same into texels 32..63
    uint64_t use23 = 0;                   // lanes of qp taken from texels 32..63
    constexpr LookupConstants() {
        for (int j = 0; j < 64; ++j) {
            const int L = j / 16, m = (j / 4) % 4, i = j % 4;
            const int t = 16 * m + 4 * L + i;       // texel of lane j
            from01[j] = uint8_t(4 * (t % 32) + 3);  // byte 3 of the texel: its level
            from23[j] = uint8_t(4 * (t % 32) + 3);
            if (t >= 32) use23 |= uint64_t(1) << j;
        }
    }
};
// Computed at compile time: no code of this AVX-512 file runs before the CPU has been checked.
constexpr LookupConstants kLookup;

inline __m512i lookup256(const uint8_t* table, __m512i q, __mmask64 high) {
    const __m512i lo = _mm512_permutex2var_epi8(_mm512_load_si512(table), q, _mm512_load_si512(table + 64));
    const __m512i hi = _mm512_permutex2var_epi8(_mm512_load_si512(table + 128), q, _mm512_load_si512(table + 192));
    return _mm512_mask_blend_epi8(high, lo, hi);
}

inline void lookup_floats(const uint8_t (*planes)[256], __m512i qp, __mmask64 high, __m512 out[4]) {
    const __m512i b0 = lookup256(planes[0], qp, high), b1 = lookup256(planes[1], qp, high);
    const __m512i b2 = lookup256(planes[2], qp, high), b3 = lookup256(planes[3], qp, high);
    const __m512i l01 = _mm512_unpacklo_epi8(b0, b1), h01 = _mm512_unpackhi_epi8(b0, b1);
    const __m512i l23 = _mm512_unpacklo_epi8(b2, b3), h23 = _mm512_unpackhi_epi8(b2, b3);
    out[0] = _mm512_castsi512_ps(_mm512_unpacklo_epi16(l01, l23));
    out[1] = _mm512_castsi512_ps(_mm512_unpackhi_epi16(l01, l23));
    out[2] = _mm512_castsi512_ps(_mm512_unpacklo_epi16(h01, h23));
    out[3] = _mm512_castsi512_ps(_mm512_unpackhi_epi16(h01, h23));
}

// Fills `s` with storage row r of the relief: u_i = (u_s + K1[q]) * R[q] + left margin as position and the final
// row coordinate v_i = (v_s + K2[q]) * R[q] + bottom margin as attribute, in float exactly as the reference's
// row_samples computes them. Returns the number of non-empty texels that cannot be pre-warped.
inline long long prepare_row(const ReliefTexture& t, const fast::FastTables& tab, const PrewarpExtent& e, int n_out,
                             int r, LineSoA& s) {
    const int w = t.width, h = t.height;
    const uint32_t* src = reinterpret_cast<const uint32_t*>(t.texels.data() + size_t(r) * size_t(w));
    const __m512 ou = _mm512_set1_ps(float(e.left)), ov = _mm512_set1_ps(float(e.bottom));
    const __m512 half = _mm512_set1_ps(0.5f);
    const __m512i from01 = _mm512_load_si512(kLookup.from01), from23 = _mm512_load_si512(kLookup.from23);
    const __m512 vs = _mm512_set1_ps(float(h - 1 - r) + 0.5f);  // P(h - 1 - r) + P(0.5)
    long long dropped = 0;
    if (tab.any_dropped)
        for (int x = 0; x < w; ++x) dropped += tab.dropped[src[x] >> 24];
    LineWriter lw(s, w, n_out);
    __m512 us = _mm512_add_ps(_mm512_cvtepi32_ps(iota16()), half);  // P(x) + P(0.5), x = 0 .. 15
    for (int x = 0; x < w; x += 64) {
        __m512i d[4];
        for (int m = 0; m < 4; ++m) d[m] = _mm512_maskz_loadu_epi32(first_lanes(w - x - 16 * m), src + x + 16 * m);
        const __m512i qp = _mm512_mask_blend_epi8(kLookup.use23, _mm512_permutex2var_epi8(d[0], from01, d[1]),
                                                  _mm512_permutex2var_epi8(d[2], from23, d[3]));
        const __mmask64 high = _mm512_movepi8_mask(qp);
        // 64 texels at zero displacement (the brick wall's bricks): (us + K1) * R + ou with K1 = +-0 and R = 1 is
        // us + ou exactly, and likewise v, without the lookups.
        if (tab.any_identity && x + 64 <= w && _mm512_movepi8_mask(lookup256(tab.identity, qp, high)) == ~0ull) {
            for (int m = 0; m < 4; ++m) {
                lw.put<true>(_mm512_add_ps(us, ou), d[m], _mm512_add_ps(vs, ov), 0xFFFF);
                us = _mm512_add_ps(us, _mm512_set1_ps(16.0f));
            }
            continue;
        }
        // Table by table, so that fewer registers are live at once (16 of the 32: no spills).
        __m512 rc[4], pos[4], v[4], tmp[4];
        lookup_floats(tab.plane[2], qp, high, rc);
        lookup_floats(tab.plane[0], qp, high, tmp);
        for (int m = 0; m < 4; ++m) {
            // (us + K1[q]) * R[q] + ou, operation by operation as row_samples; K1 is NaN where the level cannot be
            // pre-warped, which makes the position non-finite: not valid.
            pos[m] = _mm512_add_ps(_mm512_mul_ps(_mm512_add_ps(us, tmp[m]), rc[m]), ou);
            us = _mm512_add_ps(us, _mm512_set1_ps(16.0f));  // x + 0.5 stays exact (x < 2^22)
        }
        lookup_floats(tab.plane[1], qp, high, tmp);
        for (int m = 0; m < 4; ++m) v[m] = _mm512_add_ps(_mm512_mul_ps(_mm512_add_ps(vs, tmp[m]), rc[m]), ov);
        for (int m = 0; m < 4 && x + 16 * m < w; ++m) lw.put<true>(pos[m], d[m], v[m], 0xFFFF);
    }
    lw.finish();
    return dropped;
}

// Surface discontinuities along a row (paper section 4.1.1): removes the spans between texels k and k + 1 that the
// relief marks as not connected (kBreakRight in `row_breaks`, the row's marks), as the reference's RowConnected
// does in warp_line_to: with the span gone, sample k + 1 (k in the part after the split) starts a run of its own and
// is drawn as a point, exactly as warp_line_to's raster_point after an unconnected pair. Up span k joins k - 1 and
// k, down span k joins k + 1 and k; a one-pixel copy (ident) needs its up span. Returns whether the row has a mark.
inline bool apply_row_breaks(LineSoA& s, const uint8_t* row_breaks) {
    const int n = s.n;
    uint64_t carry = 0;  // the mark of the previous word's last texel
    bool any = false;
    for (int x = 0; x < n; x += 64) {
        const __mmask64 lanes = n - x >= 64 ? ~__mmask64(0) : (__mmask64(1) << (n - x)) - 1;
        const uint64_t b = _mm512_mask_test_epi8_mask(lanes, _mm512_maskz_loadu_epi8(lanes, row_breaks + x),
                                                      _mm512_set1_epi8(char(kBreakRight)));
        if (!(b | carry)) continue;
        any = any || b;
        const int w = x >> 6;
        const uint64_t up = (b << 1) | carry;
        s.up_inc[w] &= ~up;
        s.up_dec[w] &= ~up;
        s.ident[w] &= ~up;
        s.dn_inc[w] &= ~b;
        s.dn_dec[w] &= ~b;
        carry = b >> 63;
    }
    return any;
}

// The second attribute (LineSoA::attr2) of every sample of storage row r: its texel's displacement (the reference's
// tables' displ[q], what row_samples carries as RowAttr::d), carried by the row warp beside v for the columns'
// discontinuity threshold. Empty and dropped texels get whatever their level holds: they take no part.
inline void row_displacements(const ReliefTexture& t, const PrewarpTables& tab, int r, LineSoA& s) {
    const int w = t.width;
    const uint32_t* src = reinterpret_cast<const uint32_t*>(t.texels.data() + size_t(r) * size_t(w));
    for (int x = 0; x < w; x += 16) {
        const __mmask16 m = first_lanes(w - x);
        const __m512i q = _mm512_srli_epi32(_mm512_maskz_loadu_epi32(m, src + x), 24);
        _mm512_mask_storeu_ps(s.attr2 + x, m, _mm512_mask_i32gather_ps(_mm512_setzero_ps(), m, q, tab.displ.data(), 4));
    }
}

}  // namespace
}  // namespace rtm
