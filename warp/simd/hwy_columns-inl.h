// The vertical work of the Highway kernels (warp/simd/hwy_two_pass.cpp, warp/simd/hwy_pipelined.cpp), compiled once
// per target (Highway's -inl.h convention, included from warp/simd/hwy_row-inl.h): N adjacent output columns in the
// lanes of one vector, each lane computing what raster_span / raster_point (warp/line_warp.h, the naive reference)
// computes for its column, operation by operation in float (no contraction), the colour with lerp8's integer formula.
//
// Where the pixels go (the structure of the hand-written AVX-512 kernels these replaced, docs/perf-history.md, over
// Highway 1.0.3, which has no masked scatter):
// - short spans and points (at most 4 pixels a lane): the first pixel of every lane, then the second of those that
//   have one, ...; each step writes its lanes with two masked row stores (StoreOwned) when they all lie on the
//   first active lane's row or the next (neighbouring columns mostly do), lane by lane otherwise;
// - long spans (5 pixels or more, common where rows fold over) go row by row over the rows they share, one masked
//   store a row for all of them; lanes far apart from the others go alone through raster_span_pixels.
// Masked stores are used only where the whole vector lies in the caller's columns [x0, x1) (`full`): on SSE4 and
// NEON, and on AVX2 where its masked store is slow, they load, blend and store the whole vector (StoreOwned), which
// must not touch another task's columns or run past the end of a row. Elsewhere (the last vector of a task) every pixel
// is written lane by lane.
#if defined(RTM_WARP_SIMD_HWY_COLUMNS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RTM_WARP_SIMD_HWY_COLUMNS_INL_H_
#undef RTM_WARP_SIMD_HWY_COLUMNS_INL_H_
#else
#define RTM_WARP_SIMD_HWY_COLUMNS_INL_H_
#endif

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "warp/image.h"
#include "warp/line_warp.h"

HWY_BEFORE_NAMESPACE();
namespace rtm::simd::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Where a column step draws: an image ow x oh (v-row y in storage row oh - 1 - y), only v-rows [y0, y1).
struct ColumnTarget {
    uint32_t* pixels;
    int ow, oh, y0, y1;
    bool blend = false;  // StoreOwned's load, blend and store on AVX2 (the job's blend_stores)
    int ahead = 0;       // StoreRows prefetches v-row y + ahead where it writes row y (0: none; OutputAhead)
    uint32_t* vline(int y) const { return pixels + size_t(oh - 1 - y) * size_t(ow); }
};

// ColumnTarget::ahead for a pass whose v-rows move in direction `dir` (+1 upwards, -1 downwards): kOutputAhead rows
// ahead where the stores read what they overwrite (`blend`: AVX2's load, blend and store, StoreOwned), else none. A
// load of a row the pass reaches for the first time waits for memory: on a Zen 4 guest, 43% of the `avx2` two-pass
// vertical pass's samples fell on the blends after StoreRows' two row loads (bumps 1024^2, one thread). With the rows 8
// ahead prefetched (medians of 11 interleaved runs of 60 pre-warps, one thread): bumps 1024^2 two-pass 7.39 -> 6.61 ms,
// pipelined 7.85 -> 7.13, ridges two-pass 8.38 -> 7.29, bumps 2048^2 two-pass 43.5 -> 32.8, ridges pipelined (mostly
// reverse mode, whose rows go the other way) 14.3 -> 13.8; bricks, 256^2 and two threads within the noise; 2 to 16
// rows ahead alike. Where the stores do not read (masked stores: AVX-512, and AVX2 on Intel's cores and Zen 5; the
// hand-written AVX-512 kernels prefetched 8 rows ahead) the same prefetch measured within the noise on Zen 5
// (docs/perf-history.md, "The band rows prefetched" and "A Zen 4 guest").
constexpr int kOutputAhead = 8;
inline int OutputAhead(bool blend, int dir) { return blend ? dir * kOutputAhead : 0; }

// Spans longer than this many pixels (yhi - ylo >= kLongSpan) go row by row over the lanes (ColumnLongSpans).
constexpr int kLongSpan = 4;

// x86's vector targets (not Highway's one-lane scalar fallback), and ARM's.
#undef RTM_HWY_X86_VECTORS
#if HWY_ARCH_X86 && HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128
#define RTM_HWY_X86_VECTORS 1
#else
#define RTM_HWY_X86_VECTORS 0
#endif
#undef RTM_HWY_ARM_VECTORS
#if HWY_TARGET == HWY_NEON || HWY_TARGET == HWY_SVE || HWY_TARGET == HWY_SVE2 || HWY_TARGET == HWY_SVE_256 || \
    HWY_TARGET == HWY_SVE2_128
#define RTM_HWY_ARM_VECTORS 1
#else
#define RTM_HWY_ARM_VECTORS 0
#endif

#if RTM_HWY_X86_VECTORS
// The truncating conversion of floats known to lie in [-0, 2^31): the instruction alone, without ConvertTo's fix-up
// for values it cannot represent (three operations a vector).
template <size_t N>
HWY_INLINE hn::Vec128<int32_t, N> TruncateInRange(hn::Simd<int32_t, N, 0>, hn::Vec128<float, N> v) {
    return hn::Vec128<int32_t, N>{_mm_cvttps_epi32(v.raw)};
}
#if HWY_TARGET <= HWY_AVX2
HWY_INLINE hn::Vec256<int32_t> TruncateInRange(hn::Full256<int32_t>, hn::Vec256<float> v) {
    return hn::Vec256<int32_t>{_mm256_cvttps_epi32(v.raw)};
}
#endif
#if HWY_TARGET <= HWY_AVX3
HWY_INLINE hn::Vec512<int32_t> TruncateInRange(hn::Full512<int32_t>, hn::Vec512<float> v) {
    return hn::Vec512<int32_t>{_mm512_cvttps_epi32(v.raw)};
}
#endif
#endif

// The truncating conversion of floats that lie in [-2^31, 2^31) in the lanes whose result is used (the others get
// anything): on x86 the instruction alone (TruncateInRange), elsewhere ConvertTo (one instruction there too).
template <class DI, class VF>
HWY_INLINE hn::Vec<DI> ConvertInRange(DI di, VF v) {
#if RTM_HWY_X86_VECTORS
    return TruncateInRange(di, v);
#else
    return hn::ConvertTo(di, v);
#endif
}

