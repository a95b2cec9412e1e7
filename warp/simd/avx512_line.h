// The fast 1-D forward warp of one line (AVX-512), for warp/simd/avx512_two_pass.cpp and warp/simd/avx512_pipelined.cpp
// only.
//
// It computes exactly what warp_line_to (warp/line_warp.h) computes for float coordinates, samples connected unless
// the span between them was removed (discontinuity marks, apply_row_breaks in warp/simd/avx512_row.h) and one float
// attribute or none: the same occlusion-compatible order, the same spans, the same float
// operations per output pixel (no contraction into FMA: the files that include this header are compiled with
// -ffp-contract=off) and lerp8's integer colour interpolation, hence bit-identical pixels. What changes is how
// the work is organised:
//
// 1. Samples are written 16 at a time into a structure of arrays (position, packed colour, attribute,
//    1 / (pos[k] - pos[k-1]), floor/ceil(pos - 0.5) as clamped integers) with bit sets saying which samples take
//    part and which spans exist with which orientation (LineWriter).
// 2. The line is cut, in processing order, into points (a valid sample after an invalid one) and sub-runs:
//    maximal sequences of consecutive spans with the same orientation (positions increasing or decreasing),
//    found with bit scans. The spans of one sub-run cover disjoint pixels, so the pixels can be shaded in any
//    order; sub-runs are shaded one after the other in processing order, so painter's overwrites between them
//    (foldovers) come out as in the reference.
// 3. Sub-runs are shaded 16 spans at a time where possible: spans that cover at most two pixels each are shaded
//    span by span (first pixel, then second where there is one) from consecutive samples, and the pixels
//    compressed into place; spans one pixel wide on pixel centres (zero displacement) are copies. Otherwise the
//    pixels are shaded 16 at a time: the spans, left to right, start at non-decreasing pixels (the end of one span
//    and the start of the next come from the same floor or ceil), so the span covering a pixel is the last one
//    starting at or before it, found by a five-step branch-free binary search over a window of 32 starts with
//    two-register permutes; its end samples are fetched the same way (or with gathers when a block reaches over
//    more than 32 samples) and interpolated as raster_span does. Sub-runs of at most kScalarSpans spans
//    (foldover-heavy lines) go through raster_span itself.
//
// Include only after warp/simd/avx512_target_begin.h (the AVX-512 target) and after every other header: everything here
// is internal to the including file (anonymous namespace), so no inline function compiled for AVX-512 can leak
// into code that runs without it.
#pragma once

#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "warp/line_warp.h"

namespace rtm {
namespace {

constexpr int kPad = 64;  // samples of padding before and after every per-line array (windows read 32 past)

// std::aligned_alloc with the size rounded up to a multiple of the alignment, as the standard requires
// (AddressSanitizer rejects other sizes).
inline void* alloc64(size_t bytes) { return std::aligned_alloc(64, (bytes + 63) & ~size_t(63)); }
// Sub-runs with at most this many spans use the scalar raster_span (foldovers make many short sub-runs). 0, 2 and 4
// measured the same within noise on ridges 1024^2 (both passes 7.6 to 7.8 ms either way).
constexpr int kScalarSpans = 2;

inline int imin(int a, int b) { return a < b ? a : b; }
inline int imax(int a, int b) { return a > b ? a : b; }

inline bool bit(const uint64_t* m, int k) { return (m[k >> 6] >> (k & 63)) & 1; }

// Bits k .. k + 15 (k >= 0; the word after the last one read must exist).
inline uint32_t bits16(const uint64_t* m, int k) {
    const int w = k >> 6, b = k & 63;
    const uint64_t lo = m[w] >> b, hi = b ? m[w + 1] << (64 - b) : 0;
    return uint32_t((lo | hi) & 0xFFFF);
}

// One line's samples, structure of arrays, index k in [-kPad, n + kPad) addressable in every float/int array.
struct LineSoA {
    int n = 0;
    int n_out = 0;
    float* pos = nullptr;     // final position along the line, in output pixels (NaN or inf when invalid)
    float* attr = nullptr;    // carried attribute (final row coordinate)
    float* attr2 = nullptr;   // a second one (kAttr == 2: the displacement, for the columns' discontinuity test)
    float* inv = nullptr;     // 1 / (pos[k] - pos[k-1])
    int32_t* fl = nullptr;    // floor(pos - 0.5) clamped to [-1, n_out]
    int32_t* ce = nullptr;    // ceil(pos - 0.5) clamped to [-1, n_out]
    uint32_t* col = nullptr;  // packed colour r | g << 8 | b << 16 | x << 24 (x: whatever the source holds there)
    // Bit sets over k. valid: the sample takes part (valid and finite position). The others say that the span
    // ending at sample k exists (both samples take part) with an orientation: "up" spans join k - 1 and k (the part
    // before the split), "down" spans join k + 1 and k (the part after it); "inc" means pos[k] >= pos[other]
    // (raster_span's pb > pa case, or zero length), "dec" pos[k] < pos[other].
    uint64_t* valid = nullptr;
    uint64_t* up_inc = nullptr;
    uint64_t* up_dec = nullptr;
    uint64_t* dn_inc = nullptr;
    uint64_t* dn_dec = nullptr;
    // Bit k: samples k - 1 and k take part, both lie on pixel centres and pos[k] - pos[k-1] == 1. The up span k
    // then covers the one pixel of sample k, the down span k - 1 that of sample k - 1, each with t = 1 exactly:
    // the span copies its later sample. Zero displacement everywhere gives such spans, and a run of
    // them is a copy (the paper, section 5: skipping the transformation of zero-displacement texels).
    uint64_t* ident = nullptr;
};

// Per-thread storage for LineSoA, grown on demand and never shrunk (no allocation once the longest line has been
// seen).
struct LineStorage {
    void* block = nullptr;
    size_t capacity = 0;  // samples per array
    LineSoA soa;

    LineStorage() = default;
    LineStorage(const LineStorage&) = delete;
    LineStorage& operator=(const LineStorage&) = delete;
    ~LineStorage() { std::free(block); }

    void reserve(int n) {
        if (size_t(n) <= capacity) return;
        std::free(block);
        capacity = (size_t(n) + 63) & ~size_t(63);
        const size_t per_bytes = (capacity + 2 * kPad) * 4;
        const size_t mask_bytes = ((capacity / 64 + 2) * 8 + 63) & ~size_t(63);  // aligned_alloc: whole lines
        // aligned_alloc requires the size to be a multiple of the alignment (AddressSanitizer enforces it).
        const size_t total = (per_bytes * 7 + 6 * mask_bytes + 63) & ~size_t(63);
        block = alloc64(total);
        std::memset(block, 0, total);  // padding read by windows and masked-off lanes: keep it defined
        char* p = static_cast<char*>(block);
        auto take = [&](size_t bytes) {
            char* q = p;
            p += bytes;
            return q;
        };
        soa.pos = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.attr = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.attr2 = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.inv = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.fl = reinterpret_cast<int32_t*>(take(per_bytes)) + kPad;
        soa.ce = reinterpret_cast<int32_t*>(take(per_bytes)) + kPad;
        soa.col = reinterpret_cast<uint32_t*>(take(per_bytes)) + kPad;
        soa.valid = reinterpret_cast<uint64_t*>(take(mask_bytes));
        soa.up_inc = reinterpret_cast<uint64_t*>(take(mask_bytes));
        soa.up_dec = reinterpret_cast<uint64_t*>(take(mask_bytes));
        soa.dn_inc = reinterpret_cast<uint64_t*>(take(mask_bytes));
        soa.dn_dec = reinterpret_cast<uint64_t*>(take(mask_bytes));
        soa.ident = reinterpret_cast<uint64_t*>(take(mask_bytes));
    }
};

inline __m512i iota16() { return _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15); }

inline __mmask16 first_lanes(int count) {
    return count >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (count > 0 ? count : 0)) - 1u);
}

