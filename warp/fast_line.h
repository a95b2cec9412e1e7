// The fast 1-D forward warp of one line (AVX-512), for warp/fast_two_pass.cpp and warp/fast_pipelined.cpp only.
//
// It computes exactly what warp_line_to (warp/line_warp.h) computes for float coordinates, always-connected
// samples and one float attribute or none: the same occlusion-compatible order, the same spans, the same float
// operations per output pixel (no contraction into FMA: the files that include this header are compiled with
// -ffp-contract=off), hence bit-identical pixels. What changes is how the work is organised:
//
// 1. Samples are prepared in SIMD into a structure of arrays (position, colour channels as floats, attribute,
//    1 / (pos[k] - pos[k-1]), floor/ceil(pos - 0.5) as clamped integers, validity).
// 2. The line is cut, in processing order, into points (a valid sample after an invalid one), and sub-runs:
//    maximal sequences of consecutive spans with the same orientation (positions increasing or decreasing).
//    The spans of one sub-run cover disjoint pixels, so the order within it does not matter and the pixels can be
//    shaded in any order; sub-runs are shaded one after the other in processing order, so painter's overwrites
//    between them (foldovers) come out as in the reference.
// 3. A sub-run is shaded per output pixel, 16 at a time: every pixel first learns which span covers it (a
//    branch-free "index fill": each span stores its key over its first pixel and the 15 after, the next span
//    overwrites from its own first pixel), then the span's end samples are fetched with two-register permutes
//    from a 32-sample window (or gathers when the window is wider) and interpolated like raster_span does.
//    Sub-runs of at most kScalarSpans spans (foldover-heavy lines) go through raster_span itself.
//
// Include only after `#pragma GCC target(RTM_FAST_TARGET)` and after every other header: everything here is
// internal to the including file (anonymous namespace), so no inline function compiled for AVX-512 can leak into
// code that runs without it.
#pragma once

#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "warp/line_warp.h"

namespace rtm {
namespace {

constexpr int kPad = 64;  // samples of padding before and after every per-line array (windows read 32 past)
// Sub-runs with at most this many spans use the scalar raster_span: setting up one 16-pixel block costs about
// as much as rasterizing three short spans one by one (ridges at 1024^2, 45 degrees: 2 is 4% faster than 0 and
// than 4).
constexpr int kScalarSpans = 2;

inline int imin(int a, int b) { return a < b ? a : b; }
inline int imax(int a, int b) { return a > b ? a : b; }

// One line's samples, structure of arrays, index k in [-kPad, n + kPad) valid for every array.
struct LineSoA {
    int n = 0;
    float* pos = nullptr;   // final position along the line, in output pixels (NaN or inf when invalid)
    float* r = nullptr;     // colour channels as floats
    float* g = nullptr;
    float* b = nullptr;
    float* attr = nullptr;  // carried attribute (final row coordinate), or null
    float* inv = nullptr;   // 1 / (pos[k] - pos[k-1])
    int32_t* fl = nullptr;  // floor(pos - 0.5) clamped to [-1, n_out]
    int32_t* ce = nullptr;  // ceil(pos - 0.5) clamped to [-1, n_out]
    uint32_t* col = nullptr;  // packed colour r | g << 8 | b << 16 | 255 << 24
    uint8_t* valid = nullptr;  // 1 when the sample takes part (valid and finite position)
};

// Per-thread storage for LineSoA and the pixel index, grown on demand and never shrunk (no allocation once the
// largest line has been seen).
struct LineStorage {
    void* block = nullptr;
    size_t capacity = 0;      // samples per array
    size_t idx_capacity = 0;  // pixels
    int32_t* idx = nullptr;   // span key per output pixel, kPad of padding after the end
    LineSoA soa;

    LineStorage() = default;
    LineStorage(const LineStorage&) = delete;
    LineStorage& operator=(const LineStorage&) = delete;
    ~LineStorage() { std::free(block); }

    void reserve(int n, int n_out) {
        if (size_t(n) <= capacity && size_t(n_out) <= idx_capacity) return;
        std::free(block);
        capacity = imax(int(capacity), n);
        idx_capacity = imax(int(idx_capacity), n_out);
        const size_t per = capacity + 2 * kPad;  // elements of 4 bytes, rounded to whole cache lines
        const size_t per_bytes = (per * 4 + 63) & ~size_t(63);
        const size_t valid_bytes = (per + 63) & ~size_t(63);
        const size_t idx_bytes = ((idx_capacity + kPad) * 4 + 63) & ~size_t(63);
        const size_t total = per_bytes * 9 + valid_bytes + idx_bytes;
        block = std::aligned_alloc(64, total);
        std::memset(block, 0, total);  // padding read by windows and masked-off lanes: keep it defined
        char* p = static_cast<char*>(block);
        auto take = [&](size_t bytes) {
            char* q = p;
            p += bytes;
            return q;
        };
        soa.pos = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.r = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.g = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.b = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.attr = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.inv = reinterpret_cast<float*>(take(per_bytes)) + kPad;
        soa.fl = reinterpret_cast<int32_t*>(take(per_bytes)) + kPad;
        soa.ce = reinterpret_cast<int32_t*>(take(per_bytes)) + kPad;
        soa.col = reinterpret_cast<uint32_t*>(take(per_bytes)) + kPad;
        soa.valid = reinterpret_cast<uint8_t*>(take(valid_bytes)) + kPad;
        idx = reinterpret_cast<int32_t*>(take(idx_bytes));
    }
};

inline __m512i iota16() { return _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15); }

inline __mmask16 first_lanes(int count) {
    return count >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (count > 0 ? count : 0)) - 1u);
}