// lerp8's weight at parameters tt in [0, 1] or NaN (per lane): floor(t * 2^14) made odd, at most 2^14 - 1, and
// 2^14 - 1 for NaN: min(int(t * 2^14) | 1, 16383) where t >= 0, else 16383.
template <class DF, class DI>
HWY_INLINE hn::Vec<DI> Lerp8Weight(DF df, DI di, hn::Vec<DF> tt) {
#if RTM_HWY_X86_VECTORS
    // x86's minimum returns its second operand where the first is NaN (Highway's Min is minps(a, b) there), so
    // min(t * 2^14, 16383) is 16383 for NaN as for t * 2^14 >= 16383, and int(min(x, 16383)) | 1 equals
    // min(int(x) | 1, 16383) for every x in [-0, 16384]: int(x) | 1 <= 16383 where x < 16383. Four operations where
    // the portable formula below takes nine (bumps 1024^2 AVX2 two-pass: 17% of the row warp).
    const auto x = hn::Min(hn::Mul(tt, hn::Set(df, 16384.0f)), hn::Set(df, 16383.0f));
    return hn::Or(TruncateInRange(di, x), hn::Set(di, 1));
#else
    const hn::Vec<DI> w_max = hn::Set(di, 16383);
    const hn::Vec<DI> wt = hn::Min(hn::Or(hn::ConvertTo(di, hn::Mul(tt, hn::Set(df, 16384.0f))), hn::Set(di, 1)),
                                   w_max);
    return hn::IfThenElse(hn::RebindMask(di, hn::Ge(tt, hn::Zero(df))), wt, w_max);
#endif
}

// (a * (2^14 - w) + b * w + 2^13) >> 14 for channel `kShift` (a byte) of packed colours ca and cb.
template <int kShift, class DI>
HWY_INLINE hn::Vec<DI> Lerp8Channel(DI di, hn::Vec<DI> ca, hn::Vec<DI> cb, hn::Vec<DI> wt) {
    const hn::Vec<DI> byte = hn::Set(di, 0xFF);
    const hn::Vec<DI> a = hn::And(hn::ShiftRight<kShift>(ca), byte);
    const hn::Vec<DI> b = hn::And(hn::ShiftRight<kShift>(cb), byte);
    // a * (2^14 - w) + b * w == (a << 14) + (b - a) * w, exactly (below 2^23): one multiplication, not two.
    return hn::ShiftRight<14>(hn::Add(hn::Add(hn::ShiftLeft<14>(a), hn::Mul(hn::Sub(b, a), wt)), hn::Set(di, 8192)));
}

#if RTM_HWY_X86_VECTORS
// x86: lerp8's channels in 16-bit lanes. Each channel is (a (2^14 - w) + b w + 2^13) >> 14 = a + (((b - a) w + 2^13)
// >> 14) (a << 14 is a multiple of 2^14, and an arithmetic shift is a floor), and with x = b - a in [-255, 255] and
// y = 2w in [2, 32766] (both 16 bits), ((b - a) w + 2^13) >> 14 = (x y + 2^14) >> 15, which pmulhrsw computes
// exactly ((x y >> 14) + 1) >> 1 = floor((x y + 2^14) / 2^15)). The colours' bytes widened to 16 bits (4 pixels a
// 128-bit block in two halves), each pixel's weight in its 4 words, one subtraction, multiplication and addition a
// half, and the bytes packed back (packus: the sums are in [0, 255]): 14 operations where the 32-bit multiply-adds
// of each channel took 23 (bumps 1024^2 two-pass: lerp8 is about 40% of the row warp and of the vertical pass).
// The fourth byte is lerp8 of the fourth bytes, alpha 255 wherever the result is used: every colour the kernels carry
// has alpha 255 (PrepareRow, CopyStill, the still copies and the scalar paths set it; a pixel not written, alpha 0, is
// never a span's end), and lerp8 of 255 and 255 is 255. No OR with alpha, whose constant GCC 12 rebuilt at every use in
// the loops (`avx2` bumps 256^2, instructions counted under qemu: 0.5% fewer two-pass, 1.0% pipelined).
alignas(16) static constexpr uint8_t kWeightWords[2][16] = {{0, 1, 0, 1, 0, 1, 0, 1, 4, 5, 4, 5, 4, 5, 4, 5},
                                                            {8, 9, 8, 9, 8, 9, 8, 9, 12, 13, 12, 13, 12, 13, 12, 13}};
HWY_INLINE hn::Vec128<int32_t> Lerp8Channels16(hn::Vec128<int32_t> ca, hn::Vec128<int32_t> cb, hn::Vec128<int32_t> wt) {
    const __m128i zero = _mm_setzero_si128(), w2 = _mm_add_epi32(wt.raw, wt.raw);
    const __m128i wlo = _mm_shuffle_epi8(w2, _mm_load_si128(reinterpret_cast<const __m128i*>(kWeightWords[0])));
    const __m128i whi = _mm_shuffle_epi8(w2, _mm_load_si128(reinterpret_cast<const __m128i*>(kWeightWords[1])));
    const __m128i alo = _mm_unpacklo_epi8(ca.raw, zero), ahi = _mm_unpackhi_epi8(ca.raw, zero);
    const __m128i blo = _mm_unpacklo_epi8(cb.raw, zero), bhi = _mm_unpackhi_epi8(cb.raw, zero);
    const __m128i rlo = _mm_add_epi16(alo, _mm_mulhrs_epi16(_mm_sub_epi16(blo, alo), wlo));
    const __m128i rhi = _mm_add_epi16(ahi, _mm_mulhrs_epi16(_mm_sub_epi16(bhi, ahi), whi));
    return hn::Vec128<int32_t>{_mm_packus_epi16(rlo, rhi)};
}
#if HWY_TARGET <= HWY_AVX2
// kWeightWords twice, for both 128-bit blocks: an operand of the shuffle where a 16-byte load broadcast took a load
// and an insert, which GCC 12 redid (and spilled) at every use in the row warp's and the column steps' loops (`avx2`
// bumps 256^2 two-pass, instructions counted under qemu: 3.9% fewer in the pre-warp).
alignas(32) static constexpr uint8_t kWeightWords256[2][32] = {
    {0, 1, 0, 1, 0, 1, 0, 1, 4, 5, 4, 5, 4, 5, 4, 5, 0, 1, 0, 1, 0, 1, 0, 1, 4, 5, 4, 5, 4, 5, 4, 5},
    {8, 9, 8, 9, 8, 9, 8, 9, 12, 13, 12, 13, 12, 13, 12, 13, 8, 9, 8, 9, 8, 9, 8, 9, 12, 13, 12, 13, 12, 13, 12, 13}};
