// The building blocks of the Highway pre-warp kernels (warp/simd/hwy_two_pass.cpp, warp/simd/hwy_pipelined.cpp),
// compiled once per target in each of them (Highway's -inl.h convention: included after hwy/foreach_target.h, this
// header's guard toggles with HWY_TARGET_TOGGLE). A row's samples (PrepareRow), its horizontal warp (WarpRow) and
// the step of the output columns by one row of pixels (ColumnStep), each the reference's arithmetic operation by
// operation in float (no contraction: the files are compiled with -ffp-contract=off, and SSE4 has no FMA anyway),
// the colour with lerp8's integer formula. The columns' pixels are drawn by warp/simd/hwy_columns-inl.h.
#if defined(RTM_WARP_SIMD_HWY_ROW_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RTM_WARP_SIMD_HWY_ROW_INL_H_
#undef RTM_WARP_SIMD_HWY_ROW_INL_H_
#else
#define RTM_WARP_SIMD_HWY_ROW_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "warp/line_warp.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"
#include "warp/tables.h"
#include "warp/simd/fast_tables.h"
#include "warp/simd/hwy_columns-inl.h"

HWY_BEFORE_NAMESPACE();
namespace rtm::simd::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Scratch of one row: positions, row coordinates, packed colours and (where a discontinuity threshold needs them)
// displacements of the source width, in the caller's memory.
struct RowScratch {
    float* pos;
    float* v;
    uint32_t* color;
    float* d = nullptr;
};

HWY_INLINE uint32_t pack(Rgba8 c) {
    return uint32_t(c.r) | uint32_t(c.g) << 8 | uint32_t(c.b) << 16 | uint32_t(c.a) << 24;
}

HWY_INLINE Rgba8 unpack(uint32_t u) { return {uint8_t(u), uint8_t(u >> 8), uint8_t(u >> 16), uint8_t(u >> 24)}; }

// One row of pixels: packed colour (alpha 255 where written) and final row coordinate, pixel x at c[x], v[x].
struct RowOut {
    uint32_t* c;
    float* v;
    // Copy runs of a vector of spans one pixel wide on pixel centres (zero displacement) instead of shading them
    // (PrewarpOptions::copy_still_runs; CopyStill). The row is the same either way.
    bool copy = false;
    int width = 0;  // pixels in the row (WarpRow and WarpRowBackward set it from their n_out)
    // A second attribute carried like the first (the displacement, for a discontinuity threshold), pixel x at
    // attr2[x]; null: none (then the row warps take no second attribute either).
    float* attr2 = nullptr;
    bool blend = false;  // StoreOwned's load, blend and store on AVX2 where a vector lies in the row (the job's)
};

// attr_lerp (warp/line_warp.h) a vector at a time: a * (1 - t) + b * t, operation by operation (no contraction).
template <class V>
HWY_INLINE V AttrLerp(V a, V b, V tt, V one) {
    return hn::Add(hn::Mul(a, hn::Sub(one, tt)), hn::Mul(b, tt));
}

// displacements_joined (warp/line_warp.h) a vector at a time, for a threshold > 0: |da - db| <= threshold, the
// difference's sign bit cleared.
template <class DF>
HWY_INLINE hn::Mask<DF> WithinThreshold(DF df, hn::Vec<DF> da, hn::Vec<DF> db, float threshold) {
    return hn::Le(hn::Abs(hn::Sub(da, db)), hn::Set(df, threshold));
}

// Both attributes of a sample where a row carries two, interpolated by the reference's attr_lerp for its RowAttr
// (each one a * (1 - t) + b * t): what the sample-by-sample paths hand to raster_point and raster_span.
struct TwoAttrs {
    float v, d;
};
inline TwoAttrs attr_lerp(TwoAttrs a, TwoAttrs b, float t) {
    return {a.v * (1.0f - t) + b.v * t, a.d * (1.0f - t) + b.d * t};
}

#if HWY_TARGET == HWY_AVX2
// Compression of 8 lanes on AVX2 for SpanLanes: for each mask of 8 bits, the indices of the set lanes in order (then
// the others), a nibble each. Highway 1.0.3's Compress keeps the same table as a local constexpr array, which GCC 12
// copies onto the stack (1 KiB, rep movs) on every call: 40% of the row warp's samples when it was tried here
// (bumps 1024^2 two-pass, 8 -> 12 ms).
struct Compress8Table {
    uint32_t packed[256];
    constexpr Compress8Table() : packed() {
        for (int m = 0; m < 256; ++m) {
            uint32_t p = 0;
            int k = 0;
            for (int i = 0; i < 8; ++i)
                if (m >> i & 1) p |= uint32_t(i) << (4 * k++);
            for (int i = 0; i < 8; ++i)
                if (!(m >> i & 1)) p |= uint32_t(i) << (4 * k++);
            packed[m] = p;
        }
    }
};
inline constexpr Compress8Table kCompress8;

// The lanes of v where `bits` is set, moved to the lowest lanes in order, stored at p (the other lanes not written:
// StoreOwned, the whole vector loaded, blended and stored with `blend`); returns how many.
HWY_INLINE int CompressStore8(__m256i v, unsigned bits, int32_t* p, bool blend) {
    const __m256i idx = _mm256_srlv_epi32(_mm256_set1_epi32(int32_t(kCompress8.packed[bits])),
                                          _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28));
    const int n = __builtin_popcount(bits);
    const hn::Full256<int32_t> di;
    const __m256i keep = _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    StoreOwned(hn::Vec256<int32_t>{_mm256_permutevar8x32_epi32(v, idx)}, hn::MaskFromVec(hn::Vec256<int32_t>{keep}), di,
               p, blend);
    return n;
}
#endif

#if HWY_TARGET == HWY_SSE4 || HWY_TARGET == HWY_NEON
// Compression of 4 lanes of 32 bits for SpanLanes: for each mask of 4 bits, the byte indices that move the set lanes
// to the lowest lanes in order (the others after them). (Highway 1.0.3's Compress keeps its table as a local constexpr
// array, which GCC 12 copies onto the stack on every call: see Compress8Table.)
struct Compress4Table {
    uint8_t idx[16][16];
    constexpr Compress4Table() : idx() {
        for (int m = 0; m < 16; ++m) {
            int k = 0;
            for (int pass = 0; pass < 2; ++pass)
                for (int i = 0; i < 4; ++i)
                    if (((m >> i) & 1) == (pass == 0 ? 1 : 0)) {
                        for (int b = 0; b < 4; ++b) idx[m][4 * k + b] = uint8_t(4 * i + b);
                        ++k;
                    }
        }
    }
};
alignas(16) inline constexpr Compress4Table kCompress4;
#endif

// Pixels x .. x + count - 1 (count >= 1) of row `out` from the first lanes of col and v (and of d, where the row
// carries out.attr2): a whole vector where count >= N; else, where the target stores some lanes of a vector
// (kMaskedStore), StoreOwned (the pixels past them unchanged: with out.blend, a load, blend and store on AVX2 where
// the vector lies in the row; a masked store instruction otherwise), elsewhere one by one (SSE4's and NEON's
// BlendedStore stores the whole vector).
template <class DF, class DI>
HWY_INLINE void StorePixels(DF df, DI di, const RowOut& out, int x, int count, hn::Vec<DI> col, hn::Vec<DF> v,
                            hn::Vec<DF> d) {
    const bool with2 = out.attr2 != nullptr;
    if (count >= int(hn::Lanes(df))) {
        hn::StoreU(col, di, reinterpret_cast<int32_t*>(out.c + x));
        hn::StoreU(v, df, out.v + x);
        if (with2) hn::StoreU(d, df, out.attr2 + x);
    } else if (kMaskedStore) {
        const auto m = hn::FirstN(di, size_t(count));
        const bool blend = out.blend && x + int(hn::Lanes(df)) <= out.width;  // the whole vector in the row
        StoreOwned(col, m, di, reinterpret_cast<int32_t*>(out.c + x), blend);
        StoreOwned(v, hn::RebindMask(df, m), df, out.v + x, blend);
        if (with2) StoreOwned(d, hn::RebindMask(df, m), df, out.attr2 + x, blend);
    } else {
        HWY_ALIGN int32_t tc[HWY_MAX_BYTES / 4] = {};
        HWY_ALIGN float tv[HWY_MAX_BYTES / 4] = {}, td[HWY_MAX_BYTES / 4] = {};
        hn::Store(col, di, tc);
        hn::Store(v, df, tv);
        hn::Store(d, df, td);
        for (int i = 0; i < count; ++i) {
            out.c[x + i] = uint32_t(tc[i]);
            out.v[x + i] = tv[i];
            if (with2) out.attr2[x + i] = td[i];
        }
    }
}