// Non-finite lanes (NaN or +-inf).
inline __mmask16 nonfinite(__m512 x) { return _mm512_fpclass_ps_mask(x, 0x01 | 0x08 | 0x10 | 0x80); }

// Writes the samples of one line 16 at a time, in order, and derives everything the warp needs from them.
struct LineWriter {
    LineSoA& s;
    __m512 prev_pos = _mm512_setzero_ps();
    __mmask16 prev_valid = 0;
    __mmask16 prev_centre = 0;
    int k = 0;  // first sample of the next chunk

    LineWriter(LineSoA& soa, int n, int n_out) : s(soa) {
        s.n = n;
        s.n_out = n_out;
    }

    // Samples k .. k + 15: position, packed colour (the fourth byte is ignored), attribute, and which of them are
    // valid before the finiteness test (lanes past the end are dropped here).
    template <bool kAttr>
    void put(__m512 pos, __m512i color, __m512 attr, __mmask16 valid_in) {
        const __mmask16 valid = valid_in & ~nonfinite(pos) & first_lanes(s.n - k);
        _mm512_storeu_ps(s.pos + k, pos);
        _mm512_storeu_si512(s.col + k, color);
        if constexpr (kAttr) _mm512_storeu_ps(s.attr + k, attr);
        // pos[k - 1] in each lane.
        const __m512 pm = _mm512_castsi512_ps(_mm512_alignr_epi32(_mm512_castps_si512(pos),
                                                                  _mm512_castps_si512(prev_pos), 15));
        const __m512 diff = _mm512_sub_ps(pos, pm);
        _mm512_storeu_ps(s.inv + k, _mm512_div_ps(_mm512_set1_ps(1.0f), diff));
        // Clamping in float before converting keeps huge positions (and the NaN of invalid samples) in range;
        // floor/ceil values beyond [-1, n_out] only ever meet pixel indices in [0, n_out - 1]. Clamping to
        // integers commutes with floor and ceil, which the conversions do (rounding down, up).
        const __m512 c5 = _mm512_sub_ps(pos, _mm512_set1_ps(0.5f));
        const __m512 cl = _mm512_max_ps(_mm512_set1_ps(-1.0f), _mm512_min_ps(_mm512_set1_ps(float(s.n_out)), c5));
        const __m512i fl = _mm512_cvt_roundps_epi32(cl, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
        const __m512i ce = _mm512_cvt_roundps_epi32(cl, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
        _mm512_storeu_si512(s.fl + k, fl);
        _mm512_storeu_si512(s.ce + k, ce);
        const int w = k >> 4;
        reinterpret_cast<uint16_t*>(s.valid)[w] = valid;
        const __mmask16 up = valid & __mmask16((valid << 1) | (prev_valid >> 15));
        reinterpret_cast<uint16_t*>(s.up_inc)[w] = _mm512_mask_cmp_ps_mask(up, pos, pm, _CMP_GE_OQ);
        reinterpret_cast<uint16_t*>(s.up_dec)[w] = _mm512_mask_cmp_ps_mask(up, pos, pm, _CMP_LT_OQ);
        // Both ends on pixel centres (pos - 0.5 an integer: floor = ceil) and exactly one apart. (A position
        // clamped to -1 or n_out also passes as a centre; the copy checks that its pixels are inside the line.)
        const __mmask16 centre = _mm512_cmpeq_epi32_mask(fl, ce);
        reinterpret_cast<uint16_t*>(s.ident)[w] = _mm512_mask_cmp_ps_mask(
            up & centre & __mmask16((centre << 1) | (prev_centre >> 15)), diff, _mm512_set1_ps(1.0f), _CMP_EQ_OQ);
        prev_centre = centre;
        if (k > 0) down_bits(pos, valid);
        prev_pos = pos;
        prev_valid = valid;
        k += 16;
    }

    // The "down" bits of the previous chunk, which need the first sample of this one.
    void down_bits(__m512 next_pos, __mmask16 next_valid) {
        const __m512 pp = _mm512_castsi512_ps(_mm512_alignr_epi32(_mm512_castps_si512(next_pos),
                                                                  _mm512_castps_si512(prev_pos), 1));
        const __mmask16 dn = prev_valid & __mmask16((prev_valid >> 1) | ((next_valid & 1) << 15));
        const int w = (k >> 4) - 1;
        reinterpret_cast<uint16_t*>(s.dn_inc)[w] = _mm512_mask_cmp_ps_mask(dn, prev_pos, pp, _CMP_GE_OQ);
        reinterpret_cast<uint16_t*>(s.dn_dec)[w] = _mm512_mask_cmp_ps_mask(dn, prev_pos, pp, _CMP_LT_OQ);
    }

    void finish() {
        if (k > 0) down_bits(_mm512_setzero_ps(), 0);
    }
};

// First index in [j, bound] whose bit is `value`, or bound + 1 (j <= bound).
template <bool value>
inline int scan_up(const uint64_t* m, int j, int bound) {
    int w = j >> 6;
    uint64_t z = (value ? m[w] : ~m[w]) & (~uint64_t(0) << (j & 63));
    while (!z) {
        if (((w + 1) << 6) > bound) return bound + 1;
        ++w;
        z = value ? m[w] : ~m[w];
    }
    return imin((w << 6) + int(_tzcnt_u64(z)), bound + 1);
}

// Last index in [bound, j] whose bit is `value`, or bound - 1 (bound <= j).
template <bool value>
inline int scan_down(const uint64_t* m, int j, int bound) {
    int w = j >> 6;
    uint64_t z = (value ? m[w] : ~m[w]) & (~uint64_t(0) >> (63 - (j & 63)));
    while (!z) {
        if ((w << 6) - 1 < bound) return bound - 1;
        --w;
        z = value ? m[w] : ~m[w];
    }
    return imax((w << 6) + 63 - int(_lzcnt_u64(z)), bound - 1);
}

// r | g << 8 | b << 16 | 255 << 24 from the 32-bit conversions of the three channels. The channels are in
// [0, 255] except after a NaN interpolation parameter, where the conversion gives 0x80000000 for all three and the
// result, as in the reference's uint8_t conversion (low byte of the 32-bit value), is (0, 0, 0, 255).
inline __m512i pack_rgb(__m512i r, __m512i g, __m512i b) {
    return _mm512_or_si512(_mm512_ternarylogic_epi32(r, _mm512_slli_epi32(g, 8), _mm512_slli_epi32(b, 16), 0xFE),
                           _mm512_set1_epi32(int(0xFF000000)));
}

// raster_span's interpolation parameter at pixel centre xc: t = (xc - pa) * inv, t = std::clamp(t, 0, 1)
// (max(0, min(1, t)) keeps a NaN as std::clamp does).
inline __m512 span_parameter(__m512 xc, __m512 pa, __m512 inv) {
    const __m512 t = _mm512_mul_ps(_mm512_sub_ps(xc, pa), inv);
    return _mm512_max_ps(_mm512_setzero_ps(), _mm512_min_ps(_mm512_set1_ps(1.0f), t));
}

// lerp8's n = min(int(t * 2^13), 2^13 - 1) for t = raster_span's clamp((xc - pa) * inv, 0, 1), straight from
// inv8192 = inv * 2^13: scaling by a power of two commutes with the rounding of the product and with the clamp
// (where the product is subnormal t * 2^13 < 1 either way, and where inv * 2^13 overflows t is 0 or 1 either way:
// xc - pa is never 0 inside a span), and min(x, 8191) before the conversion does the clamp to 1 and the minimum
// at once (a NaN gives 8191, as in lerp8). Two operations fewer than span_parameter then at.
inline __m512i span_weight(__m512 xc, __m512 pa, __m512 inv8192) {
    const __m512 s = _mm512_mul_ps(_mm512_sub_ps(xc, pa), inv8192);
    return _mm512_cvttps_epi32(_mm512_max_ps(_mm512_min_ps(s, _mm512_set1_ps(8191.0f)), _mm512_setzero_ps()));
}

// Byte indices that put channel c of a and b side by side as two 16-bit values, (a_c, b_c), in every 32-bit lane.
struct PairIndices {
    alignas(64) uint8_t idx[3][64] = {};
    constexpr PairIndices() {
        for (int c = 0; c < 3; ++c)
            for (int j = 0; j < 64; j += 4) {
                idx[c][j] = uint8_t(j + c);           // a (first table of the two-register permute)
                idx[c][j + 2] = uint8_t(64 + j + c);  // b
            }
    }
};
constexpr PairIndices kPairs;

// lerp8 (warp/line_warp.h) on the three channels of packed colours a and b, alpha 255: set up once per pair (three
// byte permutes make the pairs), evaluated at any t. Fixed point: w = int(t * 2^14) | 1, at most 2^14 - 1, then per
// channel a * (2^14 - w) + b * w + 2^13 as one dot product of 16-bit pairs accumulated onto 2^13 (AVX512-VNNI), and
// bits 14..21 of the three sums packed by bit-field selects. The blue sum also carries 0xFF << 22, which becomes the
// alpha byte (the sums stay below 2^22: no carry). 9 operations a pixel from n (see span_weight), against 20 for the
// float formula it replaced plus six conversions and ten integer operations to unpack each pair of colours. When it
// came in (256^2 bumps, fast two-pass, one thread) it took 0.285 -> 0.262 ms; the cheaper weights and packing below
// only exist in fixed point.
struct Lerp8 {
    __m512i pr, pg, pb;
    Lerp8(__m512i a, __m512i b) {
        const __mmask64 even16 = 0x5555555555555555ull;
        pr = _mm512_maskz_permutex2var_epi8(even16, a, _mm512_load_si512(kPairs.idx[0]), b);
        pg = _mm512_maskz_permutex2var_epi8(even16, a, _mm512_load_si512(kPairs.idx[1]), b);
        pb = _mm512_maskz_permutex2var_epi8(even16, a, _mm512_load_si512(kPairs.idx[2]), b);
    }
    // w = 2n + 1 with n = min(int(t * 2^13), 2^13 - 1) (the same as min(int(t * 2^14) | 1, 2^14 - 1)).
    __m512i at(__m512 t) const {
        return at_n(_mm512_min_epu32(_mm512_cvttps_epi32(_mm512_mul_ps(t, _mm512_set1_ps(8192.0f))),
                                     _mm512_set1_epi32(8191)));
    }
    // The same from n directly (see span_weight). The pair (2^14 - w, w) as one 32-bit value is
    // w * (2^16 - 1) + 2^14 = n * (2^17 - 2) + 2^16 + 2^14 - 1.
    __m512i at_n(__m512i n) const {
        const __m512i ww = _mm512_add_epi32(_mm512_mullo_epi32(n, _mm512_set1_epi32(0x1FFFE)),
                                            _mm512_set1_epi32(0x13FFF));
        const __m512i r = _mm512_dpwssd_epi32(_mm512_set1_epi32(8192), pr, ww);
        const __m512i g = _mm512_dpwssd_epi32(_mm512_set1_epi32(8192), pg, ww);
        const __m512i b = _mm512_dpwssd_epi32(_mm512_set1_epi32(8192 | (0xFF << 22)), pb, ww);
        // Bits 14..21 of each sum into its byte (and bits 22..29 of the blue sum, 0xFF, into the alpha byte): one
        // bit-field select per sum (vpmultishiftqb picks 8 bits at any offset of the qword, two lanes per qword).
        const __m512i sel = _mm512_set1_epi64(0x362E2E2E160E0E0Eull);  // offsets 14, 14, 14, 22, 46, 46, 46, 54
        const __m512i rr = _mm512_maskz_multishift_epi64_epi8(0x1111111111111111ull, sel, r);
        const __m512i rg = _mm512_mask_multishift_epi64_epi8(rr, 0x2222222222222222ull, sel, g);
        return _mm512_mask_multishift_epi64_epi8(rg, 0xCCCCCCCCCCCCCCCCull, sel, b);
    }
};

// Output of one line: colours (packed) and, when kAttr (1 or 2), the attribute and (kAttr == 2) the second one
// (LineSoA::attr2), all stride 1. The kernels below take kAttr as 0 (colour only), 1 or 2: with 2 both attributes
// are interpolated with the same parameter t per pixel, so one walk gives what two walks, one per attribute, gave.
struct LineOut {
    uint32_t* color = nullptr;
    float* attr = nullptr;
    int n = 0;  // pixels
    // Only pixels [clip_lo, clip_hi] are wanted: sub-runs wholly outside are skipped (pixels outside may or may not
    // be written; the caller's buffer must hold all n).
    int clip_lo = 0, clip_hi = INT32_MAX;
    // Copy spans one pixel wide on pixel centres (zero displacement) instead of shading them
    // (PrewarpOptions::copy_still_runs).
    bool copy = true;
    float* attr2 = nullptr;
};

// Shades output pixels x0 .. x0 + 15 (lanes m) of a sub-run whose spans are keyed by their later sample k (in
// processing order), the earlier one being k + A; kb holds the key of the span covering each pixel, kmin and
// kmax the extreme keys over the lanes of m.
template <int A, int kAttr>
inline void shade_block(const LineSoA& s, __m512i kb, int kmin, int kmax, int x0, __mmask16 m, const LineOut& out) {
    const int base = A < 0 ? kmin - 1 : kmin;
    const int top = A < 0 ? kmax : kmax + 1;
    __m512 pa, inv, va = _mm512_setzero_ps(), vb = _mm512_setzero_ps(), wa = va, wb = va;
    __m512i ca, cb;
    const __m512i sign = _mm512_set1_epi32(int(0x80000000));
    if (top - base < 32) {
        const __m512i ib = _mm512_sub_epi32(kb, _mm512_set1_epi32(base));
        const __m512i ia = _mm512_add_epi32(ib, _mm512_set1_epi32(A));
        auto perm = [&](const float* arr, __m512i i) {
            return _mm512_permutex2var_ps(_mm512_loadu_ps(arr + base), i, _mm512_loadu_ps(arr + base + 16));
        };
        pa = perm(s.pos, ia);
        // 1 / (pb - pa): for A = -1 it is inv[k]; for A = +1 it is 1 / (pos[k] - pos[k+1]) = -inv[k+1] exactly
        // (a - b = -(b - a) and 1 / -x = -(1 / x) in IEEE arithmetic).
        inv = A < 0 ? perm(s.inv, ib)
                    : _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(perm(s.inv, ia)), sign));
        const __m512i c0 = _mm512_loadu_si512(s.col + base), c1 = _mm512_loadu_si512(s.col + base + 16);
        ca = _mm512_permutex2var_epi32(c0, ia, c1);
        cb = _mm512_permutex2var_epi32(c0, ib, c1);
        if constexpr (kAttr) {
            va = perm(s.attr, ia);
            vb = perm(s.attr, ib);
        }
        if constexpr (kAttr == 2) {
            wa = perm(s.attr2, ia);
            wb = perm(s.attr2, ib);
        }
    } else {  // a block reaching over more than 32 samples (strong minification): gathers
        const __m512i ka = _mm512_add_epi32(kb, _mm512_set1_epi32(A));
        const __m512 z = _mm512_setzero_ps();
        auto gat = [&](const float* arr, __m512i i) { return _mm512_mask_i32gather_ps(z, m, i, arr, 4); };
        pa = gat(s.pos, ka);
        inv = A < 0 ? gat(s.inv, kb) : _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(gat(s.inv, ka)), sign));
        ca = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), m, ka, s.col, 4);
        cb = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), m, kb, s.col, 4);
        if constexpr (kAttr) {
            va = gat(s.attr, ka);
            vb = gat(s.attr, kb);
        }
        if constexpr (kAttr == 2) {
            wa = gat(s.attr2, ka);
            wb = gat(s.attr2, kb);
        }
    }
    // raster_span at the pixel centres x + 0.5: t, then lerp8 and attr_lerp.
    const __m512 xc = _mm512_add_ps(_mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(x0), iota16())),
                                    _mm512_set1_ps(0.5f));
    const __m512 t = span_parameter(xc, pa, inv);
    _mm512_mask_storeu_epi32(out.color + x0, m, Lerp8(ca, cb).at(t));
    if constexpr (kAttr)
        _mm512_mask_storeu_ps(out.attr + x0, m,
                              _mm512_add_ps(_mm512_mul_ps(va, _mm512_sub_ps(_mm512_set1_ps(1.0f), t)),
                                            _mm512_mul_ps(vb, t)));
    if constexpr (kAttr == 2)
        _mm512_mask_storeu_ps(out.attr2 + x0, m,
                              _mm512_add_ps(_mm512_mul_ps(wa, _mm512_sub_ps(_mm512_set1_ps(1.0f), t)),
                                            _mm512_mul_ps(wb, t)));
}