HWY_INLINE hn::Vec256<int32_t> Lerp8Channels16(hn::Vec256<int32_t> ca, hn::Vec256<int32_t> cb, hn::Vec256<int32_t> wt) {
    // The same per 128-bit block (the unpacks, byte shuffles and packs of AVX2 stay within blocks).
    const __m256i zero = _mm256_setzero_si256(), w2 = _mm256_add_epi32(wt.raw, wt.raw);
    const __m256i wlo = _mm256_shuffle_epi8(w2,
                                            _mm256_load_si256(reinterpret_cast<const __m256i*>(kWeightWords256[0])));
    const __m256i whi = _mm256_shuffle_epi8(w2,
                                            _mm256_load_si256(reinterpret_cast<const __m256i*>(kWeightWords256[1])));
    const __m256i alo = _mm256_unpacklo_epi8(ca.raw, zero), ahi = _mm256_unpackhi_epi8(ca.raw, zero);
    const __m256i blo = _mm256_unpacklo_epi8(cb.raw, zero), bhi = _mm256_unpackhi_epi8(cb.raw, zero);
    const __m256i rlo = _mm256_add_epi16(alo, _mm256_mulhrs_epi16(_mm256_sub_epi16(blo, alo), wlo));
    const __m256i rhi = _mm256_add_epi16(ahi, _mm256_mulhrs_epi16(_mm256_sub_epi16(bhi, ahi), whi));
    return hn::Vec256<int32_t>{_mm256_packus_epi16(rlo, rhi)};
}
#endif
#if HWY_TARGET <= HWY_AVX3_DL
// AVX-512 VBMI/VNNI: each channel a (2^14 - w) + b w + 2^13 as one dot product of the 16-bit pair (a, b) with
// (2^14 - w, w), accumulated onto 2^13 (vpdpwssd); the pairs made by byte permutes of the two colours (invariant
// along a column's pixels: the compiler keeps them out of the loops), bits 14..21 of the sums packed by bit-field
// selects (vpmultishiftqb), the blue sum carrying 0xFF << 22 into the alpha byte (the sums stay below 2^22).
struct PairIndices512 {
    alignas(64) uint8_t idx[3][64] = {};
    constexpr PairIndices512() {
        for (int c = 0; c < 3; ++c)
            for (int j = 0; j < 64; j += 4) {
                idx[c][j] = uint8_t(j + c);           // a (the first table of the two-register permute)
                idx[c][j + 2] = uint8_t(64 + j + c);  // b
            }
    }
};
alignas(64) static constexpr PairIndices512 kPairs512{};
// acc + a.x * b.x + a.y * b.y in each 32-bit lane of 16-bit pairs x, y (vpdpwssd). In assembly: Highway 1.0.3's
// AVX3_DL target enables avxvnni, not avx512vnni, so the intrinsic does not compile there (the CPU has it:
// isa_supported checks avx512vnni).
HWY_INLINE __m512i DotPairs(__m512i acc, __m512i a, __m512i b) {
    asm("vpdpwssd %2, %1, %0" : "+v"(acc) : "v"(a), "v"(b));
    return acc;
}
HWY_INLINE hn::Vec512<int32_t> Lerp8Channels16(hn::Vec512<int32_t> ca, hn::Vec512<int32_t> cb, hn::Vec512<int32_t> wt) {
    const __mmask64 even16 = 0x5555555555555555ull;
    const __m512i pr = _mm512_maskz_permutex2var_epi8(even16, ca.raw, _mm512_load_si512(kPairs512.idx[0]), cb.raw);
    const __m512i pg = _mm512_maskz_permutex2var_epi8(even16, ca.raw, _mm512_load_si512(kPairs512.idx[1]), cb.raw);
    const __m512i pb = _mm512_maskz_permutex2var_epi8(even16, ca.raw, _mm512_load_si512(kPairs512.idx[2]), cb.raw);
    // (2^14 - w, w) as one 32-bit value: w (2^16 - 1) + 2^14 (2^14 - w > 0: no borrow into w's half).
    const __m512i ww = _mm512_add_epi32(_mm512_mullo_epi32(wt.raw, _mm512_set1_epi32(0xFFFF)),
                                        _mm512_set1_epi32(0x4000));
    const __m512i r = DotPairs(_mm512_set1_epi32(8192), pr, ww);
    const __m512i g = DotPairs(_mm512_set1_epi32(8192), pg, ww);
    const __m512i b = DotPairs(_mm512_set1_epi32(8192 | (0xFF << 22)), pb, ww);
    const __m512i sel = _mm512_set1_epi64(0x362E2E2E160E0E0Eull);  // bit offsets 14, 14, 14, 22, 46, 46, 46, 54
    const __m512i rr = _mm512_maskz_multishift_epi64_epi8(0x1111111111111111ull, sel, r);
    const __m512i rg = _mm512_mask_multishift_epi64_epi8(rr, 0x2222222222222222ull, sel, g);
    return hn::Vec512<int32_t>{_mm512_mask_multishift_epi64_epi8(rg, 0xCCCCCCCCCCCCCCCCull, sel, b)};
}
#elif HWY_TARGET <= HWY_AVX3
// AVX-512 without VBMI/VNNI (the avx3 target): the 16-bit products above, per 128-bit block (AVX-512 BW).
HWY_INLINE hn::Vec512<int32_t> Lerp8Channels16(hn::Vec512<int32_t> ca, hn::Vec512<int32_t> cb, hn::Vec512<int32_t> wt) {
    const __m512i zero = _mm512_setzero_si512(), w2 = _mm512_add_epi32(wt.raw, wt.raw);
    const __m512i wlo = _mm512_shuffle_epi8(
        w2, _mm512_broadcast_i32x4(_mm_load_si128(reinterpret_cast<const __m128i*>(kWeightWords[0]))));
    const __m512i whi = _mm512_shuffle_epi8(
        w2, _mm512_broadcast_i32x4(_mm_load_si128(reinterpret_cast<const __m128i*>(kWeightWords[1]))));
    const __m512i alo = _mm512_unpacklo_epi8(ca.raw, zero), ahi = _mm512_unpackhi_epi8(ca.raw, zero);
    const __m512i blo = _mm512_unpacklo_epi8(cb.raw, zero), bhi = _mm512_unpackhi_epi8(cb.raw, zero);
    const __m512i rlo = _mm512_add_epi16(alo, _mm512_mulhrs_epi16(_mm512_sub_epi16(blo, alo), wlo));
    const __m512i rhi = _mm512_add_epi16(ahi, _mm512_mulhrs_epi16(_mm512_sub_epi16(bhi, ahi), whi));
    return hn::Vec512<int32_t>{_mm512_or_si512(_mm512_packus_epi16(rlo, rhi), _mm512_set1_epi32(int32_t(0xFF000000u)))};
}
#endif
// The channels' lerp with the common signature (DI first).
template <class DI>
HWY_INLINE hn::Vec<DI> Lerp8Channels16(DI, hn::Vec<DI> ca, hn::Vec<DI> cb, hn::Vec<DI> wt) {
    return Lerp8Channels16(ca, cb, wt);
}
#elif RTM_HWY_ARM_VECTORS
// ARM's NEON and SVE: the same 16-bit products with Highway's MulFixedPoint15 (SQRDMULH there:
// saturate((2 x y + 2^15) >> 16), which is (x y + 2^14) >> 15 for these operands, as pmulhrsw): each pixel's even
// bytes (red, blue) and odd bytes (green, alpha) as 16-bit lanes, its weight 2w in both words of its lane; 16
// operations where the 32-bit multiply-adds of each channel (Lerp8Channel) took about 30. Instructions a pre-warp
// counted under qemu, 256^2 (docs/perf-history.md, "lerp8 in 16-bit lanes on ARM"): `neon` 5% to 10% fewer, `sve`
// 4% to 8%.
template <class DI>
HWY_INLINE hn::Vec<DI> Lerp8Channels16(DI di, hn::Vec<DI> ca, hn::Vec<DI> cb, hn::Vec<DI> wt) {
    const hn::Repartition<uint16_t, DI> du16;
    const hn::Repartition<int16_t, DI> d16;
    const hn::Vec<DI> w2 = hn::Add(wt, wt);
    const auto ww = hn::BitCast(d16, hn::Or(w2, hn::ShiftLeft<16>(w2)));
    const auto byte = hn::Set(du16, uint16_t(0xFF));
    const auto ua = hn::BitCast(du16, ca), ub = hn::BitCast(du16, cb);
    const auto ae = hn::BitCast(d16, hn::And(ua, byte)), be = hn::BitCast(d16, hn::And(ub, byte));
    const auto ao = hn::BitCast(d16, hn::ShiftRight<8>(ua)), bo = hn::BitCast(d16, hn::ShiftRight<8>(ub));
    const auto re = hn::Add(ae, hn::MulFixedPoint15(hn::Sub(be, ae), ww));
    const auto ro = hn::Add(ao, hn::MulFixedPoint15(hn::Sub(bo, ao), ww));
    const auto packed = hn::Or(hn::BitCast(du16, re), hn::ShiftLeft<8>(hn::BitCast(du16, ro)));
    return hn::Or(hn::BitCast(di, packed), hn::Set(di, int32_t(0xFF000000u)));
}
#endif