// The pixels of lanes `todo` of a vector of spans (from sample a to sample b: positions pa, pb, colours ca, cb,
// attributes va, vb and da, db) into row `out`: lane i's pixels xlo_i .. xhi_i (lo: xlo as floats), some or all of
// the pixels raster_span gives it, each with raster_span's colour (lerp8's integer formula) and carried row
// coordinate (and out.attr2's attribute, where the row carries one: attr_lerp) at the pixel's centre. The lanes'
// pixels are disjoint, in lane order, and together one run xa .. xb, handed to before(xa, xb) before any of them is
// written; `edge` says where each lane's pixels end for the lookup below: the centres past lane i's pixels are those
// above edge_i (`strict`) or at or above it. Where the run is at most 4 vectors long (spans of a pixel or two, the
// usual case), each pixel of it looks up its lane (the lane whose pixels contain it) and the run is computed and
// stored a vector of pixels at a time; otherwise the first pixel of every lane, then the second of those that have
// one, ..., stored lane by lane. On AVX2, lanes of at most two pixels each (bumps) go span by span, compressed into
// place (below).
template <class DF, class DI, class MI, class Before>
HWY_INLINE void DrawLanes(DF df, DI di, MI todo, hn::Vec<DF> lo, hn::Vec<DI> xlo, hn::Vec<DI> xhi, hn::Vec<DF> edge,
                          bool strict, hn::Vec<DF> pa, hn::Vec<DF> pb, hn::Vec<DI> ca, hn::Vec<DI> cb, hn::Vec<DF> va,
                          hn::Vec<DF> vb, hn::Vec<DF> da, hn::Vec<DF> db, RowOut out, const Before& before) {
    using VF = hn::Vec<DF>;
    using VI = hn::Vec<DI>;
    const int N = int(hn::Lanes(df));
    const bool with2 = out.attr2 != nullptr;
    const VF half = hn::Set(df, 0.5f), one = hn::Set(df, 1.0f), zero = hn::Zero(df);
    const VF inv = hn::Div(one, hn::Sub(pb, pa));
    HWY_ALIGN int32_t lane_x[HWY_MAX_BYTES / 4], lane_h[HWY_MAX_BYTES / 4], lane_on[HWY_MAX_BYTES / 4];
    hn::Store(xlo, di, lane_x);
    hn::Store(xhi, di, lane_h);
    // The first and last lanes with pixels, from the mask's bits (at most 64 lanes of 32 bits: SVE's 2048 bits).
#if HWY_TARGET <= HWY_AVX3
    const uint64_t mask_bits = todo.raw;  // the mask register itself
#else
    uint8_t mask_bytes[8] = {};
    hn::StoreMaskBits(di, todo, mask_bytes);
    uint64_t mask_bits = 0;
    for (int i = 0; i < 8; ++i) mask_bits |= uint64_t(mask_bytes[i]) << (8 * i);
#endif
    const int first = __builtin_ctzll(mask_bits), lastl = 63 - __builtin_clzll(mask_bits);
    const int xa = lane_x[first], xb = lane_h[lastl];
    before(xa, xb);
    const int len = xb - xa + 1;
#if HWY_TARGET <= HWY_AVX2 || HWY_TARGET == HWY_SSE4 || HWY_TARGET == HWY_NEON
    // The span-by-span paths below: every lane's span one or two pixels wide, and each lane's colour and attribute at
    // pixel centres c (raster_span's t, lerp8, attr_lerp).
    const bool narrow = hn::AllTrue(di, hn::Or(hn::Not(todo), hn::Lt(hn::Sub(xhi, xlo), hn::Set(di, 2))));
    const VF xc0 = hn::Add(lo, half);  // the centre of lo + 1 is xc0 + 1 exactly (pixel indices below 2^22)
    auto at = [&](VF c, VI & col, VF & v, VF & d) HWY_ATTR __attribute__((always_inline)) {
        // std::clamp(t, 0, 1) as Max and Min: t is never NaN (c - pa is not 0 inside a span, and 1 / (pb - pa) is
        // finite or infinite).
        const VF tt = hn::Max(zero, hn::Min(one, hn::Mul(hn::Sub(c, pa), inv)));
        col = Lerp8At(df, di, tt, ca, cb);
        v = AttrLerp(va, vb, tt, one);
        if (with2) d = AttrLerp(da, db, tt, one);
    };
#endif
#if HWY_TARGET == HWY_AVX2
    // Every lane's span one or two pixels wide (bumps: nearly every group): the lanes' first pixels, then their
    // second ones where they have one, a vector each from the lanes' own samples (no lookup), the two interleaved
    // into pixel order and compressed into place with masked stores (StoreOwned; as the hand-written AVX-512
    // kernels drew spans of up to two pixels).
    if (narrow) {
        int32_t* oc = reinterpret_cast<int32_t*>(out.c + xa);
        float* ov = out.v + xa;
        int32_t* od = with2 ? reinterpret_cast<int32_t*>(out.attr2 + xa) : nullptr;
        const bool blend = out.blend && xb + 8 < out.width;  // every vector stored below lies in the row
        VI c1;
        VF v1, d1 = zero;
        at(xc0, c1, v1, d1);
        const auto two = hn::And(todo, hn::Lt(xlo, xhi));
        const unsigned b1 = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(hn::VecFromMask(di, todo).raw)));
        if (hn::AllFalse(di, two)) {
            CompressStore8(c1.raw, b1, oc, blend);
            CompressStore8(_mm256_castps_si256(v1.raw), b1, reinterpret_cast<int32_t*>(ov), blend);
            if (with2) CompressStore8(_mm256_castps_si256(d1.raw), b1, od, blend);
            return;
        }
        VI c2;
        VF v2, d2 = zero;
        at(hn::Add(xc0, one), c2, v2, d2);
        // (a0 b0 a1 b1 a2 b2 a3 b3) and (a4 b4 .. a7 b7): the unpacks work within 128-bit blocks.
        auto zip = [](__m256i a, __m256i b, __m256i& l, __m256i& h) {
            const __m256i ul = _mm256_unpacklo_epi32(a, b), uh = _mm256_unpackhi_epi32(a, b);
            l = _mm256_permute2x128_si256(ul, uh, 0x20);
            h = _mm256_permute2x128_si256(ul, uh, 0x31);
        };
        __m256i cl4, ch4, vl4, vh4, ml4, mh4;
        zip(c1.raw, c2.raw, cl4, ch4);
        zip(_mm256_castps_si256(v1.raw), _mm256_castps_si256(v2.raw), vl4, vh4);
        zip(hn::VecFromMask(di, todo).raw, hn::VecFromMask(di, two).raw, ml4, mh4);  // the masks the same way
        const unsigned bl = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(ml4)));
        const unsigned bh = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(mh4)));
        int32_t* ovi = reinterpret_cast<int32_t*>(ov);
        const int n1 = CompressStore8(cl4, bl, oc, blend);
        CompressStore8(vl4, bl, ovi, blend);
        CompressStore8(ch4, bh, oc + n1, blend);
        CompressStore8(vh4, bh, ovi + n1, blend);
        if (with2) {
            __m256i dl4, dh4;
            zip(_mm256_castps_si256(d1.raw), _mm256_castps_si256(d2.raw), dl4, dh4);
            CompressStore8(dl4, bl, od, blend);
            CompressStore8(dh4, bh, od + n1, blend);
        }
        return;
    }
#elif HWY_TARGET <= HWY_AVX3
    // The same with 16 lanes: two-register permutes interleave, compress moves the lanes into place (in registers:
    // the compressing store to memory is slow on Zen 4), masked stores write them.
    if (narrow) {
        int32_t* oc = reinterpret_cast<int32_t*>(out.c + xa);
        int32_t* ov = reinterpret_cast<int32_t*>(out.v + xa);
        auto put = [](__m512i v, unsigned bits, int32_t* p) HWY_ATTR __attribute__((always_inline)) {
            const __mmask16 m = __mmask16(bits);
            _mm512_mask_storeu_epi32(p, __mmask16(_bzhi_u32(0xFFFFu, unsigned(_mm_popcnt_u32(bits)))),
                                     _mm512_maskz_compress_epi32(m, v));
            return int(_mm_popcnt_u32(bits));
        };
        int32_t* od = with2 ? reinterpret_cast<int32_t*>(out.attr2 + xa) : nullptr;
        VI c1;
        VF v1, d1 = zero;
        at(xc0, c1, v1, d1);
        const auto two = hn::And(todo, hn::Lt(xlo, xhi));
        const unsigned b1 = unsigned(todo.raw);
        if (hn::AllFalse(di, two)) {
            put(c1.raw, b1, oc);
            put(_mm512_castps_si512(v1.raw), b1, ov);
            if (with2) put(_mm512_castps_si512(d1.raw), b1, od);
            return;
        }
        VI c2;
        VF v2, d2 = zero;
        at(hn::Add(xc0, one), c2, v2, d2);
        // (a0 b0 a1 b1 .. a7 b7) and (a8 b8 .. a15 b15), the masks' bits the same way.
        const __m512i lo_idx = _mm512_set_epi32(23, 7, 22, 6, 21, 5, 20, 4, 19, 3, 18, 2, 17, 1, 16, 0);
        const __m512i hi_idx = _mm512_set_epi32(31, 15, 30, 14, 29, 13, 28, 12, 27, 11, 26, 10, 25, 9, 24, 8);
        const unsigned bits = _pdep_u32(b1, 0x55555555u) | _pdep_u32(unsigned(two.raw), 0xAAAAAAAAu);
        const __m512i w1 = _mm512_castps_si512(v1.raw), w2 = _mm512_castps_si512(v2.raw);
        const int n1 = put(_mm512_permutex2var_epi32(c1.raw, lo_idx, c2.raw), bits & 0xFFFFu, oc);
        put(_mm512_permutex2var_epi32(w1, lo_idx, w2), bits & 0xFFFFu, ov);
        put(_mm512_permutex2var_epi32(c1.raw, hi_idx, c2.raw), bits >> 16, oc + n1);
        put(_mm512_permutex2var_epi32(w1, hi_idx, w2), bits >> 16, ov + n1);
        if (with2) {
            const __m512i e1 = _mm512_castps_si512(d1.raw), e2 = _mm512_castps_si512(d2.raw);
            put(_mm512_permutex2var_epi32(e1, lo_idx, e2), bits & 0xFFFFu, od);
            put(_mm512_permutex2var_epi32(e1, hi_idx, e2), bits >> 16, od + n1);
        }
        return;
    }
#elif HWY_TARGET == HWY_SSE4 || HWY_TARGET == HWY_NEON
    // The same with 4 lanes, where no masked store exists: the run's pixels go out in whole-vector stores (the first
    // at xa, the second right after the first one's pixels, overwriting what the first wrote past them), and the at
    // most 4 pixels past the run that the stores overwrite are read before and written back after, all inside the row
    // (the caller's, written by this thread alone); otherwise the lane by lane loop below.
    if (xb + 4 < out.width && narrow) {
        const hn::Repartition<uint8_t, DI> du8;
        auto bits4 = [&](VI m) HWY_ATTR __attribute__((always_inline)) {
            uint8_t b[8] = {};
            hn::StoreMaskBits(di, hn::MaskFromVec(m), b);
            return unsigned(b[0]) & 15u;
        };
        // Lanes `bits` of v to the lowest lanes, stored whole at p; returns how many.
        auto put = [&](VI v, unsigned bits, int32_t* p) HWY_ATTR __attribute__((always_inline)) {
            const auto idx = hn::Load(du8, kCompress4.idx[bits]);
            hn::StoreU(hn::BitCast(di, hn::TableLookupBytes(hn::BitCast(du8, v), idx)), di, p);
            return int(hwy::PopCount(bits));
        };
        int32_t* oc = reinterpret_cast<int32_t*>(out.c + xa);
        int32_t* ov = reinterpret_cast<int32_t*>(out.v + xa);
        int32_t* od = with2 ? reinterpret_cast<int32_t*>(out.attr2 + xa) : nullptr;
        const VI keep_c = hn::LoadU(di, oc + len), keep_v = hn::LoadU(di, ov + len);
        const VI keep_d = with2 ? hn::LoadU(di, od + len) : hn::Zero(di);
        VI c1, c2;
        VF v1, v2, d1 = zero, d2 = zero;
        at(xc0, c1, v1, d1);
        const auto two = hn::And(todo, hn::Lt(xlo, xhi));
        const VI t1 = hn::VecFromMask(di, todo);
        if (hn::AllFalse(di, two)) {
            const unsigned b = bits4(t1);
            put(c1, b, oc);
            put(hn::BitCast(di, v1), b, ov);
            if (with2) put(hn::BitCast(di, d1), b, od);
        } else {
            at(hn::Add(xc0, one), c2, v2, d2);
            const VI t2 = hn::VecFromMask(di, two);
            const unsigned bl = bits4(hn::InterleaveLower(di, t1, t2)), bh = bits4(hn::InterleaveUpper(di, t1, t2));
            const VI w1 = hn::BitCast(di, v1), w2 = hn::BitCast(di, v2);
            const int n1 = put(hn::InterleaveLower(di, c1, c2), bl, oc);
            put(hn::InterleaveLower(di, w1, w2), bl, ov);
            put(hn::InterleaveUpper(di, c1, c2), bh, oc + n1);
            put(hn::InterleaveUpper(di, w1, w2), bh, ov + n1);
            if (with2) {
                const VI e1 = hn::BitCast(di, d1), e2 = hn::BitCast(di, d2);
                put(hn::InterleaveLower(di, e1, e2), bl, od);
                put(hn::InterleaveUpper(di, e1, e2), bh, od + n1);
            }
        }
        hn::StoreU(keep_c, di, oc + len);
        hn::StoreU(keep_v, di, ov + len);
        if (with2) hn::StoreU(keep_d, di, od + len);
        return;
    }