// The colour (packed, alpha 255) and attribute of pixels X, X + 1, .. X + N - 1 (N = 1, 2 or 4) of each of the 16
// spans keyed k0 .. k0 + 15 (the later sample of span k is k, the earlier k + A): raster_span's arithmetic, with the
// span's samples loaded directly (consecutive keys) instead of permuted, and set up once for the N pixels. The
// centre of X + j is that of X plus j, exactly (pixel indices stay below 2^22). Without kAttr, v is 0; w is the
// second attribute with kAttr == 2, else 0.
template <int A, int kAttr, int N>
__attribute__((always_inline)) inline void span_pixels(const LineSoA& s, int k0, __m512i X, __m512i (&c)[N],
                                                       __m512 (&v)[N], __m512 (&w)[N]) {
    static_assert(N == 1 || N == 2 || N == 4);
    const __m512i sign = _mm512_set1_epi32(int(0x80000000));
    const __m512 pa = _mm512_loadu_ps(s.pos + k0 + A);
    const __m512 inv = A < 0
                           ? _mm512_loadu_ps(s.inv + k0)
                           : _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(_mm512_loadu_ps(s.inv + k0 + 1)),
                                                                  sign));
    const Lerp8 lerp(_mm512_loadu_si512(s.col + k0 + A), _mm512_loadu_si512(s.col + k0));
    const __m512 one = _mm512_set1_ps(1.0f);
    __m512 va = _mm512_setzero_ps(), vb = _mm512_setzero_ps(), wa = va, wb = va;
    if constexpr (kAttr) {
        va = _mm512_loadu_ps(s.attr + k0 + A);
        vb = _mm512_loadu_ps(s.attr + k0);
    }
    if constexpr (kAttr == 2) {
        wa = _mm512_loadu_ps(s.attr2 + k0 + A);
        wb = _mm512_loadu_ps(s.attr2 + k0);
    }
    const __m512 xc = _mm512_add_ps(_mm512_cvtepi32_ps(X), _mm512_set1_ps(0.5f));
    for (int j = 0; j < N; ++j) {
        const __m512 t = span_parameter(j ? _mm512_add_ps(xc, _mm512_set1_ps(float(j))) : xc, pa, inv);
        c[j] = lerp.at(t);
        v[j] = kAttr ? _mm512_add_ps(_mm512_mul_ps(va, _mm512_sub_ps(one, t)), _mm512_mul_ps(vb, t))
                     : _mm512_setzero_ps();
        w[j] = kAttr == 2 ? _mm512_add_ps(_mm512_mul_ps(wa, _mm512_sub_ps(one, t)), _mm512_mul_ps(wb, t))
                          : _mm512_setzero_ps();
    }
}