// Non-finite lanes (NaN or +-inf).
inline __mmask16 nonfinite(__m512 x) { return _mm512_fpclass_ps_mask(x, 0x01 | 0x08 | 0x10 | 0x80); }

// The colour channels of packed texels (r | g << 8 | b << 16 | ...) as floats.
inline void unpack_rgb(__m512i c, __m512& r, __m512& g, __m512& b) {
    const __m512i m = _mm512_set1_epi32(0xFF);
    r = _mm512_cvtepi32_ps(_mm512_and_si512(c, m));
    g = _mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(c, 8), m));
    b = _mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(c, 16), m));
}

// Finishes the SoA of a line once pos, colours (and attr) are in place: validity, inverse span lengths, and the
// clamped floor / ceil of pos - 0.5 that give every span's pixel range. `vmask_of(k0)` must return the lanes of
// samples k0..k0+15 that are valid before the finiteness test.
template <class ValidMask>
inline void finish_soa(LineSoA& s, int n_out, ValidMask&& vmask_of) {
    const __m512 half = _mm512_set1_ps(0.5f), lo = _mm512_set1_ps(-1.0f), hi = _mm512_set1_ps(float(n_out));
    const __m512 one = _mm512_set1_ps(1.0f);
    for (int k = 0; k < s.n; k += 16) {
        const __mmask16 m = first_lanes(s.n - k);
        const __m512 p = _mm512_loadu_ps(s.pos + k);
        const __mmask16 ok = vmask_of(k) & ~nonfinite(p) & m;
        _mm_storeu_si128(reinterpret_cast<__m128i*>(s.valid + k),
                         _mm512_cvtepi32_epi8(_mm512_maskz_set1_epi32(ok, 1)));
        const __m512 pm = _mm512_loadu_ps(s.pos + k - 1);
        _mm512_storeu_ps(s.inv + k, _mm512_div_ps(one, _mm512_sub_ps(p, pm)));
        const __m512 c = _mm512_sub_ps(p, half);
        // Clamping in float before converting keeps huge positions (and the NaN of invalid samples) in range;
        // floor/ceil of values beyond [-1, n_out] only matter through min/max with 0 and n_out - 1.
        const __m512 f = _mm512_max_ps(lo, _mm512_min_ps(hi, _mm512_roundscale_ps(c, _MM_FROUND_TO_NEG_INF)));
        const __m512 e = _mm512_max_ps(lo, _mm512_min_ps(hi, _mm512_roundscale_ps(c, _MM_FROUND_TO_POS_INF)));
        _mm512_storeu_si512(s.fl + k, _mm512_cvttps_epi32(f));
        _mm512_storeu_si512(s.ce + k, _mm512_cvttps_epi32(e));
    }
    // The sample after the last must look invalid to the scans (arrays are padded).
    s.valid[s.n] = 0;
    s.valid[-1] = 0;
}

// Output of one line: colours (packed) and, when kAttr, the attribute, both stride 1.
struct LineOut {
    uint32_t* color = nullptr;
    float* attr = nullptr;
    int n = 0;  // pixels
};