#endif
    // Measured (thread CPU time, bumps 1024^2 two-pass, samples in the row warp): AVX2 about even with the lane by
    // lane loop below, SSE4 8% slower; so only from 8 lanes on. SSE4 by lookup (session 33, 4096^2 two-pass, one
    // thread, medians of two interleaved runs of 10): runs longer than 4 vectors, bricks 83 -> 83 ms, ridges 141 ->
    // 149 to 152 ms; every run, bricks 83 -> 79 to 81 ms, ridges 141 -> 155 to 157 ms: neither.
    if (N >= 8) {
        // Each pixel of the run a vector at a time, from its lane: lane i's pixel centres lie in (pa_i, pb_i] (the
        // left part, fwd) or [pb_i, pa_i), and the lanes' ends follow the lane order, so a centre's lane is the
        // number of lanes whose span ends before it: pb_i < centre, or pa_i <= centre. The ends being in order,
        // only the lanes whose end lies among a vector's centres are compared (the ones before count whole, the
        // ones after not at all): a run of long spans costs about a comparison a lane, not a vector's lanes a vector.
        // Until session 33 runs longer than 4 vectors went lane by lane (the loop below), which the joints of the
        // brick wall take at 4096^2 (4 times the pixels of parallax of 1024^2): bricks 4096^2 two-pass, one thread,
        // medians of interleaved runs, `avx512` 49.5 -> 41.0 ms, `avx2` 57 -> 51 ms; ridges `avx512` 86 -> 81 ms,
        // `avx2` unchanged (docs/perf-history.md, "Long runs of spans and the column state").
        HWY_ALIGN float lane_end[HWY_MAX_BYTES / 4];
        hn::Store(edge, df, lane_end);
        auto ends_before = [strict](float e, float centre) { return strict ? e < centre : e <= centre; };
        const VI iota = hn::Iota(di, 0);  // hoisted: GCC 12 builds Iota(di, x) in memory (a store-forwarding stall)
        int i0 = first;                   // the lanes before i0 end before the vector's first centre
        for (int j = 0; j < len; j += N) {
            const VF xc = hn::Add(hn::ConvertTo(df, hn::Add(hn::Set(di, xa + j), iota)), half);
            const float c0 = float(xa + j) + 0.5f, c1 = c0 + float(N - 1);
            while (i0 < lastl && ends_before(lane_end[i0], c0)) ++i0;
            VI own = hn::Set(di, i0);
            for (int i = i0; i < lastl && ends_before(lane_end[i], c1); ++i) {
                const auto e = hn::Set(df, lane_end[i]);
                const auto before = strict ? hn::Lt(e, xc) : hn::Le(e, xc);
                own = hn::Sub(own, hn::VecFromMask(di, hn::RebindMask(di, before)));
            }
            own = hn::Min(own, hn::Set(di, lastl));  // the pixels past the run (not stored)
            const auto ix = hn::IndicesFromVec(df, own);
            const auto ixi = hn::IndicesFromVec(di, own);
            const VF tt = Clamp01(hn::Mul(hn::Sub(xc, hn::TableLookupLanes(pa, ix)), hn::TableLookupLanes(inv, ix)));
            const VI col = Lerp8At(df, di, tt, hn::TableLookupLanes(ca, ixi), hn::TableLookupLanes(cb, ixi));
            const VF v = AttrLerp(hn::TableLookupLanes(va, ix), hn::TableLookupLanes(vb, ix), tt, one);
            const VF d = with2 ? AttrLerp(hn::TableLookupLanes(da, ix), hn::TableLookupLanes(db, ix), tt, one) : zero;
            StorePixels(df, di, out, xa + j, len - j, col, v, d);
        }
        return;
    }
    HWY_ALIGN int32_t lane_c[HWY_MAX_BYTES / 4];
    HWY_ALIGN float lane_v[HWY_MAX_BYTES / 4], lane_d[HWY_MAX_BYTES / 4];
    VI x = xlo;
    VF xc = hn::Add(hn::ConvertTo(df, xlo), half);
    auto on = todo;
    while (!hn::AllFalse(di, on)) {
        const VF tt = Clamp01(hn::Mul(hn::Sub(xc, pa), inv));
        const VI col = Lerp8At(df, di, tt, ca, cb);
        const VF v = AttrLerp(va, vb, tt, one);
        hn::Store(x, di, lane_x);
        hn::Store(col, di, lane_c);
        hn::Store(v, df, lane_v);
        hn::Store(hn::VecFromMask(di, on), di, lane_on);
        if (with2) hn::Store(AttrLerp(da, db, tt, one), df, lane_d);
        for (int i = 0; i < N; ++i)
            if (lane_on[i]) {
                out.c[lane_x[i]] = uint32_t(lane_c[i]);
                out.v[lane_x[i]] = lane_v[i];
                if (with2) out.attr2[lane_x[i]] = lane_d[i];
            }
        x = hn::Add(x, hn::Set(di, 1));
        xc = hn::Add(xc, one);
        on = hn::AndNot(hn::Lt(xhi, x), on);
    }
}

// The spans of lanes `span` (pa != pb) into row `out` (DrawLanes): each lane's pixels lo .. hi as raster_span computes
// them (centres in (pa, pb] or [pb, pa), clamped to [0, n_out)), only those in [cl, ch] (the caller's clip range,
// within [0, n_out); the backward rows draw only the pixels no later span covers). The lanes are consecutive spans of
// one orientation, pb > pa in every lane of `span` where fwd and pb < pa elsewhere, whose pixels follow the lane order
// (DrawGroup reverses the lanes where they run the other way).
template <class DF, class DI, class MF, class Before>
HWY_INLINE void SpanLanes(DF df, DI di, MF span, hn::Vec<DF> pa, hn::Vec<DF> pb, hn::Vec<DI> ca, hn::Vec<DI> cb,
                          hn::Vec<DF> va, hn::Vec<DF> vb, hn::Vec<DF> da, hn::Vec<DF> db, bool fwd, RowOut out,
                          const Before& before, int cl, int ch) {
    using VF = hn::Vec<DF>;
    const VF half = hn::Set(df, 0.5f), one = hn::Set(df, 1.0f);
    // Every lane of `span` goes one way, pb > pa where fwd (its pixels from floor(pa - 0.5) + 1 to floor(pb - 0.5)),
    // pb < pa elsewhere (ceil(pb - 0.5) to ceil(pa - 0.5) - 1), as raster_span computes them.
    const VF pah = hn::Sub(pa, half), pbh = hn::Sub(pb, half);
    VF lo = fwd ? hn::Add(hn::Floor(pah), one) : hn::Ceil(pbh);
    VF hi = fwd ? hn::Floor(pbh) : hn::Sub(hn::Ceil(pah), one);
    // (pa and pb are finite in the lanes of `span`: Max and Min clamp there as the comparisons would.)
    lo = hn::Max(lo, hn::Set(df, float(cl)));
    hi = hn::Min(hi, hn::Set(df, float(ch)));
    const auto todo = hn::RebindMask(di, hn::And(span, hn::Le(lo, hi)));
    if (hn::AllFalse(di, todo)) return;
    // Pixels in [cl, ch] in the lanes of todo, the only ones used. A centre lies past lane i's pixels where it lies
    // past the span's later end: above pb (fwd), at or above pa (the other way).
    DrawLanes(df, di, todo, lo, ConvertInRange(di, lo), ConvertInRange(di, hi), fwd ? pb : pa, fwd, pa, pb, ca, cb, va,
              vb, da, db, out, before);
}

// warp_line_to (warp/line_warp.h) of one row into `out`, each pixel written in the reference's order, for samples whose
// position is NaN where they do not take part. Consecutive spans of one orientation (a sub-run: positions
// non-decreasing along the row, or non-increasing, which folds over what came before) have disjoint pixels, end to
// end: up to a vector of them at a time (GroupPrefix: at least kMinGroup) are drawn together (DrawGroup, SpanLanes),
// at their place in the reference's order; everything else goes sample by sample, in the reference's order, through
// its raster_point / raster_span (DrawSpan: spans of kWideSpan pixels or more a vector of pixels at a time).
//
// With a `range` other than NoRange, range.before(xa, xb) precedes each group of pixels written (one sample's, or
// one vector of spans'): pixels xa .. xb, every one of them written by the group (its pixels are contiguous: one
// span, or spans end to end), and range.done() follows the row.
struct NoRange {
    void before(int, int) const {}
    void done() const {}
};

// The pixels raster_point(p) and raster_span(pa, pb) write along a line of n (xa > xb: none), by their formulas.
inline void PointPixels(float p, int n, int& xa, int& xb) {
    xa = 0, xb = -1;
    if (p >= 0.0f && p < float(n)) xa = xb = int(p);
}
inline void SpanPixels(float pa, float pb, int n, int& xa, int& xb) {
    xa = 0, xb = -1;
    if (pa == pb) return;
    float lo, hi;
    if (pb > pa) {
        lo = std::floor(pa - 0.5f) + 1.0f;
        hi = std::floor(pb - 0.5f);
    } else {
        lo = std::ceil(pb - 0.5f);
        hi = std::ceil(pa - 0.5f) - 1.0f;
    }
    lo = std::max(lo, 0.0f);
    hi = std::min(hi, float(n - 1));
    if (!(lo <= hi)) return;
    xa = int(lo), xb = int(hi);
}

// Sub-runs shorter than this go span by span (the hand-written AVX-512 line kernel's kScalarSpans + 1).
constexpr int kMinGroup = 3;

// The spans from sample pa[i] to sample pb[i], i = 0 .. N - 1 (the lanes of one vector, in memory order), taken from
// the lowest lane up (from_low) or from the highest down: how many lead with one orientation, all samples taking
// part (0 when fewer than kMinGroup), and whether that is pb >= pa (up) or pb <= pa. The first `skip` lanes in that
// order are left out (a vector moved back from a part's end: they are spans drawn before) and not counted.
template <class DF>
HWY_INLINE int GroupPrefix(DF df, const float* pa_ptr, const float* pb_ptr, bool from_low, bool& up, int skip = 0) {
    const auto pa = hn::LoadU(df, pa_ptr), pb = hn::LoadU(df, pb_ptr);
    const auto fin = hn::And(hn::IsFinite(pa), hn::IsFinite(pb));
    const int N = int(hn::Lanes(df));
    auto lanes = [&](auto m) {  // the lanes asked about, the skipped ones set
        if (HWY_LIKELY(!skip)) return m;
        return hn::Or(m, from_low ? hn::FirstN(df, size_t(skip)) : hn::Not(hn::FirstN(df, size_t(N - skip))));
    };
    // The whole vector one way (bumps: every group): no prefix to find.
    auto ge = lanes(hn::And(fin, hn::Ge(pb, pa)));
    if (hn::AllTrue(df, ge)) {
        up = true;
        return N - skip;
    }
    auto le = lanes(hn::And(fin, hn::Le(pb, pa)));
    if (hn::AllTrue(df, le)) {
        up = false;
        return N - skip;
    }
    if (!from_low) {
        ge = hn::MaskFromVec(hn::Reverse(df, hn::VecFromMask(df, ge)));
        le = hn::MaskFromVec(hn::Reverse(df, hn::VecFromMask(df, le)));
    }
    auto lead = [&](auto m) {
        const intptr_t f = hn::FindFirstTrue(df, hn::Not(m));
        return f < 0 ? N : int(f);
    };
    const int mu = lead(ge), md = lead(le);
    up = mu >= md;
    const int m = std::max(mu, md) - skip;
    return m >= kMinGroup ? m : 0;
}