// Pixels [p_lo, p_hi] of the spans i_beg .. i_end - 1 of a sub-run (shade_subrun's numbering), per pixel: each
// finds its span (the last one with st(i) <= x) by a branch-free binary search over a window of 32 starts with
// two-register permutes. Kept out of line: it serves long spans and foldovers, and inlined into the loop of
// shade_subrun it took registers from the common path.
template <int A, bool INC, int kAttr>
__attribute__((noinline)) void shade_per_pixel(const LineSoA& s, int kL, int i_beg, int i_end, int p_lo, int p_hi,
                                               const LineOut& out) {
    constexpr int step = (INC ? 1 : -1) * (A < 0 ? 1 : -1);
    const int32_t* F = INC ? s.fl : s.ce;
    const int off = INC ? kL + A : kL;
    auto st = [&](int i) { return F[off + step * i] + (INC ? 1 : 0); };
    const __m512i iota = iota16(), rev = _mm512_setr_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
    const __m512i big = _mm512_set1_epi32(INT32_MAX), one = _mm512_set1_epi32(1);
    // Starts of spans i0 .. i0 + 31 (INT32_MAX from i_end on).
    auto window = [&](int i0, __m512i& w0, __m512i& w1) {
        if constexpr (step > 0) {
            w0 = _mm512_loadu_si512(F + off + i0);
            w1 = _mm512_loadu_si512(F + off + i0 + 16);
        } else {
            w0 = _mm512_permutexvar_epi32(rev, _mm512_loadu_si512(F + off - i0 - 15));
            w1 = _mm512_permutexvar_epi32(rev, _mm512_loadu_si512(F + off - i0 - 31));
        }
        if constexpr (INC) {
            w0 = _mm512_add_epi32(w0, one);
            w1 = _mm512_add_epi32(w1, one);
        }
        const __m512i i = _mm512_add_epi32(iota, _mm512_set1_epi32(i0));
        const __m512i e = _mm512_set1_epi32(i_end);
        w0 = _mm512_mask_mov_epi32(w0, _mm512_cmpge_epi32_mask(i, e), big);
        w1 = _mm512_mask_mov_epi32(w1, _mm512_cmpge_epi32_mask(_mm512_add_epi32(i, _mm512_set1_epi32(16)), e), big);
    };
    auto search = [&](__m512i w0, __m512i w1, __m512i X) {  // largest r in [0, 31] with w[r] <= x (w[0] <= x)
        __m512i r = _mm512_setzero_si512();
        for (int d = 16; d >= 1; d >>= 1) {
            const __m512i c = _mm512_add_epi32(r, _mm512_set1_epi32(d));
            r = _mm512_mask_mov_epi32(r, _mm512_cmple_epi32_mask(_mm512_permutex2var_epi32(w0, c, w1), X), c);
        }
        return r;
    };
    // i0: the span of the first pixel of the block (st(i0) <= x0). The next block's is counted from the same
    // window, not taken from this block's search, so that blocks do not wait for one another (taking it from
    // the search made a 90-cycle chain from block to block).
    int i0 = i_beg;
    __m512i w0, w1;
    window(i0, w0, w1);
    for (int x0 = p_lo; x0 <= p_hi; x0 += 16) {
        const int nl = imin(16, p_hi - x0 + 1);
        const __mmask16 m = first_lanes(nl);
        const __m512i X = _mm512_add_epi32(_mm512_set1_epi32(x0), iota);
        const __m512i X16 = _mm512_set1_epi32(x0 + 16);
        const int cnt = int(_mm_popcnt_u32(_mm512_cmple_epi32_mask(w0, X16))) +
                        int(_mm_popcnt_u32(_mm512_cmple_epi32_mask(w1, X16)));
        int i_next = i0 + cnt - 1;  // the span of pixel x0 + 16
        __m512i i = _mm512_add_epi32(search(w0, w1, X), _mm512_set1_epi32(i0));
        if (cnt == 32) {
            // More than 31 spans start within these 16 pixels (strong minification): search on, window by
            // window.
            for (int j0 = i0 + 31; j0 + 1 < i_end;) {
                const __mmask16 more = m & _mm512_cmpeq_epi32_mask(i, _mm512_set1_epi32(j0));
                if (!more) break;
                __m512i v0, v1;
                window(j0, v0, v1);
                i = _mm512_mask_add_epi32(i, more, search(v0, v1, X), _mm512_set1_epi32(j0));
                j0 += 31;
            }
            while (i_next + 1 < i_end && st(i_next + 1) <= x0 + 16) ++i_next;
        }
        // Keys, and their range over the block: lanes lie between the spans of x0 and x0 + 16.
        const __m512i key = _mm512_add_epi32(_mm512_set1_epi32(kL), _mm512_mullo_epi32(i, _mm512_set1_epi32(step)));
        const int k0 = kL + step * i0, k1 = kL + step * imin(i_next, i_end - 1);
        shade_block<A, kAttr>(s, key, imin(k0, k1), imax(k0, k1), x0, m, out);
        i0 = i_next;
        if (x0 + 16 <= p_hi) window(i0, w0, w1);
    }
}