// std::clamp(t, 0, 1) per lane, as raster_span_pixels clamps its t: below 0 gives 0, above 1 gives 1, anything else
// (NaN included) stays.
template <class V>
HWY_INLINE V Clamp01(V tt) {
    const V zero = hn::Zero(hn::DFromV<V>()), one = hn::Set(hn::DFromV<V>(), 1.0f);
    return hn::IfThenElse(hn::Lt(tt, zero), zero, hn::IfThenElse(hn::Lt(one, tt), one, tt));
}

// lerp8 of packed colours ca -> cb at parameters tt in [0, 1] or NaN (per lane): the weight of Lerp8Weight, each
// channel (a * (2^14 - w) + b * w + 2^13) >> 14, alpha 255.
template <class DF, class DI>
HWY_INLINE hn::Vec<DI> Lerp8At(DF df, DI di, hn::Vec<DF> tt, hn::Vec<DI> ca, hn::Vec<DI> cb) {
    const hn::Vec<DI> wt = Lerp8Weight(df, di, tt);
#if RTM_HWY_X86_VECTORS || RTM_HWY_ARM_VECTORS
    return Lerp8Channels16(di, ca, cb, wt);
#else
    return hn::Or(hn::Or(Lerp8Channel<0>(di, ca, cb, wt), hn::ShiftLeft<8>(Lerp8Channel<8>(di, ca, cb, wt))),
                  hn::Or(hn::ShiftLeft<16>(Lerp8Channel<16>(di, ca, cb, wt)), hn::Set(di, int32_t(0xFF000000u))));
#endif
}

// Colours of raster_span(pv, pc, v, c) at the pixel centres yc (per lane), as raster_span_pixels computes them:
// t = clamp((yc - pv) * inv, 0, 1) with inv = 1 / (v - pv), then lerp8. (A function, not a struct of vectors: SVE's
// vectors are sizeless and cannot be members.)
template <class DF>
HWY_INLINE hn::Vec<hn::RebindToSigned<DF>> SpanColour(DF df, hn::Vec<DF> yc, hn::Vec<DF> pv, hn::Vec<DF> inv,
                                                      hn::Vec<hn::RebindToSigned<DF>> pc,
                                                      hn::Vec<hn::RebindToSigned<DF>> c) {
    // lerp8's weight straight from inv * 2^13 (the hand-written AVX-512 kernels' span_weight): w = 2n + 1
    // with n = int(max(min((yc - pv) * (inv * 2^13), 8191), 0)), which equals min(int(t * 2^14) | 1, 2^14 - 1) for
    // t = clamp((yc - pv) * inv, 0, 1): scaling by a power of two commutes with the rounding of the product and with
    // the clamp (where the product is subnormal t * 2^13 < 1 either way; where inv * 2^13 overflows, t is 0 or 1
    // either way: yc - pv is never 0 inside a span, so the product is never NaN in the lanes used; x86's minimum would
    // give 8191 for NaN as lerp8 does), and int(2x) | 1 = 2 int(x) + 1. Five operations where the clamp and
    // Lerp8Weight take nine (inv * 2^13 is the same for every pixel of a span: the compiler keeps it out of the
    // loops). Every vector target, x86's and ARM's (Highway's one-lane fallbacks aside).
    const hn::RebindToSigned<DF> di;
#if RTM_HWY_X86_VECTORS || RTM_HWY_ARM_VECTORS
    const hn::Vec<DF> s = hn::Mul(hn::Sub(yc, pv), hn::Mul(inv, hn::Set(df, 8192.0f)));
    const auto n = ConvertInRange(di, hn::Max(hn::Min(s, hn::Set(df, 8191.0f)), hn::Zero(df)));
    return Lerp8Channels16(di, pc, c, hn::Add(hn::Add(n, n), hn::Set(di, 1)));
#else
    return Lerp8At(df, di, Clamp01(hn::Mul(hn::Sub(yc, pv), inv)), pc, c);
#endif
}

// Writes the lanes `on` of col to pixels (x + lane, v-row y[lane]), one at a time.
template <class DI, class MI>
HWY_INLINE void StoreLanes(DI di, const ColumnTarget& o, int x, MI on, hn::Vec<DI> y, hn::Vec<DI> col) {
    HWY_ALIGN int32_t lane_y[HWY_MAX_BYTES / 4], lane_c[HWY_MAX_BYTES / 4], lane_on[HWY_MAX_BYTES / 4];
    hn::Store(y, di, lane_y);
    hn::Store(col, di, lane_c);
    hn::Store(hn::VecFromMask(di, on), di, lane_on);
    const size_t N = hn::Lanes(di);
    for (size_t i = 0; i < N; ++i)
        if (lane_on[i]) o.vline(lane_y[i])[size_t(x) + i] = uint32_t(lane_c[i]);
}

// Writes the lanes `act` of col to pixels (x + lane, v-row y[lane]): two masked row stores when every lane is on the
// first active lane's row or the next (and the vector is `full`), else lane by lane. With o.ahead, the first active
// lane's row plus o.ahead is prefetched (OutputAhead).
// Targets where storing some lanes of a whole vector pays: a masked store instruction (AVX2, AVX-512, SVE; on AVX2 8
// lanes loaded, blended and stored where that instruction is slow, StoreOwned); with 4 lanes (SSE4, NEON), whose
// masked store is a load, blend and store, that costs more than the lanes one by one.
#if HWY_TARGET == HWY_SSE4 || HWY_TARGET == HWY_NEON
constexpr bool kMaskedStore = false;
#else
constexpr bool kMaskedStore = true;
#endif