// Draws the m spans GroupPrefix found among the spans from sample a0 + i to sample b0 + i (b0 = a0 + 1 in the left
// part, a0 - 1 in the right part), only pixels in [cl, ch], after the `skip` lanes GroupPrefix left out. SpanLanes
// wants the lanes' pixels in lane order: the lanes are reversed where the pixels run the other way (left part: spans
// going down; right part: going up).
template <class DF, class Before>
HWY_INLINE void DrawGroup(DF df, const float* pos, const uint32_t* col, const float* attr, const float* attr2, int a0,
                          int b0, int m, bool from_low, bool up, RowOut out, const Before& before, int cl, int ch,
                          int skip = 0) {
    const hn::RebindToSigned<DF> di;
    const int N = int(hn::Lanes(df));
    const bool reverse = (b0 > a0) != up;
    auto mask = from_low ? hn::AndNot(hn::FirstN(df, size_t(skip)), hn::FirstN(df, size_t(skip + m)))
                         : hn::AndNot(hn::FirstN(df, size_t(N - skip - m)), hn::FirstN(df, size_t(N - skip)));
    if (reverse) mask = hn::MaskFromVec(hn::Reverse(df, hn::VecFromMask(df, mask)));
    auto lf = [&](const float* p) {
        const auto v = hn::LoadU(df, p);
        return reverse ? hn::Reverse(df, v) : v;
    };
    auto li = [&](const uint32_t* p) {
        const auto v = hn::LoadU(di, reinterpret_cast<const int32_t*>(p));
        return reverse ? hn::Reverse(di, v) : v;
    };
    const auto pa = lf(pos + a0), pb = lf(pos + b0);
    const auto da = attr2 ? lf(attr2 + a0) : hn::Zero(df), db = attr2 ? lf(attr2 + b0) : hn::Zero(df);
    SpanLanes(df, di, hn::And(mask, hn::Ne(pb, pa)), pa, pb, li(col + a0), li(col + b0), lf(attr + a0), lf(attr + b0),
              da, db, up, out, before, cl, ch);
}

// Whole vectors of spans after a group of them, while every lane goes the part's usual way (a smooth row, where
// positions increase along the row: the left part's spans k - 1 -> k going up, the right part's k + 1 -> k going
// down), without the loop's other tests: DrawGroup of each vector GroupPrefix finds whole that way (all of it, no lane
// skipped or reversed), from sample k (d = -1: the left part, lanes k .. k + N - 1 while they end before `end` = the
// split; d = +1: the right part, lanes k - N + 1 .. k while they start at or after `end` = the split). Returns the next
// k; the loop takes the vector that stopped the run (a vector of equal positions, which GroupPrefix calls up, too: it
// draws nothing either way).
template <class DF, class Before>
HWY_INLINE int SpanRun(DF df, const float* pos, const uint32_t* col, const float* attr, const float* attr2, int k,
                       int end, int d, int n_out, RowOut out, const Before& before) {
    const int N = int(hn::Lanes(df));
    for (;;) {
        const int b0 = d < 0 ? k : k - N + 1;  // the lanes' later samples (b0 + i), their earlier ones b0 + i + d
        if (d < 0 ? k + N > end : b0 < end) return k;
        bool up;
        if (GroupPrefix(df, pos + b0 + d, pos + b0, d < 0, up) != N || up != (d < 0)) return k;
        DrawGroup(df, pos, col, attr, attr2, b0 + d, b0, N, d < 0, d < 0, out, before, 0, n_out - 1);
        k -= d * N;
    }
}

// The spans ending at samples b .. b + N - 1 (the lanes of one vector), each from the sample on its other side (d =
// -1: the left part's spans s - 1 -> s; d = +1: the right part's s + 1 -> s), where they are one pixel wide on a pixel
// centre: neighbouring positions exactly 1 apart, sample s on a centre. Span s then writes the one pixel pos[s] - 0.5
// with t = 1 exactly (raster_span: (pb - pa) * (1 / (pb - pa))), that is sample s's colour (lerp8 at t = 1) and
// attribute (attr_lerp: a * 0 + b), and consecutive such spans write consecutive pixels: copied at memory speed. Zero
// displacement gives such runs (the paper, section 5: skipping the transformation of still texels; the hand-written
// AVX-512 kernels' `ident` runs). Copies the spans that lead in processing order (from lane 0 up in
// the left part, from lane N - 1 down in the right part) when all N are such spans or, on targets with a masked store,
// at least kMinGroup of them (the bricks of a wall end inside a vector), every pixel inside the line; returns how many
// (0: nothing written).
template <class DF, class Before>
HWY_INLINE int CopyStill(DF df, const float* pos, const uint32_t* col, const float* attr, const float* attr2, int b,
                         int d, int n_out, RowOut out, const Before& before) {
    const hn::RebindToSigned<DF> di;
    const int N = int(hn::Lanes(df));
    const auto ps = hn::LoadU(df, pos + b), pn = hn::LoadU(df, pos + b + d);
    const auto step = d < 0 ? hn::Sub(ps, pn) : hn::Sub(pn, ps);
    const auto c = hn::Sub(ps, hn::Set(df, 0.5f));
    const auto still = hn::And(hn::Eq(step, hn::Set(df, 1.0f)), hn::Eq(hn::Floor(c), c));
    int lead = N;
    if (!hn::AllTrue(df, still)) {
        if (!kMaskedStore) return 0;
        // The lanes in processing order: the right part's reversed.
        const auto order = d < 0 ? still : hn::MaskFromVec(hn::Reverse(df, hn::VecFromMask(df, still)));
        lead = int(hn::FindFirstTrue(df, hn::Not(order)));
        if (lead < kMinGroup) return 0;
    }
    // Lanes i0 .. i0 + lead - 1 write pixels x0 .. x0 + lead - 1; the vector is stored from pixel x0 - i0 (inside the
    // line too: the other lanes masked).
    const int i0 = d < 0 ? 0 : N - lead;
    const float x0f = pos[b + i0] - 0.5f;
    if (!(x0f >= float(i0) && x0f + float(lead) <= float(n_out))) return 0;
    const int x0 = int(x0f);
    before(x0, x0 + lead - 1);
    const auto alpha = hn::Set(di, int32_t(0xFF000000u));
    const auto cv = hn::Or(hn::LoadU(di, reinterpret_cast<const int32_t*>(col + b)), alpha);
    const auto av = hn::LoadU(df, attr + b);
    int32_t* oc = reinterpret_cast<int32_t*>(out.c + x0 - i0);
    float* ov = out.v + x0 - i0;
    if (lead == N) {
        hn::StoreU(cv, di, oc);
        hn::StoreU(av, df, ov);
        if (attr2) hn::StoreU(hn::LoadU(df, attr2 + b), df, out.attr2 + x0);
        return N;
    }
    const auto first = hn::FirstN(di, size_t(lead));
    const auto lanes = d < 0 ? first : hn::MaskFromVec(hn::Reverse(di, hn::VecFromMask(di, first)));
    const bool blend = out.blend && x0 - i0 + N <= n_out;  // the whole vector in the row (StoreOwned)
    StoreOwned(cv, lanes, di, oc, blend);
    StoreOwned(av, hn::RebindMask(df, lanes), df, ov, blend);
    if (attr2) StoreOwned(hn::LoadU(df, attr2 + b), hn::RebindMask(df, lanes), df, out.attr2 + x0 - i0, blend);
    return lead;
}

// The sample-by-sample paths of the row warps: raster_point and raster_span_pixels of samples a and b of one row
// carrying its attribute attr (and attr2, where not null, as TwoAttrs) into out.
struct ScalarRow {
    const float* pos;
    const uint32_t* col;
    const float* attr;
    const float* attr2;
    RowOut out;
    auto put1() const {
        return [o = out](int x, Rgba8 c, float v) {
            o.c[x] = pack(c);
            o.v[x] = v;
        };
    }
    auto put2() const {
        return [o = out](int x, Rgba8 c, TwoAttrs a) {
            o.c[x] = pack(c);
            o.v[x] = a.v;
            o.attr2[x] = a.d;
        };
    }
    void point(int k, int n_out) const {
        if (attr2)
            raster_point(pos[k], unpack(col[k]), TwoAttrs{attr[k], attr2[k]}, n_out, put2());
        else
            raster_point(pos[k], unpack(col[k]), attr[k], n_out, put1());
    }
    void span_pixels(int a, int b, int x0, int x1) const {
        if (attr2)
            raster_span_pixels(pos[a], unpack(col[a]), TwoAttrs{attr[a], attr2[a]}, pos[b], unpack(col[b]),
                               TwoAttrs{attr[b], attr2[b]}, x0, x1, put2());
        else
            raster_span_pixels(pos[a], unpack(col[a]), attr[a], pos[b], unpack(col[b]), attr[b], x0, x1, put1());
    }
};

// Spans of at least this many pixels go a vector of pixels at a time (DrawSpan): a brick's edge, stretched by
// the parallax between its face and the mortar, or a texel magnified by the view.
constexpr int kWideSpan = 4;

// raster_span_pixels of samples a and b, pixels x0 .. x1, into s.out (DrawSpan: from kWideSpan pixels on) a vector of
// pixels at a time, with the scalar formula's operations in its order, so the same bits: inv = 1 / (pb - pa), at each
// centre x + 0.5 (exact: pixel indices are below 2^22) t = clamp((x + 0.5 - pa) * inv, 0, 1), lerp8 (Lerp8At) and
// attr_lerp. (Not inlined: in the row warps' loops it slowed bumps and ridges, which have few such spans, by 2%.)
template <class DF>
HWY_NOINLINE void WideSpan(DF df, const ScalarRow& s, int a, int b, int x0, int x1) {
    using VF = hn::Vec<DF>;
    const hn::RebindToSigned<DF> di;
    const int N = int(hn::Lanes(df));
    const bool with2 = s.attr2 != nullptr;
    const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f), half = hn::Set(df, 0.5f);
    const VF pa = hn::Set(df, s.pos[a]);
    const VF inv = hn::Set(df, 1.0f / (s.pos[b] - s.pos[a]));
    const auto ca = hn::Set(di, int32_t(s.col[a])), cb = hn::Set(di, int32_t(s.col[b]));
    const VF va = hn::Set(df, s.attr[a]), vb = hn::Set(df, s.attr[b]);
    const VF da = with2 ? hn::Set(df, s.attr2[a]) : zero, db = with2 ? hn::Set(df, s.attr2[b]) : zero;
    const auto iota = hn::Iota(di, 0);
    for (int x = x0; x <= x1; x += N) {
        const VF xc = hn::Add(hn::ConvertTo(df, hn::Add(hn::Set(di, x), iota)), half);
        const VF tt = Clamp01(hn::Mul(hn::Sub(xc, pa), inv));
        const VF d = with2 ? AttrLerp(da, db, tt, one) : zero;
        StorePixels(df, di, s.out, x, x1 - x + 1, Lerp8At(df, di, tt, ca, cb), AttrLerp(va, vb, tt, one), d);
    }
}

// raster_span_pixels of samples a and b, pixels x0 .. x1 (x0 <= x1): WideSpan from kWideSpan pixels on, else the
// reference's loop.
template <class DF>
HWY_INLINE void DrawSpan(DF df, const ScalarRow& s, int a, int b, int x0, int x1) {
    if (x1 - x0 + 1 >= kWideSpan)
        WideSpan(df, s, a, b, x0, x1);
    else
        s.span_pixels(a, b, x0, x1);
}