// A sub-run: spans keyed k_first .. k_last (inclusive, in processing order), all of orientation INC (pb >= pa) or
// DEC (pb < pa). Writes its pixels and returns their range [x_lo, x_hi] (empty when x_lo > x_hi).
//
// Left to right the spans are number i = 0 .. S-1, span i keyed kL + step * i, and start at st(i) = floor(pa - 0.5)
// + 1 (INC) or ceil(pb - 0.5) (DEC), a non-decreasing sequence whose next term, less one, is where the span ends
// (raster_span's first and last pixels; the clamped values compare with pixels in [0, n_out) exactly as the
// unclamped ones would).
//
// Spans of the usual sub-runs (keys increasing left to right) that cover at most 2 pixels are shaded 16 spans at
// a time, one or two pixels each, and the pixels compressed into place. Otherwise pixels are shaded 16 at a time,
// each finding its span (the last one with st(i) <= x) by a branch-free binary search over a window of 32 starts,
// and fetching its samples with two-register permutes. (Measured on a 1024-sample line at 1:1 with small
// perturbations, in TSC cycles a pixel: per pixel for every sub-run 4.1, about 100 vector operations a block of
// 16 with the vector units as the limit; per span where possible 2.1. Bumps 1024^2, both passes: 8.5 ->
// 6.5 ms. Earlier variants: a scatter of span keys to their first pixels and a running maximum, 1 ms of 9 at
// 1024^2 in the scatter alone; an unaligned 64-byte store of the key per span, 2.5x slower still.)
//
// kStrict (warp_line_reverse): exactly the pixels of [out.clip_lo, out.clip_hi] are written, none outside.
template <int A, bool INC, int kAttr, bool kStrict = false>
inline void shade_subrun(const LineSoA& s, int k_first, int k_last, const LineOut& out, int& x_lo, int& x_hi) {
    const int n_out = out.n;
    // Spans from left to right: processing order when positions increase, the reverse otherwise.
    const int kL = INC ? k_first : k_last, kR = INC ? k_last : k_first;
    constexpr int step = (INC ? 1 : -1) * (A < 0 ? 1 : -1);  // key increment from one span to the next on its right
    const int S = (kR - kL) * step + 1;
    // st(i) = F[off + step * i] (+ 1 for INC); the span ends at st(i + 1) - 1, also for the last one.
    const int32_t* F = INC ? s.fl : s.ce;
    const int off = INC ? kL + A : kL;
    auto st = [&](int i) { return F[off + step * i] + (INC ? 1 : 0); };
    x_lo = imax(st(0), 0);
    x_hi = imin(st(S) - 1, n_out - 1);
    if (x_lo > x_hi) return;
    const __m512i zero = _mm512_setzero_si512();
    const __m512i last = _mm512_set1_epi32(n_out - 1), one = _mm512_set1_epi32(1);
    auto per_pixel = [&](int i_beg, int i_end, int p_lo, int p_hi) {
        shade_per_pixel<A, INC, kAttr>(s, kL, i_beg, i_end, p_lo, p_hi, out);
    };

    // Lanes of 16 pixels from `base` inside the clip range (all of them when not strict).
    auto clip16 = [&](int base) -> __mmask16 {
        if constexpr (!kStrict) {
            return __mmask16(0xFFFF);
        } else {
            const int a = imax(out.clip_lo - base, 0), b = imin(out.clip_hi - base, 15);
            return a > b ? __mmask16(0) : __mmask16(((2u << b) - 1u) & ~((1u << a) - 1u));
        }
    };

    if constexpr (step < 0) {  // keys decreasing from left to right: foldovers only
        const int p_lo = imax(x_lo, out.clip_lo), p_hi = imin(x_hi, out.clip_hi);
        if (p_lo <= p_hi) {
            int i_beg = 0;
            if constexpr (kStrict) {
                // The last span starting at or before p_lo (binary search over the non-decreasing starts), so that
                // the per-pixel search does not walk the spans left of the clip range.
                int lo = 0, hi = S - 1;
                while (lo < hi) {
                    const int mid = (lo + hi + 1) >> 1;
                    if (st(mid) <= p_lo)
                        lo = mid;
                    else
                        hi = mid - 1;
                }
                i_beg = lo;
            }
            per_pixel(i_beg, S, p_lo, p_hi);
        }
    } else {
        // Interleaving of two vectors (first pixel, second pixel of each span), low and high halves.
        const __m512i il_lo = _mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
        const __m512i il_hi = _mm512_setr_epi32(8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31);
        for (int c0 = 0; c0 < S; c0 += 16) {
            const __mmask16 m = first_lanes(S - c0);
            const int k0 = kL + c0;
            if (st(imin(c0 + 16, S)) <= out.clip_lo) continue;  // these spans end left of the wanted pixels
            if (st(c0) > out.clip_hi) break;
            // Copies: every span one pixel wide on pixel centres, all inside the line (bricks 1024^2: horizontal
            // pass 2.75 -> 2.4 ms; bumps 256^2, where it never applies, 3% slower for the test).
            if (out.copy && (bits16(s.ident, A < 0 ? k0 : k0 + 1) & m) == m) {
                const int x0 = s.fl[k0];  // the pixel of span k0 (pos[k0] is its centre)
                const int nl = int(_mm_popcnt_u32(m));
                if (x0 >= 0 && x0 + nl <= n_out) {
                    const __mmask16 mc = m & clip16(x0);
                    _mm512_mask_storeu_epi32(out.color + x0, mc,
                                             _mm512_or_si512(_mm512_loadu_si512(s.col + k0),
                                                             _mm512_set1_epi32(int(0xFF000000))));
                    if constexpr (kAttr) _mm512_mask_storeu_ps(out.attr + x0, mc, _mm512_loadu_ps(s.attr + k0));
                    if constexpr (kAttr == 2) _mm512_mask_storeu_ps(out.attr2 + x0, mc, _mm512_loadu_ps(s.attr2 + k0));
                    continue;
                }
            }
            __m512i lo = _mm512_loadu_si512(F + off + c0), nx = _mm512_loadu_si512(F + off + c0 + 1);
            if constexpr (INC) {
                lo = _mm512_add_epi32(lo, one);
                nx = _mm512_add_epi32(nx, one);
            }
            lo = _mm512_max_epi32(lo, zero);
            const __m512i hi = _mm512_min_epi32(_mm512_sub_epi32(nx, one), last);
            const __m512i cnt = _mm512_sub_epi32(hi, lo);  // pixels - 1
            const __mmask16 has1 = _mm512_mask_cmpge_epi32_mask(m, cnt, zero);
            const __mmask16 has2 = _mm512_mask_cmpge_epi32_mask(m, cnt, one);
            const __mmask16 has3 = _mm512_mask_cmpge_epi32_mask(m, cnt, _mm512_set1_epi32(2));
            const int p0 = imax(st(c0), 0);  // the first pixel of these spans (empty ones start where the next does)
            if (!has1) continue;
            if (has3) {  // a span of 3 pixels or more: span by span up to 4, else per pixel
                const int c1 = imin(c0 + 16, S);
                // Spans of 3 and 4 pixels (stretched faces of foldover rows): span by span, four pixels each,
                // the pixels put in order with two rounds of permutes and compressed into place. Ridges, fast
                // two-pass (backward rows), one thread, medians of 6 interleaved runs: 256^2 0.290 -> 0.266 ms,
                // 1024^2 5.31 -> 4.91 ms (shade_per_pixel 19% -> 12.5% of the time). Forward rows too (the
                // pipelined kernel's, which shades every emission): ridges pipelined, one thread, medians of 5
                // interleaved runs, 256^2 0.486 -> 0.462 ms, 1024^2 8.67 -> 7.99; two-pass at 256^2 within
                // 1.5% for every relief. Bumps never gets here.
                if (!_mm512_mask_cmpge_epi32_mask(m, cnt, _mm512_set1_epi32(4))) {
                    const __mmask16 has4 = _mm512_mask_cmpge_epi32_mask(m, cnt, _mm512_set1_epi32(3));
                    __m512i c[4];
                    __m512 v[4], w[4];
                    span_pixels<A, kAttr, 4>(s, k0, lo, c, v, w);
                    const __m512i qa = _mm512_setr_epi64(0, 8, 1, 9, 2, 10, 3, 11);
                    const __m512i qb = _mm512_setr_epi64(4, 12, 5, 13, 6, 14, 7, 15);
                    const __m512i p12l = _mm512_permutex2var_epi32(c[0], il_lo, c[1]);
                    const __m512i p12h = _mm512_permutex2var_epi32(c[0], il_hi, c[1]);
                    const __m512i p34l = _mm512_permutex2var_epi32(c[2], il_lo, c[3]);
                    const __m512i p34h = _mm512_permutex2var_epi32(c[2], il_hi, c[3]);
                    const __m512i qc[4] = {_mm512_permutex2var_epi64(p12l, qa, p34l),
                                           _mm512_permutex2var_epi64(p12l, qb, p34l),
                                           _mm512_permutex2var_epi64(p12h, qa, p34h),
                                           _mm512_permutex2var_epi64(p12h, qb, p34h)};
                    // The four pixels of each span in pixel order (as the colours above).
                    auto in_order = [&](const __m512(&a)[4], __m512(&q)[4]) {
                        const __m512d a12l = _mm512_castps_pd(_mm512_permutex2var_ps(a[0], il_lo, a[1]));
                        const __m512d a12h = _mm512_castps_pd(_mm512_permutex2var_ps(a[0], il_hi, a[1]));
                        const __m512d a34l = _mm512_castps_pd(_mm512_permutex2var_ps(a[2], il_lo, a[3]));
                        const __m512d a34h = _mm512_castps_pd(_mm512_permutex2var_ps(a[2], il_hi, a[3]));
                        q[0] = _mm512_castpd_ps(_mm512_permutex2var_pd(a12l, qa, a34l));
                        q[1] = _mm512_castpd_ps(_mm512_permutex2var_pd(a12l, qb, a34l));
                        q[2] = _mm512_castpd_ps(_mm512_permutex2var_pd(a12h, qa, a34h));
                        q[3] = _mm512_castpd_ps(_mm512_permutex2var_pd(a12h, qb, a34h));
                    };
                    __m512 qv[4], qw[4];
                    if constexpr (kAttr) in_order(v, qv);
                    if constexpr (kAttr == 2) in_order(w, qw);
                    const uint32_t h1 = has1, h2 = has2, h3 = has3, h4 = has4;
                    int p = p0;
                    for (int g = 0; g < 4; ++g) {
                        const int sh = 4 * g;
                        const __mmask16 mg = __mmask16(_pdep_u32((h1 >> sh) & 0xF, 0x1111) |
                                                       _pdep_u32((h2 >> sh) & 0xF, 0x2222) |
                                                       _pdep_u32((h3 >> sh) & 0xF, 0x4444) |
                                                       _pdep_u32((h4 >> sh) & 0xF, 0x8888));
                        if (!mg) continue;
                        const int np = int(_mm_popcnt_u32(mg));
                        const __mmask16 ms = first_lanes(np) & clip16(p);
                        _mm512_mask_storeu_epi32(out.color + p, ms, _mm512_maskz_compress_epi32(mg, qc[g]));
                        if constexpr (kAttr)
                            _mm512_mask_storeu_ps(out.attr + p, ms, _mm512_maskz_compress_ps(mg, qv[g]));
                        if constexpr (kAttr == 2)
                            _mm512_mask_storeu_ps(out.attr2 + p, ms, _mm512_maskz_compress_ps(mg, qw[g]));
                        p += np;
                    }
                    continue;
                }
                const int q_lo = kStrict ? imax(p0, out.clip_lo) : p0;
                const int q_end = imin(st(c1) - 1, n_out - 1);
                const int q_hi = kStrict ? imin(q_end, out.clip_hi) : q_end;
                if (q_lo <= q_hi) per_pixel(c0, c1, q_lo, q_hi);
                continue;
            }
            if (!has2) {
                __m512i c[1];
                __m512 v[1], w[1];
                span_pixels<A, kAttr, 1>(s, k0, lo, c, v, w);
                const int np = int(_mm_popcnt_u32(has1));
                const __mmask16 ms = first_lanes(np) & clip16(p0);
                _mm512_mask_storeu_epi32(out.color + p0, ms, _mm512_maskz_compress_epi32(has1, c[0]));
                if constexpr (kAttr) _mm512_mask_storeu_ps(out.attr + p0, ms, _mm512_maskz_compress_ps(has1, v[0]));
                if constexpr (kAttr == 2)
                    _mm512_mask_storeu_ps(out.attr2 + p0, ms, _mm512_maskz_compress_ps(has1, w[0]));
                continue;
            }
            __m512i c[2];
            __m512 v[2], w[2];
            span_pixels<A, kAttr, 2>(s, k0, lo, c, v, w);
            const __m512i c1 = c[0], c2 = c[1];
            const __m512 v1 = v[0], v2 = v[1];
            // Pixel order: span by span, first pixel then second.
            const uint32_t m1 = has1, m2 = has2;
            const __mmask16 mlo = __mmask16(_pdep_u32(m1 & 0xFF, 0x5555) | _pdep_u32(m2 & 0xFF, 0xAAAA));
            const __mmask16 mhi = __mmask16(_pdep_u32(m1 >> 8, 0x5555) | _pdep_u32(m2 >> 8, 0xAAAA));
            const int nlo = int(_mm_popcnt_u32(mlo)), nhi = int(_mm_popcnt_u32(mhi));
            const __mmask16 slo = first_lanes(nlo) & clip16(p0), shi = first_lanes(nhi) & clip16(p0 + nlo);
            _mm512_mask_storeu_epi32(out.color + p0, slo,
                                     _mm512_maskz_compress_epi32(mlo, _mm512_permutex2var_epi32(c1, il_lo, c2)));
            _mm512_mask_storeu_epi32(out.color + p0 + nlo, shi,
                                     _mm512_maskz_compress_epi32(mhi, _mm512_permutex2var_epi32(c1, il_hi, c2)));
            if constexpr (kAttr) {
                _mm512_mask_storeu_ps(out.attr + p0, slo,
                                      _mm512_maskz_compress_ps(mlo, _mm512_permutex2var_ps(v1, il_lo, v2)));
                _mm512_mask_storeu_ps(out.attr + p0 + nlo, shi,
                                      _mm512_maskz_compress_ps(mhi, _mm512_permutex2var_ps(v1, il_hi, v2)));
            }
            if constexpr (kAttr == 2) {
                _mm512_mask_storeu_ps(out.attr2 + p0, slo,
                                      _mm512_maskz_compress_ps(mlo, _mm512_permutex2var_ps(w[0], il_lo, w[1])));
                _mm512_mask_storeu_ps(out.attr2 + p0 + nlo, shi,
                                      _mm512_maskz_compress_ps(mhi, _mm512_permutex2var_ps(w[0], il_hi, w[1])));
            }
        }
    }
}