// Stores the lanes m of v at p, whose whole vector [p, p + N) is the caller's (no other thread writes it meanwhile, and
// it lies inside its array). On AVX2 with `blend` (where its masked store is slow: avx2_masked_store_slow, warp/isa.h,
// 12 cycles of the store pipe on Zen 2 to Zen 4) a load, blend and store of the whole vector. Else BlendedStore: AVX2's
// masked store (about a plain store's cost on Intel's cores and Zen 5, and cheaper there than a load, blend and store,
// whose store waits for the load: docs/perf-history.md, "AVX2's masked stores"), AVX-512's and SVE's masked stores,
// SSE4's and NEON's load, blend and store.
template <class D, class M, typename T>
HWY_INLINE void StoreOwned(hn::Vec<D> v, M m, D d, T* p, bool blend) {
#if HWY_TARGET == HWY_AVX2
    if (blend) {
        hn::StoreU(hn::IfThenElse(m, v, hn::LoadU(d, p)), d, p);
        return;
    }
#endif
    (void)blend;
    hn::BlendedStore(v, m, d, p);
}

template <class DI, class MI>
HWY_INLINE void StoreRows(DI di, const ColumnTarget& o, int x, bool full, MI act, hn::Vec<DI> y, hn::Vec<DI> col) {
    if (kMaskedStore && full) {
        HWY_ALIGN int32_t lane_y[HWY_MAX_BYTES / 4];
        hn::Store(y, di, lane_y);
        const int yf = lane_y[hn::FindFirstTrue(di, act)];
        int32_t* row = reinterpret_cast<int32_t*>(o.vline(yf) + x);
        // Row yf + ahead, o.ahead lines of o.ow pixels before row yf in memory; where that lies outside the image the
        // prefetch fetches nothing of use and cannot fault (the row clamped into the image and its address computed
        // afresh took about 15 instructions a call on AVX2).
        if (o.ahead)
            hwy::Prefetch(reinterpret_cast<const void*>(reinterpret_cast<uintptr_t>(row) -
                                                        uintptr_t(std::ptrdiff_t(o.ahead) * o.ow * 4)));
        // (Compared with yf and yf + 1 broadcast: two instructions fewer than y - yf against 0 and a constant 1.)
        const auto same = hn::And(act, hn::Eq(y, hn::Set(di, yf)));
        const auto next = hn::And(act, hn::Eq(y, hn::Set(di, yf + 1)));
        if (hn::AllFalse(di, hn::AndNot(hn::Or(same, next), act))) {
            StoreOwned(col, same, di, row, o.blend);
            if (!hn::AllFalse(di, next)) StoreOwned(col, next, di, row - o.ow, o.blend);
            return;
        }
    }
    StoreLanes(di, o, x, act, y, col);
}

#if HWY_TARGET <= HWY_AVX3
// AVX-512: the two row stores without a branch on whether the second has lanes, and one scatter instead of the lanes
// one by one (32-bit offsets from v-line 0 of column x: fast_prewarp_covers keeps the image under 2^31 - 16 pixels).
HWY_INLINE void StoreRows(hn::Full512<int32_t>, const ColumnTarget& o, int x, bool, hn::Mask512<int32_t> act,
                          hn::Vec512<int32_t> y, hn::Vec512<int32_t> col) {
    const __mmask16 a = act.raw;
    const int yf = _mm512_cvtsi512_si32(_mm512_permutexvar_epi32(_mm512_set1_epi32(int(_tzcnt_u32(a))), y.raw));
    const __m512i d = _mm512_sub_epi32(y.raw, _mm512_set1_epi32(yf));
    if (_mm512_mask_cmpgt_epu32_mask(a, d, _mm512_set1_epi32(1)) == 0) {
        _mm512_mask_storeu_epi32(o.vline(yf) + x, a & _mm512_cmpeq_epi32_mask(d, _mm512_setzero_si512()), col.raw);
        _mm512_mask_storeu_epi32(o.vline(std::min(yf + 1, o.oh - 1)) + x,
                                 a & _mm512_cmpeq_epi32_mask(d, _mm512_set1_epi32(1)), col.raw);
        return;
    }
    const __m512i iota = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
    const __m512i off = _mm512_add_epi32(_mm512_mullo_epi32(y.raw, _mm512_set1_epi32(-o.ow)), iota);
    _mm512_mask_i32scatter_epi32(o.vline(0) + x, a, off, col.raw, 4);
}
#endif

// Long spans, lanes `lng`, rows ylo .. yhi: row by row over the rows they cover together, one masked store a row (so
// that each line of the output is touched once rather than once per column); where the lanes' rows are sparse (the
// union more than twice their sum), the lanes outside the range of the longest go alone through raster_span_pixels.
// Only for `full` vectors.
template <class DF, class MI>
HWY_NOINLINE void ColumnLongSpans(DF df, const ColumnTarget& o, int x, MI lng, hn::Vec<hn::RebindToSigned<DF>> ylo,
                                  hn::Vec<hn::RebindToSigned<DF>> yhi, hn::Vec<DF> pv, hn::Vec<DF> inv,
                                  hn::Vec<hn::RebindToSigned<DF>> pc, hn::Vec<hn::RebindToSigned<DF>> c,
                                  hn::Vec<DF> v) {
    const hn::RebindToSigned<DF> di;
    const size_t N = hn::Lanes(df);
    HWY_ALIGN int32_t ilo[HWY_MAX_BYTES / 4], ihi[HWY_MAX_BYTES / 4], on[HWY_MAX_BYTES / 4];
    hn::Store(ylo, di, ilo);
    hn::Store(yhi, di, ihi);
    hn::Store(hn::VecFromMask(di, lng), di, on);
    int ymin = 1 << 30, ymax = -(1 << 30), best = -1;
    long long total = 0, count = 0;
    for (size_t i = 0; i < N; ++i) {
        if (!on[i]) continue;
        ymin = std::min(ymin, ilo[i]);
        ymax = std::max(ymax, ihi[i]);
        total += ihi[i] - ilo[i] + 1;
        ++count;
        if (best < 0 || ihi[i] - ilo[i] > ihi[best] - ilo[best]) best = int(i);
    }
    auto rowwise = lng;
    if ((long long)(ymax - ymin + 1) * count > 2 * total) {
        rowwise = hn::And(lng,
                          hn::And(hn::Gt(ylo, hn::Set(di, ilo[best] - 1)), hn::Lt(yhi, hn::Set(di, ihi[best] + 1))));
        const auto alone = hn::AndNot(rowwise, lng);
        if (!hn::AllFalse(di, alone)) {
            HWY_ALIGN float fpv[HWY_MAX_BYTES / 4], fv[HWY_MAX_BYTES / 4];
            HWY_ALIGN uint32_t fpc[HWY_MAX_BYTES / 4], fc[HWY_MAX_BYTES / 4];
            HWY_ALIGN int32_t al[HWY_MAX_BYTES / 4];
            const hn::RebindToUnsigned<DF> du;
            hn::Store(pv, df, fpv);
            hn::Store(v, df, fv);
            hn::Store(hn::BitCast(du, pc), du, fpc);
            hn::Store(hn::BitCast(du, c), du, fc);
            hn::Store(hn::VecFromMask(di, alone), di, al);
            auto rgba = [](uint32_t u) {
                return Rgba8{uint8_t(u), uint8_t(u >> 8), uint8_t(u >> 16), uint8_t(u >> 24)};
            };
            for (size_t i = 0; i < N; ++i) {
                if (!al[i]) continue;
                uint32_t* px = o.pixels + size_t(x) + i;
                raster_span_pixels(fpv[i], rgba(fpc[i]), 0.0f, fv[i], rgba(fc[i]), 0.0f, ilo[i], ihi[i],
                                   [&](int y, Rgba8 cc, float) {
                                       px[size_t(o.oh - 1 - y) * size_t(o.ow)] = uint32_t(cc.r) | uint32_t(cc.g) << 8 |
                                                                                 uint32_t(cc.b) << 16 | 0xFF000000u;
                                   });
            }
        }
        ymin = 1 << 30, ymax = -(1 << 30);
        hn::Store(hn::VecFromMask(di, rowwise), di, on);
        for (size_t i = 0; i < N; ++i)
            if (on[i]) ymin = std::min(ymin, ilo[i]), ymax = std::max(ymax, ihi[i]);
    }
    hn::Vec<DF> yc = hn::Set(df, float(ymin) + 0.5f);  // steps by 1 exactly
    for (int yy = ymin; yy <= ymax; ++yy) {
        const auto act = hn::And(rowwise, hn::And(hn::Lt(ylo, hn::Set(di, yy + 1)), hn::Gt(yhi, hn::Set(di, yy - 1))));
        StoreOwned(SpanColour(df, yc, pv, inv, pc, c), act, di, reinterpret_cast<int32_t*>(o.vline(yy) + x), o.blend);
        yc = hn::Add(yc, hn::Set(df, 1.0f));
    }
}