// How many of the `count` spans keyed first, first + dir, ... lead before one whose pair the row's marks break
// (kBreakRight on the pair's left texel, which is the key itself: the left part's span k joins k - 1 and k and is
// looked up as k - 1 by its caller; the right part's span k joins k + 1 and k).
inline int UnbrokenLead(const uint8_t* marks, int first, int dir, int count) {
    for (int i = 0; i < count; ++i)
        if (marks[first + dir * i] & kBreakRight) return i;
    return count;
}

// `marks` (null: none) are the row's surface-discontinuity marks (ReliefTexture::breaks, paper section 4.1.1): no
// span joins texels k and k + 1 where texel k has kBreakRight, and the later of the two in the part's order starts a
// run of its own (a point), as warp_line_to with the reference's RowConnected. A group of spans stops before such a
// pair; a copy of still texels (CopyStill) needs no test: a still sample's pixel is the same whether it is joined to
// its neighbour (a one-pixel span at t = 1) or not (a point on the same pixel).
// `attr2` (null: none) is a second attribute carried like the first into out.attr2 (null exactly when it is).
template <class Range = NoRange>
void WarpRow(const float* pos, const uint32_t* col, const float* attr, const float* attr2, int n, int split, int n_out,
             RowOut out, const Range& range = {}, const uint8_t* marks = nullptr) {
    out.width = n_out;
    const hn::ScalableTag<float> df;
    const int N = int(hn::Lanes(df));
    constexpr bool kRange = !std::is_same_v<Range, NoRange>;
    const ScalarRow scalar{pos, col, attr, attr2, out};
    auto before = [&](int xa, int xb) {
        if constexpr (kRange) range.before(xa, xb);
    };
    auto span = [&](int a, int b) {
        int xa, xb;
        SpanPixels(pos[a], pos[b], n_out, xa, xb);
        if (xa > xb) return;
        before(xa, xb);
        DrawSpan(df, scalar, a, b, xa, xb);
    };
    auto ok = [&](int k) { return std::isfinite(pos[k]); };
    // Samples a and b (adjacent) joined: the reference's RowConnected.
    auto joined = [&](int a, int b) { return !marks || !(marks[std::min(a, b)] & kBreakRight); };
    // Sample k after sample `prev` (-1: none) in processing order: the reference's part loop body.
    auto one_sample = [&](int k, int prev) {
        if (!ok(k)) return -1;
        if (prev < 0 || !joined(prev, k)) {
            if constexpr (kRange) {
                int xa, xb;
                PointPixels(pos[k], n_out, xa, xb);
                if (xa <= xb) before(xa, xb);
            }
            scalar.point(k, n_out);
        } else {
            span(prev, k);
        }
        return k;
    };
    // Left part: k = 0 .. split - 1, spans k - 1 -> k.
    int prev = -1, k = 0;
    while (k < split) {
        // A group's vector: spans w0 .. w0 + N - 1, those from k on drawn; at the row's end it moves back (skip > 0),
        // and its lanes may reach past the split (loaded, not drawn).
        const int w0 = std::min(k, n - N);
        if (prev == k - 1 && prev >= 0 && w0 >= 1) {
            const int skip = k - w0;
            if (k + N <= split && out.copy) {
                const int copied = CopyStill(df, pos, col, attr, attr2, k, -1, n_out, out, before);
                if (copied) {
                    k += copied;
                    prev = k - 1;
                    continue;
                }
            }
            bool up;
            int m = std::min(GroupPrefix(df, pos + w0 - 1, pos + w0, true, up, skip), split - k);
            if (m && marks) m = UnbrokenLead(marks, k - 1, +1, m);
            if (m >= kMinGroup) {
                DrawGroup(df, pos, col, attr, attr2, w0 - 1, w0, m, true, up, out, before, 0, n_out - 1, skip);
                k += m;
                if (!marks && !out.copy) k = SpanRun(df, pos, col, attr, attr2, k, split, -1, n_out, out, before);
                prev = k - 1;
                continue;
            }
        }
        prev = one_sample(k, prev);
        ++k;
    }
    const int left_last = prev;
    // Right part: k = n - 1 down to split, spans k + 1 -> k.
    prev = -1;
    k = n - 1;
    while (k >= split) {
        // Lanes: samples b .. b + N - 1, each after sample + 1, processing order from lane N - 1, those from k down
        // drawn: at the row's start the vector moves up (skip > 0), and its lanes may reach below the split.
        const int b = std::max(k - N + 1, 0);
        if (prev == k + 1 && b + N <= n - 1) {
            const int skip = b + N - 1 - k;
            if (b >= split && !skip && out.copy) {
                const int copied = CopyStill(df, pos, col, attr, attr2, b, +1, n_out, out, before);
                if (copied) {
                    k -= copied;
                    prev = k + 1;
                    continue;
                }
            }
            bool up;
            int m = std::min(GroupPrefix(df, pos + b + 1, pos + b, false, up, skip), k - split + 1);
            if (m && marks) m = UnbrokenLead(marks, k, -1, m);
            if (m >= kMinGroup) {
                DrawGroup(df, pos, col, attr, attr2, b + 1, b, m, false, up, out, before, 0, n_out - 1, skip);
                k -= m;
                if (!marks && !out.copy) k = SpanRun(df, pos, col, attr, attr2, k, split, +1, n_out, out, before);
                prev = k + 1;
                continue;
            }
        }
        prev = one_sample(k, prev);
        --k;
    }
    const int right_last = prev;
    if (left_last >= 0 && right_last >= 0 && left_last == split - 1 && right_last == split &&
        joined(left_last, right_last))
        span(left_last, right_last);
    if constexpr (kRange) range.done();
}

// Whether WarpRowBackward should take the row: every sample takes part and (unless any_row, the tests' policy) at
// least one span in kFoldShare folds over (left of the split positions going down, right of it going up: later
// spans overwrite earlier ones). The hand-written AVX-512 kernels' rule (line_folds_over): bricks (8 to
// 31 foldover spans a row of 256 to 1024) stays forwards, ridges (a quarter to a half) goes backwards.
constexpr int kFoldShare = 16;
inline bool RowFoldsOver(const float* pos, int n, int split, bool any_row) {
    if (n < 1) return false;
    const hn::ScalableTag<float> df;
    const int N = int(hn::Lanes(df));
    // Pairs (k - 1, k), k = 1 .. n - 1, but the seam's (k == split): without foldovers the positions never go down
    // along the row, on either side of the split (the left part's span keyed k joins k - 1 -> k, the right part's
    // keyed k - 1 joins k -> k - 1); a span folds over where they do, pos[k] < pos[k - 1].
    // Counted in the lanes (a lane's count goes down by one for each: VecFromMask is -1), the seam's pair taken out
    // at the end.
    const hn::RebindToSigned<decltype(df)> di;
    auto count = hn::Zero(di);
    auto finite = hn::IsFinite(hn::Set(df, pos[0]));
    int k = 1;
    for (; k + N <= n; k += N) {
        const auto a = hn::LoadU(df, pos + k - 1), b = hn::LoadU(df, pos + k);
        finite = hn::And(finite, hn::IsFinite(b));
        count = hn::Add(count, hn::VecFromMask(di, hn::RebindMask(di, hn::Lt(b, a))));
    }
    bool all = hn::AllTrue(df, finite);
    int folds = -int(hn::GetLane(hn::SumOfLanes(di, count)));
    for (; k < n; ++k) {
        all = all && std::isfinite(pos[k]);
        folds += pos[k] < pos[k - 1];
    }
    if (split >= 1 && split < n && pos[split] < pos[split - 1]) --folds;
    if (!all) return false;
    if (any_row) return true;
    return folds > 0 && folds * kFoldShare >= n;
}