// The reference span rasterizer for one span (a = earlier sample, b = later sample).
template <int kAttr>
inline void scalar_span(const LineSoA& s, int a, int b, const LineOut& out, int& x_lo, int& x_hi) {
    auto rgba = [](uint32_t c) { return Rgba8{uint8_t(c), uint8_t(c >> 8), uint8_t(c >> 16), uint8_t(c >> 24)}; };
    const Rgba8 rca = rgba(s.col[a]), rcb = rgba(s.col[b]);
    x_lo = out.n;
    x_hi = -1;
    raster_span(s.pos[a], rca, kAttr ? s.attr[a] : 0.0f, s.pos[b], rcb, kAttr ? s.attr[b] : 0.0f, out.n,
                [&](int x, Rgba8 c, float v) {
                    out.color[x] = uint32_t(c.r) | uint32_t(c.g) << 8 | uint32_t(c.b) << 16 | uint32_t(c.a) << 24;
                    if constexpr (kAttr) out.attr[x] = v;
                    x_lo = imin(x_lo, x);
                    x_hi = imax(x_hi, x);
                });
    // The second attribute: the same span again (the same pixels and parameters), its value only.
    if constexpr (kAttr == 2)
        raster_span(s.pos[a], rca, s.attr2[a], s.pos[b], rcb, s.attr2[b], out.n,
                    [&](int x, Rgba8, float v) { out.attr2[x] = v; });
}