// Shades output pixels [x0, X1] (at most 16 from x0) of a sub-run whose spans are keyed by their later sample
// k (processing order) with the earlier one at k + A; idx[x] is the key of the span covering pixel x.
template <int A, bool kAttr>
inline void shade_block(const LineSoA& s, const int32_t* idx, int x0, int X1, const LineOut& out) {
    const int nl = imin(16, X1 - x0 + 1);
    const __mmask16 m = first_lanes(nl);
    const __m512i kb = _mm512_maskz_loadu_epi32(m, idx + x0);
    const int kf = idx[x0], kl = idx[x0 + nl - 1];
    const int kmin = imin(kf, kl), kmax = imax(kf, kl);
    const int base = A < 0 ? kmin - 1 : kmin;
    const int top = A < 0 ? kmax : kmax + 1;
    __m512 pa, inv, ra, ga, ba, rb, gb, bb, va = _mm512_setzero_ps(), vb = _mm512_setzero_ps();
    if (top - base < 32) {
        const __m512i ib = _mm512_sub_epi32(kb, _mm512_set1_epi32(base));
        const __m512i ia = _mm512_add_epi32(ib, _mm512_set1_epi32(A));
        auto perm = [&](const float* arr, __m512i i) {
            return _mm512_permutex2var_ps(_mm512_loadu_ps(arr + base), i, _mm512_loadu_ps(arr + base + 16));
        };
        pa = perm(s.pos, ia);
        // 1 / (pb - pa): for A = -1 it is inv[k]; for A = +1 it is 1 / (pos[k] - pos[k+1]) = -inv[k+1] exactly
        // (a - b = -(b - a) and 1 / -x = -(1 / x) in IEEE arithmetic).
        inv = A < 0 ? perm(s.inv, ib) : _mm512_castsi512_ps(_mm512_xor_si512(
                                             _mm512_castps_si512(perm(s.inv, ia)), _mm512_set1_epi32(int(0x80000000))));
        ra = perm(s.r, ia);
        ga = perm(s.g, ia);
        ba = perm(s.b, ia);
        rb = perm(s.r, ib);
        gb = perm(s.g, ib);
        bb = perm(s.b, ib);
        if constexpr (kAttr) {
            va = perm(s.attr, ia);
            vb = perm(s.attr, ib);
        }
    } else {  // a window wider than 32 samples (strong minification): gathers
        const __m512i ka = _mm512_add_epi32(kb, _mm512_set1_epi32(A));
        const __m512 z = _mm512_setzero_ps();
        auto gat = [&](const float* arr, __m512i i) { return _mm512_mask_i32gather_ps(z, m, i, arr, 4); };
        pa = gat(s.pos, ka);
        inv = A < 0 ? gat(s.inv, kb)
                    : _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(gat(s.inv, ka)),
                                                           _mm512_set1_epi32(int(0x80000000))));
        ra = gat(s.r, ka);
        ga = gat(s.g, ka);
        ba = gat(s.b, ka);
        rb = gat(s.r, kb);
        gb = gat(s.g, kb);
        bb = gat(s.b, kb);
        if constexpr (kAttr) {
            va = gat(s.attr, ka);
            vb = gat(s.attr, kb);
        }
    }
    const __m512 half = _mm512_set1_ps(0.5f), one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
    // raster_span: t = (P(x) + P(0.5) - pa) * inv, t = std::clamp(t, 0, 1) (max(0, min(1, t)) keeps a NaN as
    // std::clamp does), then lerp8 and attr_lerp.
    const __m512 xc = _mm512_add_ps(_mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(x0), iota16())), half);
    __m512 t = _mm512_mul_ps(_mm512_sub_ps(xc, pa), inv);
    t = _mm512_max_ps(zero, _mm512_min_ps(one, t));
    const __m512 u = _mm512_sub_ps(one, t);
    auto lerp8 = [&](__m512 a, __m512 b) {
        // uint8_t(float) truncates towards zero and keeps the low byte of the 32-bit conversion.
        const __m512 f = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(a, u), _mm512_mul_ps(b, t)), half);
        return _mm512_and_si512(_mm512_cvttps_epi32(f), _mm512_set1_epi32(0xFF));
    };
    const __m512i cr = lerp8(ra, rb), cg = lerp8(ga, gb), cb = lerp8(ba, bb);
    const __m512i c = _mm512_or_si512(_mm512_or_si512(cr, _mm512_slli_epi32(cg, 8)),
                                      _mm512_or_si512(_mm512_slli_epi32(cb, 16), _mm512_set1_epi32(int(0xFF000000))));
    _mm512_mask_storeu_epi32(out.color + x0, m, c);
    if constexpr (kAttr)
        _mm512_mask_storeu_ps(out.attr + x0, m, _mm512_add_ps(_mm512_mul_ps(va, u), _mm512_mul_ps(vb, t)));
}