// WarpRowBackward's items for a vector of consecutive spans, in its order from lane 0 up (dir = +1) or from lane N - 1
// down (dir = -1), whichever way each span goes: each draws the pixels of its span (raster_span's, from pa_i to pb_i)
// outside the interval [w_lo, w_hi] written before it, which then grows by them. Each span's new pixels lie above the
// interval or below it; those above are one run whose pixels follow the order of the items, those below one run that
// goes the other way, and DrawLanes draws each (with the lanes reversed where the run goes down the lanes). The
// interval before and after each lane comes from prefix maxima and minima across the lanes. Returns false where a
// span does not touch the interval before it (WarpRowBackward's items do the same).
// WarpRowBackward takes a vector this way where no group of spans one way (GroupPrefix) starts it. A folding row's
// spans change direction every few spans (bumps 2048^2: groups of 13 spans on average, then two single spans), and
// until session 36 such vectors went span by span (raster_span_pixels), one span at a time between two GroupPrefix
// calls: bumps 2048^2 two-pass `avx512` 3.5% faster, 4096^2 5.6% (one thread, on a Zen 4; docs/perf-history.md).
// Taking every vector this way (no groups) made bumps 4096^2 11% faster but ridges 1024^2 13% slower: a group's
// spans mostly lie inside the interval there, which GroupPrefix and one test of the group's pixels skip cheaply.
template <class DF>
HWY_INLINE bool BackwardLanes(DF df, int dir, hn::Vec<DF> pa, hn::Vec<DF> pb, hn::Vec<hn::RebindToSigned<DF>> ca,
                              hn::Vec<hn::RebindToSigned<DF>> cb, hn::Vec<DF> va, hn::Vec<DF> vb, hn::Vec<DF> da,
                              hn::Vec<DF> db, int n_out, const RowOut& out, int& w_lo, int& w_hi) {
    using VF = hn::Vec<DF>;
    const hn::RebindToSigned<DF> di;
    using VI = hn::Vec<decltype(di)>;
    const int N = int(hn::Lanes(df));
    const VF half = hn::Set(df, 0.5f), one = hn::Set(df, 1.0f);
    // SpanPixels a lane at a time (pa == pb: none), clamped to [-1, n_out] besides (empty stays empty) for the
    // conversion.
    const auto up = hn::Gt(pb, pa);
    const VF pah = hn::Sub(pa, half), pbh = hn::Sub(pb, half);
    VF lof = hn::IfThenElse(up, hn::Add(hn::Floor(pah), one), hn::Ceil(pbh));
    VF hif = hn::IfThenElse(up, hn::Floor(pbh), hn::Sub(hn::Ceil(pah), one));
    lof = hn::Min(hn::Max(lof, hn::Zero(df)), hn::Set(df, float(n_out)));
    hif = hn::Max(hn::Min(hif, hn::Set(df, float(n_out - 1))), hn::Set(df, -1.0f));
    const VI lo = ConvertInRange(di, lof), hi = ConvertInRange(di, hif);
    const auto todo = hn::Not(hn::Gt(lo, hi));
    if (hn::AllFalse(di, todo)) return true;
    if (w_lo > w_hi) {
        // Nothing written yet: the first span with pixels draws them all, as if after the empty interval at its
        // first pixel.
        HWY_ALIGN int32_t lane_lo[HWY_MAX_BYTES / 4], lane_hi[HWY_MAX_BYTES / 4];
        hn::Store(lo, di, lane_lo);
        hn::Store(hi, di, lane_hi);
        for (int k = 0; k < N; ++k) {
            const int i = dir > 0 ? k : N - 1 - k;
            if (lane_lo[i] <= lane_hi[i]) {
                w_lo = lane_lo[i];
                w_hi = w_lo - 1;
                break;
            }
        }
    }
    // Prefix maxima of the spans' last pixels and minima of their first ones in the items' order (lanes without
    // pixels left out), inclusive and exclusive, then with the interval before the vector: the interval after each
    // lane and before it. (The scans do not depend on w_lo and w_hi, which carry from vector to vector.)
    const VI iota = hn::Iota(di, 0), izero = hn::Zero(di), ione = hn::Set(di, 1), top = hn::Set(di, N - 1);
    const VI none_hi = hn::Set(di, -(1 << 30)), none_lo = hn::Set(di, 1 << 30);
    auto from = [&](int s) {  // the lane s before each in the items' order (itself where there is none)
        return hn::IndicesFromVec(di, dir > 0 ? hn::Max(hn::Sub(iota, hn::Set(di, s)), izero)
                                              : hn::Min(hn::Add(iota, hn::Set(di, s)), top));
    };
    VI scan_hi = hn::IfThenElse(todo, hi, none_hi), scan_lo = hn::IfThenElse(todo, lo, none_lo);
    for (int s = 1; s < N; s *= 2) {
        const auto ix = from(s);
        scan_hi = hn::Max(scan_hi, hn::TableLookupLanes(scan_hi, ix));
        scan_lo = hn::Min(scan_lo, hn::TableLookupLanes(scan_lo, ix));
    }
    const auto first = dir > 0 ? hn::FirstN(di, 1) : hn::Not(hn::FirstN(di, size_t(N - 1)));
    const auto ix1 = from(1);
    const VI before_hi = hn::IfThenElse(first, none_hi, hn::TableLookupLanes(scan_hi, ix1));
    const VI before_lo = hn::IfThenElse(first, none_lo, hn::TableLookupLanes(scan_lo, ix1));
    const VI w_hi_v = hn::Set(di, w_hi), w_lo_v = hn::Set(di, w_lo);
    const VI incl_hi = hn::Max(scan_hi, w_hi_v);
    const VI excl_hi = hn::Max(before_hi, w_hi_v), excl_lo = hn::Min(before_lo, w_lo_v);
    const auto apart = hn::Or(hn::Lt(hi, hn::Sub(excl_lo, ione)), hn::Gt(lo, hn::Add(excl_hi, ione)));
    if (!hn::AllFalse(di, hn::And(todo, apart))) return false;
    // The scans' last lanes in the items' order hold the whole vector's.
    const auto last = [&](VI v) { return int(hn::GetLane(dir > 0 ? hn::Reverse(di, v) : v)); };
    w_hi = std::max(w_hi, last(scan_hi));
    w_lo = std::min(w_lo, last(scan_lo));
    auto no_before = [](int, int) {};
    const auto rf = [df](VF v) { return hn::Reverse(df, v); };
    const auto ri = [di](VI v) { return hn::Reverse(di, v); };
    // Above: pixels excl_hi + 1 .. hi, ending at incl_hi; below: lo .. excl_lo - 1, ending at excl_lo - 1 (the lanes'
    // ends for DrawLanes' lookup, in the order of the run's pixels).
    const auto ups = hn::And(todo, hn::Gt(hi, excl_hi));
    if (!hn::AllFalse(di, ups)) {
        const VI xl = hn::Add(excl_hi, ione);
        const VF end = hn::Add(hn::ConvertTo(df, incl_hi), half);
        if (dir > 0)
            DrawLanes(df, di, ups, hn::ConvertTo(df, xl), xl, hi, end, true, pa, pb, ca, cb, va, vb, da, db, out,
                      no_before);
        else
            DrawLanes(df, di, hn::MaskFromVec(ri(hn::VecFromMask(di, ups))), rf(hn::ConvertTo(df, xl)), ri(xl), ri(hi),
                      rf(end), true, rf(pa), rf(pb), ri(ca), ri(cb), rf(va), rf(vb), rf(da), rf(db), out, no_before);
    }
    const auto dns = hn::And(todo, hn::Lt(lo, excl_lo));
    if (!hn::AllFalse(di, dns)) {
        const VI xh = hn::Sub(excl_lo, ione);
        const VF end = hn::Sub(hn::ConvertTo(df, excl_lo), half);
        if (dir < 0)
            DrawLanes(df, di, dns, lof, lo, xh, end, true, pa, pb, ca, cb, va, vb, da, db, out, no_before);
        else
            DrawLanes(df, di, hn::MaskFromVec(ri(hn::VecFromMask(di, dns))), rf(lof), ri(lo), ri(xh), rf(end), true,
                      rf(pa), rf(pb), ri(ca), ri(cb), rf(va), rf(vb), rf(da), rf(db), out, no_before);
    }
    return true;
}

// warp_line_to of one row whose samples all take part (RowFoldsOver), with the painter's algorithm run backwards
// (the hand-written AVX-512 kernels' warp_line_reverse): the items (points, groups of spans one way, vectors of spans
// both ways, single spans, the seam) in the reverse of WarpRow's order, each drawing only the pixels no later item (in
// WarpRow's order) writes. A pixel's value does not depend on which other pixels are drawn, and WarpRow leaves every
// pixel with the value of the last item that writes it, the first one here to reach it: the same row. The pixels
// written so far are one interval [w_lo, w_hi]: every sample taking part, the spans form one connected path from the
// seam outwards and an item's pixels touch that interval. If one ever did not, this returns false (some pixels
// written) and the caller clears the row and warps it forwards.
// Why: on foldover-heavy reliefs most pixels of a row are written again later in the same row (ridges 1024^2: 2.43
// row pixels a texel); measured in docs/perf-history.md.
inline bool WarpRowBackward(const float* pos, const uint32_t* col, const float* attr, const float* attr2, int n,
                            int split, int n_out, RowOut out) {
    out.width = n_out;
    const ScalarRow scalar{pos, col, attr, attr2, out};
    const hn::ScalableTag<float> df;
    const int N = int(hn::Lanes(df));
    int w_lo = 0, w_hi = -1;
    // An item writing pixels [lo, hi] (empty when lo > hi) through shade(cl, ch), which writes exactly its pixels
    // in [cl, ch].
    auto item = [&](int lo, int hi, auto&& shade) -> bool {
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
        w_lo = std::min(w_lo, lo);
        w_hi = std::max(w_hi, hi);
        return true;
    };
    auto span = [&](int a, int b) -> bool {
        int lo, hi;
        SpanPixels(pos[a], pos[b], n_out, lo, hi);
        return item(lo, hi, [&](int cl, int ch) { DrawSpan(df, scalar, a, b, cl, ch); });
    };
    auto point = [&](int k) -> bool {
        int lo, hi;
        PointPixels(pos[k], n_out, lo, hi);
        return item(lo, hi, [&](int, int) { scalar.point(k, n_out); });
    };
    auto no_before = [](int, int) {};
    const hn::RebindToSigned<decltype(df)> di;
    auto lf = [&](const float* p) { return hn::LoadU(df, p); };
    auto li = [&](const uint32_t* p) { return hn::LoadU(di, reinterpret_cast<const int32_t*>(p)); };
    auto lf2 = [&](int k) { return attr2 ? hn::LoadU(df, attr2 + k) : hn::Zero(df); };
    if (split >= 1 && split < n && !span(split - 1, split)) return false;
    // The part after the split, from its last span (keyed split: samples split + 1 -> split) outwards, then its
    // first sample.
    if (split < n) {
        for (int j = split; j <= n - 2;) {
            if (j + N - 1 <= n - 2) {
                bool up;
                const int m = GroupPrefix(df, pos + j + 1, pos + j, true, up);  // spans j .. j + m - 1
                if (m) {
                    int lo, hi;
                    SpanPixels(pos[j + m], pos[j], n_out, lo, hi);
                    if (!item(lo, hi, [&](int cl, int ch) {
                            DrawGroup(df, pos, col, attr, attr2, j + 1, j, m, true, up, out, no_before, cl, ch);
                        }))
                        return false;
                    j += m;
                    continue;
                }
                // Spans j .. j + N - 1 (lane i: samples j + i + 1 -> j + i).
                if (!BackwardLanes(df, +1, lf(pos + j + 1), lf(pos + j), li(col + j + 1), li(col + j), lf(attr + j + 1),
                                   lf(attr + j), lf2(j + 1), lf2(j), n_out, out, w_lo, w_hi))
                    return false;
                j += N;
                continue;
            }
            if (!span(j + 1, j)) return false;
            ++j;
        }
        if (!point(n - 1)) return false;
    }
    // The part before the split, from its last span (keyed split - 1) outwards, then its first sample.
    if (split > 0) {
        for (int j = split - 1; j >= 1;) {
            if (j - N + 1 >= 1) {
                bool up;
                const int m = GroupPrefix(df, pos + j - N, pos + j - N + 1, false, up);  // spans j - m + 1 .. j
                if (m) {
                    int lo, hi;
                    SpanPixels(pos[j - m], pos[j], n_out, lo, hi);
                    if (!item(lo, hi, [&](int cl, int ch) {
                            DrawGroup(df, pos, col, attr, attr2, j - N, j - N + 1, m, false, up, out, no_before, cl,
                                      ch);
                        }))
                        return false;
                    j -= m;
                    continue;
                }
                // Spans j down to j - N + 1 (lane i: samples b + i - 1 -> b + i), in the order of the lanes down.
                const int b = j - N + 1;
                if (!BackwardLanes(df, -1, lf(pos + b - 1), lf(pos + b), li(col + b - 1), li(col + b), lf(attr + b - 1),
                                   lf(attr + b), lf2(b - 1), lf2(b), n_out, out, w_lo, w_hi))
                    return false;
                j -= N;
                continue;
            }
            if (!span(j - 1, j)) return false;
            --j;
        }
        if (!point(0)) return false;
    }
    return true;
}

#if HWY_TARGET == HWY_AVX3_DL
// AVX-512 VBMI: the tables looked up 64 texels at a time with byte permutes of FastTables' byte planes, not gathers
// (three 16-lane gathers a vector took most of the row set-up: bumps 256^2, about 3.5 cycles a texel). Each plane
// (256 bytes: byte b of a table at every level) is two two-register permutes and a blend by the level's high bit;
// the four planes of a table interleave into floats with unpacks, which work within 128-bit blocks, so the levels
// go in a permuted order qp (qp[16L + 4m + i] = q[16m + 4L + i]) that puts texels 16m .. 16m + 15 in vector m.
struct PlaneOrder {
    alignas(64) uint8_t from01[64] = {};  // byte index into texels 0 .. 31 (two registers) of each lane of qp
    alignas(64) uint8_t from23[64] = {};  // the same into texels 32 .. 63
    uint64_t use23 = 0;                   // lanes of qp taken from texels 32 .. 63
    constexpr PlaneOrder() {
        for (int j = 0; j < 64; ++j) {
            const int L = j / 16, m = (j / 4) % 4, i = j % 4;
            const int t = 16 * m + 4 * L + i;       // the texel of lane j
            from01[j] = uint8_t(4 * (t % 32) + 3);  // its byte 3: the level
            from23[j] = uint8_t(4 * (t % 32) + 3);
            if (t >= 32) use23 |= uint64_t(1) << j;
        }
    }
};
alignas(64) static constexpr PlaneOrder kPlaneOrder{};