// Pixels ylo .. yhi of lanes `act` of columns x .. x + N - 1 (`full`: all of them in the caller's columns): in lanes
// `spani` of the span from (pv, pc) to (v, c) with inv = 1 / (v - pv) (raster_span_pixels), in the others the point
// (v, c) (one pixel, ylo == yhi). Any rows of a span may be asked for: a pixel's colour depends on its row alone.
template <class DF, class MI>
HWY_INLINE void ColumnPixels(DF df, const ColumnTarget& o, int x, bool full, MI act, MI spani, MI pointi,
                             hn::Vec<hn::RebindToSigned<DF>> ylo, hn::Vec<hn::RebindToSigned<DF>> yhi, hn::Vec<DF> pv,
                             hn::Vec<DF> inv, hn::Vec<hn::RebindToSigned<DF>> pc, hn::Vec<DF> v,
                             hn::Vec<hn::RebindToSigned<DF>> c) {
    const hn::RebindToSigned<DF> di;
    using VF = hn::Vec<DF>;
    using VI = hn::Vec<decltype(di)>;
    const VF half = hn::Set(df, 0.5f), one = hn::Set(df, 1.0f);
    if (full) {
        const auto lng = hn::And(hn::And(act, spani), hn::Gt(hn::Sub(yhi, ylo), hn::Set(di, kLongSpan - 1)));
        if (!hn::AllFalse(di, lng)) {
            ColumnLongSpans(df, o, x, lng, ylo, yhi, pv, inv, pc, c, v);
            act = hn::AndNot(lng, act);
            if (hn::AllFalse(di, act)) return;
        }
    }
    // Pixel k of every lane: y = ylo + k, colour at the centre y + 0.5 (steps by 1 exactly); a point's colour is
    // its own with alpha 255.
    const VI cpoint = hn::Or(c, hn::Set(di, int32_t(0xFF000000u)));
    VI y = ylo;
    VF yc = hn::Add(hn::ConvertTo(df, ylo), half);
    StoreRows(di, o, x, full, act, y, hn::IfThenElse(pointi, cpoint, SpanColour(df, yc, pv, inv, pc, c)));
    act = hn::And(act, hn::And(spani, hn::Lt(y, yhi)));
    while (!hn::AllFalse(di, act)) {
        y = hn::Add(y, hn::Set(di, 1));
        yc = hn::Add(yc, one);
        StoreRows(di, o, x, full, act, y, SpanColour(df, yc, pv, inv, pc, c));
        act = hn::And(act, hn::Lt(y, yhi));
    }
}

// The rows raster_span(pv, v) / raster_point(v) write in columns x .. x + N - 1, for ColumnDraw and ColumnDrawRev
// (see there): lanes `span` and `point` (as masks of DI), rows ylo .. yhi clamped to [y0, y1 - 1].
template <class DF, class MF, class MI>
HWY_INLINE void ColumnRows(DF df, const ColumnTarget& o, MF fin, MF pok, hn::Vec<DF> pv, hn::Vec<DF> v, MI& spani,
                           MI& pointi, hn::Vec<hn::RebindToSigned<DF>>& ylo, hn::Vec<hn::RebindToSigned<DF>>& yhi) {
    const hn::RebindToSigned<DF> di;
    using VF = hn::Vec<DF>;
    const VF half = hn::Set(df, 0.5f), one = hn::Set(df, 1.0f);
    // (y1 - 1 from y1 as floats, exact below 2^24: one conversion a vector fewer where GCC redoes them in the loop.)
    const VF first = hn::Set(df, float(o.y0)), end = hn::Set(df, float(o.y1)), last = hn::Sub(end, one);
    // raster_span's rows in float: lo .. hi, clamped to [0, oh - 1] and to [y0, y1 - 1].
    const auto inc = hn::And(pok, hn::Gt(v, pv)), dec = hn::And(pok, hn::Lt(v, pv));
    const VF pvh = hn::Sub(pv, half), vh = hn::Sub(v, half);
    VF lo = hn::IfThenElse(inc, hn::Add(hn::Floor(pvh), one), hn::Ceil(vh));
    VF hi = hn::IfThenElse(inc, hn::Floor(vh), hn::Sub(hn::Ceil(pvh), one));
    // (Finite in the lanes of inc and dec, where pv and v are: Max and Min clamp as the comparisons would.)
    lo = hn::Max(lo, first);
    hi = hn::Min(hi, last);
    const auto span = hn::And(hn::Or(inc, dec), hn::Le(lo, hi));
    // raster_point: row int(v) where 0 <= v < oh, and y0 <= int(v) < y1.
    const auto point = hn::AndNot(pok, hn::And(fin, hn::And(hn::Ge(v, first), hn::Lt(v, end))));
    spani = hn::RebindMask(di, span);
    pointi = hn::RebindMask(di, point);
    // Rows in [y0, y1 - 1] in the lanes of span and point, the only ones used.
    ylo = ConvertInRange(di, hn::IfThenElse(point, v, lo));
    yhi = hn::IfThenElse(pointi, ylo, ConvertInRange(di, hi));
}