// A sub-run: spans keyed k_first .. k_last (inclusive, processing order, step -A... i.e. +1 when A = -1), all of
// orientation INC (pb >= pa... pb > pa, or zero length) or DEC (pb < pa). Writes its pixels, returns their range
// in [x_lo, x_hi] (empty when x_lo > x_hi).
template <int A, bool INC, bool kAttr>
inline void shade_subrun(const LineSoA& s, int32_t* idx, int k_first, int k_last, const LineOut& out, int& x_lo,
                         int& x_hi) {
    const int n_out = out.n;
    auto lo_of = [&](int k) { return imax(INC ? s.fl[k + A] + 1 : s.ce[k], 0); };
    auto hi_of = [&](int k) { return imin(INC ? s.fl[k] : s.ce[k + A] - 1, n_out - 1); };
    // Spans from left to right: processing order when positions increase, the reverse otherwise.
    const int kL = INC ? k_first : k_last, kR = INC ? k_last : k_first;
    const int step = (INC ? 1 : -1) * (A < 0 ? 1 : -1);
    x_lo = lo_of(kL);
    x_hi = hi_of(kR);
    if (x_lo > x_hi) return;
    for (int k = kL;; k += step) {
        const int lo = lo_of(k), hi = hi_of(k);
        const int L = imin(lo, n_out);
        const __m512i key = _mm512_set1_epi32(k);
        _mm512_storeu_si512(idx + L, key);
        for (int x = L + 16; x <= hi; x += 16) _mm512_storeu_si512(idx + x, key);
        if (k == kR) break;
    }
    for (int x = x_lo; x <= x_hi; x += 16) shade_block<A, kAttr>(s, idx, x, x_hi, out);
}

// The reference span rasterizer for one span (a = earlier sample, b = later sample).
template <bool kAttr>
inline void scalar_span(const LineSoA& s, int a, int b, const LineOut& out, int& x_lo, int& x_hi) {
    const uint32_t ca = s.col[a], cb = s.col[b];
    Rgba8 rca, rcb;
    std::memcpy(&rca, &ca, 4);
    std::memcpy(&rcb, &cb, 4);
    x_lo = out.n;
    x_hi = -1;
    raster_span(s.pos[a], rca, kAttr ? s.attr[a] : 0.0f, s.pos[b], rcb, kAttr ? s.attr[b] : 0.0f, out.n,
                [&](int x, Rgba8 c, float v) {
                    std::memcpy(&out.color[x], &c, 4);
                    if constexpr (kAttr) out.attr[x] = v;
                    x_lo = imin(x_lo, x);
                    x_hi = imax(x_hi, x);
                });
}

// One part of the line: samples from `first` towards the split (A = -1: first = 0, end = split, increasing;
// A = +1: first = n - 1, end = split - 1, decreasing). on_range(x_lo, x_hi) is called after each group of writes.
template <int A, bool kAttr, class OnRange>
inline void warp_part(const LineSoA& s, int first, int end, int32_t* idx, const LineOut& out, OnRange&& on_range) {
    constexpr int step = A < 0 ? 1 : -1;
    const float* P = s.pos;
    const uint8_t* V = s.valid;
    int k = first;
    while (k != end) {
        if (!V[k]) {
            k += step;
            continue;
        }
        // A valid sample after an invalid one (or the first of the part): raster_point.
        const float p = P[k];
        if (p >= 0.0f && p < float(out.n)) {
            const int x = int(p);
            out.color[x] = s.col[k];
            if constexpr (kAttr) out.attr[x] = s.attr[k];
            on_range(x, x);
        }
        int j = k + step;
        while (j != end && V[j]) {
            // Span j joins samples j + A (earlier) and j. Orientation of the sub-run starting here.
            const bool inc = P[j] >= P[j + A];
            int e = j, spans = 1;
            if (inc) {
                while (e + step != end && V[e + step] && P[e + step] >= P[e]) e += step, ++spans;
            } else {
                while (e + step != end && V[e + step] && P[e + step] < P[e]) e += step, ++spans;
            }
            int x_lo, x_hi;
            if (spans <= kScalarSpans) {
                for (int q = j;; q += step) {
                    scalar_span<kAttr>(s, q + A, q, out, x_lo, x_hi);
                    if (x_lo <= x_hi) on_range(x_lo, x_hi);
                    if (q == e) break;
                }
            } else {
                if (inc)
                    shade_subrun<A, true, kAttr>(s, idx, j, e, out, x_lo, x_hi);
                else
                    shade_subrun<A, false, kAttr>(s, idx, j, e, out, x_lo, x_hi);
                if (x_lo <= x_hi) on_range(x_lo, x_hi);
            }
            j = e + step;
        }
        k = j;
    }
}

// The whole line, as warp_line_to does it with AlwaysConnected: the part before the split from the first sample,
// the part after it from the last sample, then the span across the split.
template <bool kAttr, class OnRange>
inline void warp_line_fast(const LineSoA& s, int split, int32_t* idx, const LineOut& out, OnRange&& on_range) {
    warp_part<-1, kAttr>(s, 0, split, idx, out, on_range);
    warp_part<+1, kAttr>(s, s.n - 1, split - 1, idx, out, on_range);
    if (split >= 1 && split < s.n && s.valid[split - 1] && s.valid[split]) {
        int x_lo, x_hi;
        scalar_span<kAttr>(s, split - 1, split, out, x_lo, x_hi);
        if (x_lo <= x_hi) on_range(x_lo, x_hi);
    }
}

}  // namespace
}  // namespace rtm