// Byte q of a 256-byte table for the 64 levels qp (`high`: the levels >= 128).
HWY_INLINE __m512i LookupBytes(const uint8_t* table, __m512i qp, __mmask64 high) {
    const __m512i lo = _mm512_permutex2var_epi8(_mm512_load_si512(table), qp, _mm512_load_si512(table + 64));
    const __m512i hi = _mm512_permutex2var_epi8(_mm512_load_si512(table + 128), qp, _mm512_load_si512(table + 192));
    return _mm512_mask_blend_epi8(high, lo, hi);
}

// Table `planes` (four byte planes) at the levels qp, as floats of texels 16m .. 16m + 15 in out[m].
HWY_INLINE void LookupFloats(const uint8_t (*planes)[256], __m512i qp, __mmask64 high, __m512 out[4]) {
    const __m512i b0 = LookupBytes(planes[0], qp, high), b1 = LookupBytes(planes[1], qp, high);
    const __m512i b2 = LookupBytes(planes[2], qp, high), b3 = LookupBytes(planes[3], qp, high);
    const __m512i l01 = _mm512_unpacklo_epi8(b0, b1), h01 = _mm512_unpackhi_epi8(b0, b1);
    const __m512i l23 = _mm512_unpacklo_epi8(b2, b3), h23 = _mm512_unpackhi_epi8(b2, b3);
    out[0] = _mm512_castsi512_ps(_mm512_unpacklo_epi16(l01, l23));
    out[1] = _mm512_castsi512_ps(_mm512_unpackhi_epi16(l01, l23));
    out[2] = _mm512_castsi512_ps(_mm512_unpacklo_epi16(h01, h23));
    out[3] = _mm512_castsi512_ps(_mm512_unpackhi_epi16(h01, h23));
}

// PrepareRow's loop for texels x .. x + 63 of the row src (the same values, stored to s). Returns whether any of
// them is at zero displacement (an identity level).
HWY_INLINE bool PrepareTexels64(const fast::FastTables& ft, const uint32_t* src, int x, __m512 vs, __m512 ou, __m512 ov,
                                const RowScratch& s) {
    __m512i d[4];
    for (int m = 0; m < 4; ++m) {
        d[m] = _mm512_loadu_si512(src + x + 16 * m);
        _mm512_storeu_si512(s.color + x + 16 * m, _mm512_or_si512(d[m], _mm512_set1_epi32(int32_t(0xFF000000u))));
    }
    const __m512i qp = _mm512_mask_blend_epi8(
        kPlaneOrder.use23, _mm512_permutex2var_epi8(d[0], _mm512_load_si512(kPlaneOrder.from01), d[1]),
        _mm512_permutex2var_epi8(d[2], _mm512_load_si512(kPlaneOrder.from23), d[3]));
    const __mmask64 high = _mm512_movepi8_mask(qp);
    const __m512i iota = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
    __m512 us[4];
    for (int m = 0; m < 4; ++m)
        us[m] = _mm512_add_ps(_mm512_cvtepi32_ps(_mm512_add_epi32(_mm512_set1_epi32(x + 16 * m), iota)),
                              _mm512_set1_ps(0.5f));
    const uint64_t still = ft.any_identity ? _mm512_movepi8_mask(LookupBytes(ft.identity, qp, high)) : 0;
    if (still == ~0ull) {
        // Zero displacement at all 64 (PrepareRow says why no lookup is needed).
        for (int m = 0; m < 4; ++m) {
            _mm512_storeu_ps(s.pos + x + 16 * m, _mm512_add_ps(us[m], ou));
            _mm512_storeu_ps(s.v + x + 16 * m, _mm512_add_ps(vs, ov));
        }
        return true;
    }
    // Table by table, so that fewer registers are live at once.
    __m512 rcp[4], k[4];
    LookupFloats(ft.plane[2], qp, high, rcp);
    LookupFloats(ft.plane[0], qp, high, k);
    for (int m = 0; m < 4; ++m)
        _mm512_storeu_ps(s.pos + x + 16 * m, _mm512_add_ps(_mm512_mul_ps(_mm512_add_ps(us[m], k[m]), rcp[m]), ou));
    LookupFloats(ft.plane[1], qp, high, k);
    for (int m = 0; m < 4; ++m)
        _mm512_storeu_ps(s.v + x + 16 * m, _mm512_add_ps(_mm512_mul_ps(_mm512_add_ps(vs, k[m]), rcp[m]), ov));
    return still != 0;
}
#endif

// The reference's row_samples (lookup-table path) of storage row r into s: position (NaN where the texel does not
// take part, which WarpRow treats as the reference treats an invalid sample), final row coordinate and colour
// (alpha 255) of every texel. Returns the texels dropped (not empty, but 1 + k3*d <= 0). `ft` holds each level's K1
// (NaN at the levels that cannot be pre-warped: (u_s + NaN) * R + margin is NaN, not finite, as the reference's
// invalid sample), K2 and R (FastTables::level) and the identity levels (zero displacement: K1 = K2 = +-0, R = 1).
// Also says whether the row has a texel at zero displacement (one of the first run of identity levels, which holds
// every level at zero displacement of a monotonic quantizer): without one, no vector of its spans is a copy of still
// texels (CopyStill), and WarpRow need not test for them (RowOut::copy).
struct PreparedRow {
    long long dropped;
    bool still;
};
inline PreparedRow PrepareRow(const ReliefTexture& t, const fast::FastTables& ft, const PrewarpExtent& e, int r,
                              const RowScratch& s) {
    const int w = t.width, h = t.height;
    const float vs = float(h - 1 - r) + 0.5f;
    const ReliefTexel* src = &t.texels[size_t(r) * size_t(w)];
    const float ou = float(e.left), ov = float(e.bottom);
    long long dropped = 0;
    if (ft.any_dropped)
        for (int x = 0; x < w; ++x) dropped += ft.dropped[src[x].q];
    // A vector of texels at a time: the tables' entries gathered by displacement index, the same float operations.
    const hn::ScalableTag<float> df;
    const hn::RebindToSigned<decltype(df)> di;
    using VF = hn::Vec<decltype(df)>;
    using VI = hn::Vec<decltype(di)>;
    const int N = int(hn::Lanes(df));
    static_assert(sizeof(ReliefTexel) == 4 && offsetof(ReliefTexel, q) == 3, "texels are r, g, b, q bytes");
    const VF half = hn::Set(df, 0.5f), vou = hn::Set(df, ou), vov = hn::Set(df, ov);
    const VF vvs = hn::Set(df, vs);
    const VI byte = hn::Set(di, 0xFF), rgb = hn::Set(di, 0xFFFFFF), alpha = hn::Set(di, int32_t(0xFF000000u));
    const VI iota = hn::Iota(di, 0);
    // Texels at zero displacement (the brick wall's bricks, paper section 5): (u_s + +-0) * 1 + ou is u_s + ou
    // exactly (u_s >= 0.5, never zero), and v likewise: a vector of them needs no lookup (the hand-written AVX-512
    // row set-up's shortcut).
    const bool any_id = ft.identity_lo <= ft.identity_hi;
    const VI id_lo = hn::Set(di, ft.identity_lo), id_hi = hn::Set(di, ft.identity_hi);
    const VF still_v = hn::Add(vvs, vov);
    bool still = false;
    int x = 0;
#if HWY_TARGET == HWY_AVX3_DL
    for (; x + 64 <= w; x += 64)
        still = PrepareTexels64(ft, reinterpret_cast<const uint32_t*>(src), x, vvs.raw, vou.raw, vov.raw, s) || still;
#endif
    for (; x + N <= w; x += N) {
        const VI tx = hn::LoadU(di, reinterpret_cast<const int32_t*>(src + x));
        const VI q = hn::And(hn::ShiftRight<24>(tx), byte);
        hn::StoreU(hn::Or(hn::And(tx, rgb), alpha), di, reinterpret_cast<int32_t*>(s.color + x));
        const VF us = hn::Add(hn::ConvertTo(df, hn::Add(hn::Set(di, x), iota)), half);
        if (any_id) {
            const auto moving = hn::Or(hn::Lt(q, id_lo), hn::Gt(q, id_hi));
            if (hn::AllFalse(di, moving)) {
                hn::StoreU(hn::Add(us, vou), df, s.pos + x);
                hn::StoreU(still_v, df, s.v + x);
                still = true;
                continue;
            }
            still = still || !hn::AllTrue(di, moving);
        }
#if HWY_TARGET == HWY_AVX2
        // Each texel's (K1, K2, R) as one 16-byte load, texels i and i + 4 in one register, then a 4x4 transpose
        // within each 128-bit half: fewer operations than three 8-lane gathers.
        // The levels read from the texels' bytes (a byte load each), not extracted from q's lanes.
        const uint8_t* qb = &src[x].q;
        const float* lv = &ft.level[0][0];
        auto pair = [&](int i) {
            return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(lv + 4 * size_t(qb[4 * i]))),
                                        _mm_load_ps(lv + 4 * size_t(qb[4 * i + 16])), 1);
        };
        const __m256 r0 = pair(0), r1 = pair(1), r2 = pair(2), r3 = pair(3);
        const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
        const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
        const VF k1{_mm256_shuffle_ps(t0, t2, 0x44)}, k2{_mm256_shuffle_ps(t0, t2, 0xEE)};
        const VF rcp{_mm256_shuffle_ps(t1, t3, 0x44)};
#elif HWY_TARGET == HWY_SSE4 || HWY_TARGET == HWY_NEON
        // The same with 4 lanes: each texel's (K1, K2, R) as one 16-byte load, and a 4x4 transpose; fewer operations
        // than three emulated 4-lane gathers (12 single loads and their inserts).
        const uint8_t* qb = &src[x].q;  // the levels from the texels' bytes, as on AVX2
        const float* lv = &ft.level[0][0];
        const VF r0 = hn::Load(df, lv + 4 * size_t(qb[0])), r1 = hn::Load(df, lv + 4 * size_t(qb[4]));
        const VF r2 = hn::Load(df, lv + 4 * size_t(qb[8])), r3 = hn::Load(df, lv + 4 * size_t(qb[12]));
        const VF t01 = hn::InterleaveLower(df, r0, r1), t23 = hn::InterleaveLower(df, r2, r3);  // K1 K1 K2 K2
        const VF u01 = hn::InterleaveUpper(df, r0, r1), u23 = hn::InterleaveUpper(df, r2, r3);  // R R - -
        const VF k1 = hn::ConcatLowerLower(df, t23, t01), k2 = hn::ConcatUpperUpper(df, t23, t01);
        const VF rcp = hn::ConcatLowerLower(df, u23, u01);
#else
        const VI q4 = hn::ShiftLeft<2>(q);  // four floats a level
        const VF k1 = hn::GatherIndex(df, &ft.level[0][0], q4), k2 = hn::GatherIndex(df, &ft.level[0][1], q4);
        const VF rcp = hn::GatherIndex(df, &ft.level[0][2], q4);