// Whether every lane of a vector is a still step: connected (pok) to the column's previous sample exactly one row
// before (|v - pv| == 1: below it in the bottom part, above it in the top part), the new sample on the centre of
// v-row y = v - 0.5, the same y in every lane, inside [y0, y1). raster_span(pv, pc, v, c) then writes the one pixel y
// of each column with t = (y + 0.5 - pv) * (1 / (v - pv)) = 1 exactly (+-1 over +-1), lerp8 at t = 1 (weight
// 2^14 - 1: (a + (2^14 - 1) b + 2^13) >> 14 = b) gives c, alpha 255: the step is a copy of c into row y. Zero
// displacement gives such steps (the paper, section 5: still texels need no warp; the two-pass kernels copy blocks of
// them in their vertical pass, vertical_with_still in warp/simd/schedule.cpp).
template <class DF, class MF>
HWY_INLINE bool StillStep(DF df, const ColumnTarget& o, MF pok, hn::Vec<DF> pv, hn::Vec<DF> v, int& y) {
    if (!hn::AllTrue(df, pok)) return false;
    const float v0 = hn::GetLane(v);
    const auto step = hn::Eq(hn::Abs(hn::Sub(v, pv)), hn::Set(df, 1.0f));
    if (!hn::AllTrue(df, hn::And(step, hn::Eq(v, hn::Set(df, v0))))) return false;
    const float yf = v0 - 0.5f;
    if (!(yf >= float(o.y0) && yf < float(o.y1)) || std::floor(yf) != yf) return false;
    y = int(yf);
    return float(y) + 0.5f == v0;  // the pixel centre the span's arithmetic computes is v itself
}

// Columns x .. x + N - 1 (`full`: all of them in the caller's columns): in lanes `fin` a new sample (final row
// coordinate v, packed colour c) arrives; in lanes `pok` (a subset) the column's previous sample (pv, pc) is
// connected to it, raster_span(pv, pc, v, c) along the column; in the other lanes of `fin` the new sample starts a
// run, raster_point(v, c). Only pixels in v-rows [y0, y1) are written.
//
// With `copy` (PrewarpOptions::copy_still_runs; the pipelined kernel's), a `full` vector of still steps (StillStep)
// is one row store.
template <class DF, class MF>
HWY_INLINE void ColumnDraw(DF df, const ColumnTarget& o, int x, bool full, bool copy, MF fin, MF pok, hn::Vec<DF> pv,
                           hn::Vec<hn::RebindToSigned<DF>> pc, hn::Vec<DF> v, hn::Vec<hn::RebindToSigned<DF>> c) {
    const hn::RebindToSigned<DF> di;
    int ys;
    if (copy && full && StillStep(df, o, pok, pv, v, ys)) {
        hn::StoreU(hn::Or(c, hn::Set(di, int32_t(0xFF000000u))), di, reinterpret_cast<int32_t*>(o.vline(ys) + x));
        return;
    }
    auto spani = hn::FirstN(di, 0), pointi = spani;
    hn::Vec<decltype(di)> ylo, yhi;
    ColumnRows(df, o, fin, pok, pv, v, spani, pointi, ylo, yhi);
    const auto todo = hn::Or(spani, pointi);
    if (hn::AllFalse(di, todo)) return;
    ColumnPixels(df, o, x, full, todo, spani, pointi, ylo, yhi, pv, hn::Div(hn::Set(df, 1.0f), hn::Sub(v, pv)), pc, v,
                 c);
}

// The pipelined kernel's reverse mode (warp/simd/hwy_pipelined.cpp): per output column, the rows written so far,
// as one interval [lo, hi] (empty when lo > hi) or, where that is not one interval (bits_on), a bitmask of nw
// words. Arrays of the output width, readable and writable a whole vector past it.
struct ColumnsWritten {
    int32_t* lo;
    int32_t* hi;
    int32_t* bits_on;
    uint64_t* bits;
    int nw;
};

// ColumnDrawRev's lanes `fb` (as a mask of DI) whose rows ylo .. yhi are not one interval with the rows their column
// has: the column's bitmask (made from its interval the first time), and the runs of rows not yet written, one lane
// at a time.
template <class DF, class MI>
HWY_NOINLINE void ColumnBits(DF df, const ColumnTarget& o, const ColumnsWritten& cw, int x, MI fb, MI spani,
                             hn::Vec<hn::RebindToSigned<DF>> ylo, hn::Vec<hn::RebindToSigned<DF>> yhi, hn::Vec<DF> pv,
                             hn::Vec<hn::RebindToSigned<DF>> pc, hn::Vec<DF> v, hn::Vec<hn::RebindToSigned<DF>> c) {
    const hn::RebindToSigned<DF> di;
    const hn::RebindToUnsigned<DF> du;
    const size_t N = hn::Lanes(df);
    HWY_ALIGN int32_t lo[HWY_MAX_BYTES / 4], hi[HWY_MAX_BYTES / 4], on[HWY_MAX_BYTES / 4], sp[HWY_MAX_BYTES / 4];
    HWY_ALIGN float fpv[HWY_MAX_BYTES / 4], fv[HWY_MAX_BYTES / 4];
    HWY_ALIGN uint32_t fpc[HWY_MAX_BYTES / 4], fc[HWY_MAX_BYTES / 4];
    hn::Store(ylo, di, lo);
    hn::Store(yhi, di, hi);
    hn::Store(hn::VecFromMask(di, fb), di, on);
    hn::Store(hn::VecFromMask(di, spani), di, sp);
    hn::Store(pv, df, fpv);
    hn::Store(v, df, fv);
    hn::Store(hn::BitCast(du, pc), du, fpc);
    hn::Store(hn::BitCast(du, c), du, fc);
    auto rgba = [](uint32_t u) { return Rgba8{uint8_t(u), uint8_t(u >> 8), uint8_t(u >> 16), uint8_t(u >> 24)}; };
    for (size_t i = 0; i < N; ++i) {
        if (!on[i]) continue;
        const size_t col = size_t(x) + i;
        uint64_t* w = cw.bits + col * size_t(cw.nw);
        uint32_t* px = o.pixels + col;
        // Rows a .. b (a <= b) marked written; with `draw`, those that were not are drawn.
        auto set_range = [&](int a, int b, bool draw) {
            for (int q = a >> 6; q <= b >> 6; ++q) {
                const int s = std::max(a, q * 64) - q * 64, e = std::min(b, q * 64 + 63) - q * 64;
                const uint64_t rm = (~uint64_t(0) >> (63 - e)) & (~uint64_t(0) << s);
                uint64_t todo = draw ? rm & ~w[q] : 0;
                w[q] |= rm;
                while (todo) {
                    const int r0 = int(hwy::Num0BitsBelowLS1Bit_Nonzero64(todo));
                    const uint64_t rest = ~(todo >> r0);
                    const int len = rest ? int(hwy::Num0BitsBelowLS1Bit_Nonzero64(rest)) : 64 - r0;
                    const int ya = q * 64 + r0, yb = ya + len - 1;
                    if (sp[i]) {
                        raster_span_pixels(fpv[i], rgba(fpc[i]), 0.0f, fv[i], rgba(fc[i]), 0.0f, ya, yb,
                                           [&](int y, Rgba8 cc, float) {
                                               px[size_t(o.oh - 1 - y) * size_t(o.ow)] = uint32_t(cc.r) |
                                                                                         uint32_t(cc.g) << 8 |
                                                                                         uint32_t(cc.b) << 16 |
                                                                                         0xFF000000u;
                                           });
                    } else {
                        px[size_t(o.oh - 1 - ya) * size_t(o.ow)] = fc[i] | 0xFF000000u;
                    }
                    todo &= len == 64 ? 0 : ~(((uint64_t(1) << len) - 1) << r0);
                }
            }
        };
        if (!cw.bits_on[col]) {
            cw.bits_on[col] = 1;
            std::fill(w, w + cw.nw, uint64_t(0));
            if (cw.lo[col] <= cw.hi[col]) set_range(cw.lo[col], cw.hi[col], false);
        }
        set_range(lo[i], hi[i], true);
    }
}