// One part of the line: samples from `first` towards the split (A = -1: first = 0, end = split, increasing;
// A = +1: first = n - 1, end = split - 1, decreasing). on_range(x_lo, x_hi) is called after each group of writes.
template <int A, int kAttr, class OnRange>
inline void warp_part(const LineSoA& s, int first, int end, const LineOut& out, OnRange&& on_range) {
    constexpr int step = A < 0 ? 1 : -1;
    const uint64_t* inc_bits = A < 0 ? s.up_inc : s.dn_inc;
    const uint64_t* dec_bits = A < 0 ? s.up_dec : s.dn_dec;
    int k = first;
    while (k != end) {
        // The next sample that takes part.
        k = A < 0 ? scan_up<true>(s.valid, k, end - 1) : scan_down<true>(s.valid, k, end + 1);
        if (k == end) break;
        // A valid sample after an invalid one (or the first of the part): raster_point.
        const float p = s.pos[k];
        if (p >= 0.0f && p < float(out.n)) {
            const int x = int(p);
            out.color[x] = s.col[k] | 0xFF000000u;
            if constexpr (kAttr) out.attr[x] = s.attr[k];
            if constexpr (kAttr == 2) out.attr2[x] = s.attr2[k];
            on_range(x, x);
        }
        int j = k + step;
        while (j != end && (bit(inc_bits, j) || bit(dec_bits, j))) {
            // Span j joins samples j + A (earlier) and j; the sub-run runs on while the spans exist and keep the
            // orientation of the first.
            const bool inc = bit(inc_bits, j);
            const uint64_t* bits = inc ? inc_bits : dec_bits;
            const int e = A < 0 ? scan_up<false>(bits, j, end - 1) - 1 : scan_down<false>(bits, j, end + 1) + 1;
            const int spans = (e - j) * step + 1;
            int x_lo, x_hi;
            if (spans <= kScalarSpans) {
                for (int q = j;; q += step) {
                    scalar_span<kAttr>(s, q + A, q, out, x_lo, x_hi);
                    if (x_lo <= x_hi) on_range(x_lo, x_hi);
                    if (q == e) break;
                }
            } else {
                if (inc)
                    shade_subrun<A, true, kAttr>(s, j, e, out, x_lo, x_hi);
                else
                    shade_subrun<A, false, kAttr>(s, j, e, out, x_lo, x_hi);
                if (x_lo <= x_hi) on_range(x_lo, x_hi);
            }
            j = e + step;
        }
        // Sample j (if any) does not take part: the span to it does not exist and j - step does.
        k = j;
    }
}

// The whole line, as warp_line_to does it: the part before the split from the first sample, the part after it from
// the last sample, then the span across the split where samples split - 1 and split are connected (both take part
// and no discontinuity mark removed the up span keyed split, apply_row_breaks; without marks, connected samples
// are all pairs of adjacent samples that take part, as with AlwaysConnected).
template <int kAttr, class OnRange>
inline void warp_line_fast(const LineSoA& s, int split, const LineOut& out, OnRange&& on_range) {
    warp_part<-1, kAttr>(s, 0, split, out, on_range);
    warp_part<+1, kAttr>(s, s.n - 1, split - 1, out, on_range);
    if (split >= 1 && split < s.n && (bit(s.up_inc, split) || bit(s.up_dec, split))) {
        int x_lo, x_hi;
        scalar_span<kAttr>(s, split - 1, split, out, x_lo, x_hi);
        if (x_lo <= x_hi) on_range(x_lo, x_hi);
    }
}

// Bits of m set in [lo, hi] (0 when lo > hi).
inline int count_bits(const uint64_t* m, int lo, int hi) {
    if (lo > hi) return 0;
    const int w0 = lo >> 6, w1 = hi >> 6;
    const uint64_t first = ~uint64_t(0) << (lo & 63), last = ~uint64_t(0) >> (63 - (hi & 63));
    if (w0 == w1) return int(_mm_popcnt_u64(m[w0] & first & last));
    int c = int(_mm_popcnt_u64(m[w0] & first)) + int(_mm_popcnt_u64(m[w1] & last));
    for (int w = w0 + 1; w < w1; ++w) c += int(_mm_popcnt_u64(m[w]));
    return c;
}