#endif
        hn::StoreU(hn::Add(hn::Mul(hn::Add(us, k1), rcp), vou), df, s.pos + x);
        hn::StoreU(hn::Add(hn::Mul(hn::Add(vvs, k2), rcp), vov), df, s.v + x);
    }
    for (; x < w; ++x) {
        const ReliefTexel tx = src[x];
        const float us = float(x) + 0.5f;
        s.color[size_t(x)] = pack({tx.r, tx.g, tx.b, 255});
        const float* lv = ft.level[tx.q];
        s.pos[size_t(x)] = (us + lv[0]) * lv[2] + ou;  // NaN where the level cannot be pre-warped
        s.v[size_t(x)] = (vs + lv[1]) * lv[2] + ov;
        still = still || (tx.q >= ft.identity_lo && tx.q <= ft.identity_hi);
    }
    return {dropped, still};
}

// The marks of storage row r (ReliefTexture::breaks, `breaks` being the relief's or null), or null where none of them
// breaks a pair of neighbours (kBreakRight on texels 0 .. w - 2): WarpRow's `marks`.
inline const uint8_t* RowMarks(const ReliefTexture& t, const uint8_t* breaks, int r) {
    if (!breaks) return nullptr;
    const uint8_t* row = breaks + size_t(r) * size_t(t.width);
    for (int x = 0; x + 1 < t.width; ++x)
        if (row[x] & kBreakRight) return row;
    return nullptr;
}

// Each texel's displacement along storage row r into s.d (the reference's RowAttr::d: its tables' displ by
// displacement index), the second attribute the rows carry for a discontinuity threshold.
inline void RowDisplacements(const ReliefTexture& t, const PrewarpTables& tab, int r, const RowScratch& s) {
    const ReliefTexel* src = &t.texels[size_t(r) * size_t(t.width)];
    for (int x = 0; x < t.width; ++x) s.d[x] = tab.displ[src[x].q];
}

// The state of the output columns: each column's last sample (final row coordinate v, NaN where the column has none,
// and packed colour c); with a discontinuity threshold (ColumnStep<true>) also its carried displacement d. Arrays of
// the output width, readable a whole vector past it. Eight bytes a column (twelve with d): at 4096^2 the state of a
// step's 4,100 columns fits in a 48 KiB L1 cache, where an int32 "has a sample" flag and the kept floor and ceiling
// of v - 0.5 (20 bytes a column, until session 33) did not: bumps 4096^2 two-pass, `avx512`, one thread, medians of
// 4 interleaved runs 95.6 -> 91.2 ms, ridges 92 -> 85 ms (docs/perf-history.md, "Long runs of spans and the column
// state").
struct Columns {
    float* v;
    uint32_t* c;
    float* d = nullptr;
};

// Floor and ceiling of min(max(a - 0.5, -1), oh) (oh: the image's height, a float), converted to int32, in the lanes
// where a is finite (the others get anything).
template <class DF, class DI>
HWY_INLINE void FloorCeil(DF df, DI di, hn::Vec<DF> a, hn::Vec<DF> oh, hn::Vec<DI>& f, hn::Vec<DI>& e) {
    const hn::Vec<DF> cl = hn::Min(hn::Max(hn::Sub(a, hn::Set(df, 0.5f)), hn::Set(df, -1.0f)), oh);
#if HWY_TARGET <= HWY_AVX3
    // Rounded and converted by one instruction each.
    (void)di;
    f = hn::Vec<DI>{_mm512_cvt_roundps_epi32(cl.raw, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)};
    e = hn::Vec<DI>{_mm512_cvt_roundps_epi32(cl.raw, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC)};
#elif HWY_TARGET == HWY_NEON
    // The same on NEON: FCVTMS and FCVTPS (where Floor and Ceil take FRINTM/FRINTP, then FCVTZS; SVE converts by
    // truncation only).
    (void)di;
    f = hn::Vec<DI>{vcvtmq_s32_f32(cl.raw)};
    e = hn::Vec<DI>{vcvtpq_s32_f32(cl.raw)};
#else
    f = ConvertInRange(di, hn::Floor(cl));
    e = ConvertInRange(di, hn::Ceil(cl));
#endif
}

// ColumnStep's columns x .. x + N - 1: with kFull all of them the caller's (x + N <= x1), loaded whole with no lane
// mask (each masked load cost a mask built from x1 - x and a load that cannot be an operand: `avx2` bumps 256^2
// two-pass, instructions counted under qemu, 5.6% fewer in the vertical pass, 2.4% in the pre-warp); else the lanes
// below x1, loaded masked.
template <bool kFull, bool kThreshold>
HWY_INLINE void ColumnVector(const Columns& col, const ColumnTarget& o, const uint32_t* rc, const float* rv, int x,
                             int x1, const float* rd, float threshold) {
    const hn::ScalableTag<float> df;
    const hn::RebindToSigned<decltype(df)> di;
    using VF = hn::Vec<decltype(df)>;
    using VI = hn::Vec<decltype(di)>;
    const VI alpha = hn::Set(di, int32_t(0xFF000000u)), izero = hn::Zero(di), ione = hn::Set(di, 1);
    const VI last = hn::Set(di, o.oh - 1);
    const VF hi_clamp = hn::Set(df, float(o.oh));
    const auto m = hn::FirstN(df, size_t(x1 - x));  // all lanes where kFull (not used there)
    const auto mi = hn::RebindMask(di, m);
    auto loadf = [&](const float* p) HWY_ATTR __attribute__((always_inline)) {
        if constexpr (kFull)
            return hn::LoadU(df, p);
        else
            return hn::MaskedLoad(m, df, p);
    };
    auto loadi = [&](const uint32_t* p) HWY_ATTR __attribute__((always_inline)) {
        if constexpr (kFull)
            return hn::LoadU(di, reinterpret_cast<const int32_t*>(p));
        else
            return hn::MaskedLoad(mi, di, reinterpret_cast<const int32_t*>(p));
    };
    const VF v = loadf(rv + x);
    const VI c = loadi(rc + x);
    auto fin = hn::And(hn::Ne(hn::And(c, alpha), izero), hn::RebindMask(di, hn::IsFinite(v)));
    if constexpr (!kFull) fin = hn::And(mi, fin);
    // The column's last sample (NaN where it has none), replaced by the new one (NaN where there is none).
    const VF pv = loadf(col.v + x);
    const auto finf = hn::RebindMask(df, fin);
    const VF vnext = hn::IfThenElse(finf, v, hn::Set(df, std::numeric_limits<float>::quiet_NaN()));
    if constexpr (kFull)
        hn::StoreU(vnext, df, col.v + x);
    else
        hn::BlendedStore(vnext, m, df, col.v + x);
    if (hn::AllFalse(di, fin)) return;
    auto pok = hn::And(fin, hn::RebindMask(di, hn::Not(hn::IsNaN(pv))));
    // The columns' other state: where the vector is all the caller's (kFull), whole-vector stores of the new values
    // blended with the old ones just loaded (no masked store, which costs more on AVX2: StoreOwned), else masked
    // stores of the caller's lanes.
    auto keep = [&](auto d, auto vnew, auto vold, auto* p) HWY_ATTR __attribute__((always_inline)) {
        const auto f = hn::RebindMask(d, fin);
        if constexpr (kFull)
            hn::StoreU(hn::IfThenElse(f, vnew, vold), d, p);
        else
            hn::BlendedStore(vnew, f, d, p);
    };
    if constexpr (kThreshold) {
        const VF d = loadf(rd + x), pd = loadf(col.d + x);
        pok = hn::And(pok, hn::RebindMask(di, WithinThreshold(df, pd, d, threshold)));
        keep(df, d, pd, col.d + x);
    }
    const VI pc = loadi(col.c + x);
    // (v and pv are finite in the lanes where f, e, pf and pe are used: fin and pok.)
    VI f, e, pf, pe;
    FloorCeil(df, di, v, hi_clamp, f, e);
    FloorCeil(df, di, pv, hi_clamp, pf, pe);
    keep(di, c, pc, reinterpret_cast<int32_t*>(col.c + x));
    const auto pokf = hn::RebindMask(df, pok);
    const auto inc = hn::RebindMask(di, hn::And(pokf, hn::Gt(v, pv)));
    const auto dec = hn::RebindMask(di, hn::And(pokf, hn::Lt(v, pv)));
    VI ylo = hn::Max(hn::IfThenElse(inc, hn::Add(pf, ione), e), izero);
    VI yhi = hn::Min(hn::IfThenElse(inc, f, hn::Sub(pe, ione)), last);
    const auto span = hn::AndNot(hn::Gt(ylo, yhi), hn::Or(inc, dec));
    const VF inv = hn::Div(hn::Set(df, 1.0f), hn::Sub(v, pv));
    const auto point = hn::AndNot(pok, fin);
    if (!hn::AllFalse(di, point)) [[unlikely]] {
        // A column that had no sample starts a run: raster_point(v, c), row int(v) where 0 <= v < oh.
        const auto pin = hn::And(point, hn::RebindMask(di, hn::And(hn::Ge(v, hn::Zero(df)), hn::Lt(v, hi_clamp))));
        const VI vi = ConvertInRange(di, v);  // used in the lanes of pin alone
        ylo = hn::IfThenElse(pin, vi, ylo);
        yhi = hn::IfThenElse(pin, vi, yhi);
        const auto todo = hn::Or(span, pin);
        if (!hn::AllFalse(di, todo)) ColumnPixels(df, o, x, kFull, todo, span, pin, ylo, yhi, pv, inv, pc, v, c);
        return;
    }
    if (!hn::AllFalse(di, span))
        ColumnPixels(df, o, x, kFull, span, span, hn::FirstN(di, 0), ylo, yhi, pv, inv, pc, v, c);
}

// The column step of one row of pixels rc (packed colour, alpha 0 where not written) and rv (final row
// coordinate) for columns [x0, x1): in every column whose pixel was written with a finite row coordinate, the span
// from the column's last sample to it (raster_span) or, where the column had none, the point (raster_point), only
// their pixels in v-rows [0, oh); the column keeps it as its last sample, and the others lose theirs.
// rc and rv are read a whole vector past x1.
//
// raster_span's rows floor(pv - 0.5) + 1 .. floor(v - 0.5) (v > pv) or ceil(v - 0.5) .. ceil(pv - 0.5) - 1 (v < pv),
// clamped to [0, oh - 1], in integers from floor and ceil of pv - 0.5 and v - 0.5 clamped to [-1, oh] (which
// commutes with floor and ceil and changes no row in [0, oh - 1]), both computed at each step (FloorCeil: four
// operations on AVX-512, where keeping the previous sample's with it cost two loads and two stores).
//
// With kThreshold (the relief's discontinuity threshold, paper section 4.1.1) the row also brings each pixel's
// carried displacement rd, and a column joins its last sample to the new one only where |d_last - d| <= threshold
// (the reference's DisplConnected, operation by operation: the sign bit of the difference cleared); elsewhere the
// new sample starts a run (a point).
template <bool kThreshold = false>
HWY_INLINE void ColumnStep(const Columns& col, const ColumnTarget& o, const uint32_t* rc, const float* rv, int x0,
                           int x1, const float* rd = nullptr, float threshold = 0.0f) {
    const int N = int(hn::Lanes(hn::ScalableTag<float>()));
    int x = x0;
    for (; x + N <= x1; x += N) ColumnVector<true, kThreshold>(col, o, rc, rv, x, x1, rd, threshold);
    if (x < x1) ColumnVector<false, kThreshold>(col, o, rc, rv, x, x1, rd, threshold);
}

}  // namespace rtm::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // RTM_WARP_SIMD_HWY_ROW_INL_H_