// ColumnDraw in reverse mode (the emissions replayed from the last to the first): writes only the rows no emission
// replayed before wrote in its column, and records them. Where the rows extend the column's interval (below it,
// above it, or both), the lanes go together (ColumnPixels); elsewhere (rows apart from the interval, or a column
// already on a bitmask) ColumnBits.
//
// With `copy`, a `full` vector of still steps (StillStep: one row y in every column) whose row lies in, or next to,
// the interval of every column (no bitmask) is one row store of the lanes whose interval does not hold y yet.
template <class DF, class MF>
HWY_INLINE void ColumnDrawRev(DF df, const ColumnTarget& o, const ColumnsWritten& cw, int x, bool full, bool copy,
                              MF fin, MF pok, hn::Vec<DF> pv, hn::Vec<hn::RebindToSigned<DF>> pc, hn::Vec<DF> v,
                              hn::Vec<hn::RebindToSigned<DF>> c) {
    const hn::RebindToSigned<DF> di;
    using VI = hn::Vec<decltype(di)>;
    int ys;
    if (copy && full && StillStep(df, o, pok, pv, v, ys)) {
        const VI y = hn::Set(di, ys), one = hn::Set(di, 1);
        const VI clo = hn::LoadU(di, cw.lo + x), chi = hn::LoadU(di, cw.hi + x);
        const auto emp = hn::Gt(clo, chi);
        const auto inside = hn::AndNot(emp, hn::Not(hn::Or(hn::Lt(y, clo), hn::Gt(y, chi))));
        const auto next_to = hn::Or(emp, hn::Or(hn::Eq(y, hn::Sub(clo, one)), hn::Eq(y, hn::Add(chi, one))));
        if (hn::AllFalse(di, hn::Ne(hn::LoadU(di, cw.bits_on + x), hn::Zero(di))) &&
            hn::AllTrue(di, hn::Or(inside, next_to))) {
            hn::StoreU(hn::IfThenElse(emp, y, hn::Min(clo, y)), di, cw.lo + x);
            hn::StoreU(hn::IfThenElse(emp, y, hn::Max(chi, y)), di, cw.hi + x);
            const VI cy = hn::Or(c, hn::Set(di, int32_t(0xFF000000u)));
            int32_t* row = reinterpret_cast<int32_t*>(o.vline(ys) + x);
            if (hn::AllFalse(di, inside))
                hn::StoreU(cy, di, row);
            else if (!hn::AllTrue(di, inside))
                StoreOwned(cy, hn::Not(inside), di, row, o.blend);  // `full`: the whole vector is the caller's
            return;
        }
    }
    auto spani = hn::FirstN(di, 0), pointi = spani;
    VI ylo, yhi;
    ColumnRows(df, o, fin, pok, pv, v, spani, pointi, ylo, yhi);
    const auto todo = hn::Or(spani, pointi);
    if (hn::AllFalse(di, todo)) return;
    const VI one = hn::Set(di, 1);
    const VI clo = hn::LoadU(di, cw.lo + x), chi = hn::LoadU(di, cw.hi + x);
    const auto emp = hn::Gt(clo, chi);
    // (Highway 1.0.3 has no Ge / Le for integers.) Lanes whose rows reach outside the interval, or with none.
    const auto outside = hn::Or(emp, hn::Or(hn::Lt(ylo, clo), hn::Gt(yhi, chi)));
    const auto apart = hn::AndNot(emp, hn::Or(hn::Lt(yhi, hn::Sub(clo, one)), hn::Gt(ylo, hn::Add(chi, one))));
    const auto fb = hn::And(todo, hn::Or(hn::Ne(hn::LoadU(di, cw.bits_on + x), hn::Zero(di)), apart));
    const auto go = hn::And(outside, hn::AndNot(fb, todo));
    const auto inv = hn::Div(hn::Set(df, 1.0f), hn::Sub(v, pv));
    if (!hn::AllFalse(di, go)) {
        // cw.lo / hi are the task's own, padded: a whole-vector store (StoreOwned) touches no one else's.
        StoreOwned(hn::IfThenElse(emp, ylo, hn::Min(ylo, clo)), go, di, cw.lo + x, o.blend);
        StoreOwned(hn::IfThenElse(emp, yhi, hn::Max(yhi, chi)), go, di, cw.hi + x, o.blend);
        // Below the interval (everything where the column has none), above it, or both.
        const auto low = hn::And(go, hn::Or(emp, hn::Lt(ylo, clo)));
        const auto high = hn::And(go, hn::AndNot(emp, hn::Gt(yhi, chi)));
        if (!hn::AllFalse(di, low))
            ColumnPixels(df, o, x, full, low, hn::And(spani, low), hn::And(pointi, low), ylo,
                         hn::IfThenElse(emp, yhi, hn::Min(yhi, hn::Sub(clo, one))), pv, inv, pc, v, c);
        if (!hn::AllFalse(di, high))
            ColumnPixels(df, o, x, full, high, hn::And(spani, high), hn::And(pointi, high),
                         hn::Max(ylo, hn::Add(chi, one)), yhi, pv, inv, pc, v, c);
    }
    if (!hn::AllFalse(di, fb)) [[unlikely]]
        ColumnBits(df, o, cw, x, fb, spani, ylo, yhi, pv, pc, v, c);
}

}  // namespace rtm::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // RTM_WARP_SIMD_HWY_COLUMNS_INL_H_