// Whether warp_line_reverse should take the line: every sample takes part and at least one span in kFoldShare
// folds over (keys decreasing from left to right: spans of the part before the split with positions decreasing, of
// the part after it with positions increasing), i.e. later spans overwrite earlier ones. any_row: the first
// condition only (tests). Foldover spans per row: ridges a quarter to a half of the samples; bricks 8 to 15 of 256,
// 16 to 31 of 1024, where the backward order measured no faster or slower within noise (2.69 against 2.80 ms at
// 1024^2, 0.198 against 0.203 at 256^2, then the other way round), so bricks keeps the forward order.
constexpr int kFoldShare = 16;
inline bool line_folds_over(const LineSoA& s, int split, bool any_row = false) {
    const int n = s.n;
    if (n < 1) return false;
    for (int w = 0; w < (n >> 6); ++w)
        if (~s.valid[w]) return false;
    if ((n & 63) && (~s.valid[n >> 6] & ((uint64_t(1) << (n & 63)) - 1))) return false;
    if (any_row) return true;
    const int folds = count_bits(s.up_dec, 1, split - 1) + count_bits(s.dn_inc, split, n - 2);
    return folds > 0 && folds * kFoldShare >= n;
}

// The whole line as warp_line_fast (with no range callback), with the painter's algorithm run backwards: the items
// (points, sub-runs, single spans, the seam) in the reverse of warp_line_fast's order, each shading only the pixels
// that no later item (in the forward order) writes. A pixel's value does not depend on which other pixels are
// shaded, and the forward order leaves every pixel with the value of the last item that writes it, which is the
// first one here to reach it: the output is the same. The pixels written so far are kept as one interval
// [w_lo, w_hi]; every sample taking part (line_folds_over), the spans form one connected path from the seam
// outwards and an item's pixels always touch that interval. If one ever did not (returns false, some pixels
// written), the caller clears the line and warps it forwards.
//
// Why: on foldover-heavy reliefs most horizontal pixel shading is overwritten later in the same row (ridges 1024^2:
// 2.44 writes per pixel that survives its row, bumps 1.00, bricks 1.16), and shade_per_pixel took 40% of the
// two-pass kernel's time on ridges. Fast two-pass, ridges, one thread, `rtm bench` medians of 5 runs interleaved
// with the forward-only build: 1024^2 6.15 -> 4.04 ms, 256^2 0.376 -> 0.250 ms (two threads 3.12 -> 2.07, 0.209 ->
// 0.149); of that, the backward order alone 6.9 -> 4.9 and 0.40 -> 0.28, the four-pixel spans in shade_subrun the
// rest. Bumps and bricks (forward rows) unchanged within noise. Only the two-pass kernel uses it: the pipelined
// kernel's emitter receives the ranges of the forward order.
template <int kAttr>
inline bool warp_line_reverse(const LineSoA& s, int split, const LineOut& out) {
    const int n = s.n, n_out = out.n;
    int w_lo = 0, w_hi = -1;
    // An item writing pixels [lo, hi] (clamped to the line; empty when lo > hi) through shade(clip_lo, clip_hi),
    // which writes exactly its pixels inside the clip range.
    auto item = [&](int lo, int hi, auto&& shade) -> bool {
        lo = imax(lo, 0);
        hi = imin(hi, n_out - 1);
        if (lo > hi) return true;
        if (w_lo > w_hi) {
            shade(lo, hi);
            w_lo = lo;
            w_hi = hi;
            return true;
        }
        if (hi < w_lo - 1 || lo > w_hi + 1) return false;
        if (lo < w_lo) shade(lo, w_lo - 1);
        if (hi > w_hi) shade(w_hi + 1, hi);
        w_lo = imin(w_lo, lo);
        w_hi = imax(w_hi, hi);
        return true;
    };
    auto rgba = [](uint32_t c) { return Rgba8{uint8_t(c), uint8_t(c >> 8), uint8_t(c >> 16), uint8_t(c >> 24)}; };
    // The span from sample a (earlier) to b: raster_span's pixels, those in [cl, ch] only.
    auto span = [&](int a, int b) -> bool {
        const float pa = s.pos[a], pb = s.pos[b];
        int lo = 0, hi = -1;
        if (pb > pa) {
            lo = s.fl[a] + 1;
            hi = s.fl[b];
        } else if (pb < pa) {
            lo = s.ce[b];
            hi = s.ce[a] - 1;
        }
        return item(lo, hi, [&](int cl, int ch) {
            const float aa = kAttr ? s.attr[a] : 0.0f, ab = kAttr ? s.attr[b] : 0.0f;
            raster_span_pixels(pa, rgba(s.col[a]), aa, pb, rgba(s.col[b]), ab, cl, ch, [&](int x, Rgba8 c, float d) {
                out.color[x] = uint32_t(c.r) | uint32_t(c.g) << 8 | uint32_t(c.b) << 16 | 0xFF000000u;
                if constexpr (kAttr) out.attr[x] = d;
            });
            if constexpr (kAttr == 2)
                raster_span_pixels(pa, rgba(s.col[a]), s.attr2[a], pb, rgba(s.col[b]), s.attr2[b], cl, ch,
                                   [&](int x, Rgba8, float d) { out.attr2[x] = d; });
        });
    };
    auto point = [&](int k) -> bool {
        const float p = s.pos[k];
        if (!(p >= 0.0f && p < float(n_out))) return true;
        const int x = int(p);
        return item(x, x, [&](int, int) {
            out.color[x] = s.col[k] | 0xFF000000u;
            if constexpr (kAttr) out.attr[x] = s.attr[k];
            if constexpr (kAttr == 2) out.attr2[x] = s.attr2[k];
        });
    };
    // A sub-run keyed k_first .. k_last in processing order (as warp_part cuts it).
    auto subrun = [&]<int A, bool INC>(int k_first, int k_last) -> bool {
        constexpr int step = A < 0 ? 1 : -1;
        const int spans = (k_last - k_first) * step + 1;
        if (spans <= kScalarSpans) {
            for (int q = k_last;; q -= step) {
                if (!span(q + A, q)) return false;
                if (q == k_first) return true;
            }
        }
        // shade_subrun's pixel range st(0) .. st(S) - 1: from the first sample (k_first + A) to the last (k_last).
        const int lo = INC ? s.fl[k_first + A] + 1 : s.ce[k_last];
        const int hi = INC ? s.fl[k_last] : s.ce[k_first + A] - 1;
        return item(lo, hi, [&](int cl, int ch) {
            LineOut o = out;
            o.clip_lo = cl;
            o.clip_hi = ch;
            int xl, xh;
            shade_subrun<A, INC, kAttr, true>(s, k_first, k_last, o, xl, xh);
        });
    };
    if (split >= 1 && split < n && !span(split - 1, split)) return false;
    // The part after the split, from its last span (keyed split: samples split + 1 and split) outwards, then its
    // first sample.
    if (split < n) {
        for (int j = split; j <= n - 2;) {
            const bool inc = bit(s.dn_inc, j);
            const int e = scan_up<false>(inc ? s.dn_inc : s.dn_dec, j, n - 2) - 1;  // the sub-run's first key
            if (!(inc ? subrun.template operator()<+1, true>(e, j) : subrun.template operator()<+1, false>(e, j)))
                return false;
            j = e + 1;
        }
        if (!point(n - 1)) return false;
    }
    // The part before the split, from its last span (keyed split - 1) outwards, then its first sample.
    if (split > 0) {
        for (int j = split - 1; j >= 1;) {
            const bool inc = bit(s.up_inc, j);
            const int e = scan_down<false>(inc ? s.up_inc : s.up_dec, j, 1) + 1;
            if (!(inc ? subrun.template operator()<-1, true>(e, j) : subrun.template operator()<-1, false>(e, j)))
                return false;
            j = e - 1;
        }
        if (!point(0)) return false;
    }
    return true;
}

}  // namespace
}  // namespace rtm
