// The fast pipelined pre-warp kernel (see fast_pipelined.h). Compiled with -ffp-contract=off (warp/CMakeLists.txt):
// the pixel identity with the reference rests on every float operation being the one the reference performs.
#include "warp/fast_pipelined.h"

#include <immintrin.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "warp/line_warp.h"

#pragma GCC push_options
// GCC 12 reports _mm512_undefined_* inside its own intrinsics as possibly uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC target("avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi,bmi,bmi2,lzcnt,popcnt")
#include "warp/fast_line.h"
#include "warp/fast_row.h"

namespace rtm {
namespace {

// Per-thread buffers: the line, one row of horizontal output, and the column state of the task (the previous
// row's sample per column and the current row's).
struct PipeScratch {
    LineStorage line;
    void* block = nullptr;
    size_t capacity = 0;  // columns
    uint32_t* row_c = nullptr;
    float* row_v = nullptr;
    float* prev_v = nullptr;
    float* cur_v = nullptr;
    uint32_t* prev_c = nullptr;
    uint32_t* cur_c = nullptr;
    uint8_t* prev_ok = nullptr;
    uint8_t* cur_ok = nullptr;

    PipeScratch() = default;
    PipeScratch(const PipeScratch&) = delete;
    PipeScratch& operator=(const PipeScratch&) = delete;
    ~PipeScratch() { std::free(block); }
    void reserve(int ow) {
        if (size_t(ow) <= capacity) return;
        std::free(block);
        capacity = (size_t(ow) + 63) & ~size_t(63);
        const size_t n = capacity + 64;  // 16-wide loads and stores may reach past the end
        block = alloc64(n * 4 * 6 + n * 2);
        std::memset(block, 0, n * 4 * 6 + n * 2);
        char* p = static_cast<char*>(block);
        auto take = [&](size_t bytes) {
            char* q = p;
            p += bytes;
            return q;
        };
        row_c = reinterpret_cast<uint32_t*>(take(n * 4));
        row_v = reinterpret_cast<float*>(take(n * 4));
        prev_v = reinterpret_cast<float*>(take(n * 4));
        cur_v = reinterpret_cast<float*>(take(n * 4));
        prev_c = reinterpret_cast<uint32_t*>(take(n * 4));
        cur_c = reinterpret_cast<uint32_t*>(take(n * 4));
        prev_ok = reinterpret_cast<uint8_t*>(take(n));
        cur_ok = reinterpret_cast<uint8_t*>(take(n));
    }
};

PipeScratch& pipe_scratch() {
    static thread_local PipeScratch s;
    return s;
}

inline void unpack_rgb(__m512i c, __m512& r, __m512& g, __m512& b) {
    const __m512i m = _mm512_set1_epi32(0xFF);
    r = _mm512_cvtepi32_ps(_mm512_and_si512(c, m));
    g = _mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(c, 8), m));
    b = _mm512_cvtepi32_ps(_mm512_and_si512(_mm512_srli_epi32(c, 16), m));
}

// What the reference's put() does for each pixel the row warp emits, for columns [xa, xb] at once: connect the
// column's previous sample to the new one with raster_span (or start with raster_point), writing only output
// v-rows [y0, y1), and make the new sample the column's current one.
struct Emitter {
    PipeScratch& sc;
    uint32_t* out;
    int ow, oh, y0, y1;

    // Pixels ylo .. yhi of column x of raster_span(pa, ca, pb, cb): 16 rows at a time.
    void long_span(int x, int ylo, int yhi, float pa, float inv, float ra, float ga, float ba, float rb, float gb,
                   float bb) const {
        const __m512 half = _mm512_set1_ps(0.5f), one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
        const __m512 vpa = _mm512_set1_ps(pa), vinv = _mm512_set1_ps(inv);
        alignas(64) uint32_t col[16];
        for (int y0 = ylo; y0 <= yhi; y0 += 16) {
            const __m512i y = _mm512_add_epi32(_mm512_set1_epi32(y0), iota16());
            __m512 t = _mm512_mul_ps(_mm512_sub_ps(_mm512_add_ps(_mm512_cvtepi32_ps(y), half), vpa), vinv);
            t = _mm512_max_ps(zero, _mm512_min_ps(one, t));
            const __m512 u = _mm512_sub_ps(one, t);
            auto lerp8 = [&](float a, float b) {
                return _mm512_cvttps_epi32(_mm512_add_ps(
                    _mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(a), u), _mm512_mul_ps(_mm512_set1_ps(b), t)), half));
            };
            _mm512_store_si512(col, pack_rgb(lerp8(ra, rb), lerp8(ga, gb), lerp8(ba, bb)));
            const int n = imin(16, yhi - y0 + 1);
            uint32_t* p = out + size_t(oh - 1 - y0) * size_t(ow) + size_t(x);
            for (int i = 0; i < n; ++i, p -= ow) *p = col[i];
        }
    }

    void operator()(int xa, int xb) const {
        const __m512 half = _mm512_set1_ps(0.5f), one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
        const __m512 last = _mm512_set1_ps(float(oh - 1)), ohf = _mm512_set1_ps(float(oh));
        const __m512i iy0 = _mm512_set1_epi32(y0), iy1 = _mm512_set1_epi32(y1 - 1);
        for (int x = xa; x <= xb; x += 16) {
            const __mmask16 m = first_lanes(xb - x + 1);
            const __m512 v = _mm512_maskz_loadu_ps(m, sc.row_v + x);
            const __m512i c = _mm512_maskz_loadu_epi32(m, sc.row_c + x);
            const __mmask16 fin = m & ~nonfinite(v);  // the reference skips emissions with a non-finite row coordinate
            if (!fin) continue;
            const __m128i okb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(sc.prev_ok + x));
            const __mmask16 pok = fin & _mm_test_epi8_mask(okb, okb);
            const __m512 pv = _mm512_loadu_ps(sc.prev_v + x);
            const __m512i pc = _mm512_loadu_si512(sc.prev_c + x);
            _mm512_mask_storeu_ps(sc.cur_v + x, fin, v);
            _mm512_mask_storeu_epi32(sc.cur_c + x, fin, c);
            _mm_mask_storeu_epi8(sc.cur_ok + x, fin, _mm_set1_epi8(1));
            // Spans (raster_span(pv, pc, v, c, oh)): pixel range in float as the reference computes it.
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
            // Points (raster_point(v, c, oh)) where the column had no sample.
            const __mmask16 point =
                fin & ~pok & _mm512_cmp_ps_mask(v, zero, _CMP_GE_OQ) & _mm512_cmp_ps_mask(v, ohf, _CMP_LT_OQ);
            // Integer rows, clamped to this part's output rows (the reference's put() drops the others).
            const __m512i vi = _mm512_cvttps_epi32(_mm512_mask_mov_ps(zero, point, v));
            __m512i ylo = _mm512_mask_mov_epi32(vi, span, _mm512_cvttps_epi32(_mm512_mask_mov_ps(zero, span, lo)));
            __m512i yhi = _mm512_mask_mov_epi32(vi, span, _mm512_cvttps_epi32(_mm512_mask_mov_ps(zero, span, hi)));
            ylo = _mm512_max_epi32(ylo, iy0);
            yhi = _mm512_min_epi32(yhi, iy1);
            const __mmask16 todo = (span | point) & _mm512_cmple_epi32_mask(ylo, yhi);
            if (!todo) continue;
            const __m512 inv = _mm512_div_ps(one, _mm512_sub_ps(v, pv));
            __m512 ra, ga, ba, rb, gb, bb;
            unpack_rgb(pc, ra, ga, ba);
            unpack_rgb(c, rb, gb, bb);
            const __m512i cpoint = _mm512_or_si512(c, _mm512_set1_epi32(int(0xFF000000)));
            // Long spans (a column connected to a sample far away, common where rows fold over: ridges 1024^2
            // write 93 pixels a texel this way) go row by row over the rows they cover together, one masked store
            // per row for all of them, so that each line of the output is touched once rather than once per
            // column (ridges 1024^2: 310 ms with every lane waiting for the longest span, 489 ms column by column,
            // see the figures in docs/BENCHMARKS.md for row by row). Spans far apart from the others go alone.
            const __mmask16 lng = todo & _mm512_cmpge_epi32_mask(_mm512_sub_epi32(yhi, ylo), _mm512_set1_epi32(4));
            if (lng) {
                const int ymin = _mm512_mask_reduce_min_epi32(lng, ylo), ymax = _mm512_mask_reduce_max_epi32(lng, yhi);
                const long long total = _mm512_mask_reduce_add_epi32(
                    lng, _mm512_add_epi32(_mm512_sub_epi32(yhi, ylo), _mm512_set1_epi32(1)));
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
                        alignas(64) float fpa[16], finv[16], fra[16], fga[16], fba[16], frb[16], fgb[16], fbb[16];
                        _mm512_store_ps(fpa, pv);
                        _mm512_store_ps(finv, inv);
                        _mm512_store_ps(fra, ra);
                        _mm512_store_ps(fga, ga);
                        _mm512_store_ps(fba, ba);
                        _mm512_store_ps(frb, rb);
                        _mm512_store_ps(fgb, gb);
                        _mm512_store_ps(fbb, bb);
                        for (__mmask16 l = alone; l; l &= __mmask16(l - 1)) {
                            const int i = int(_tzcnt_u32(l));
                            long_span(x + i, ilo[i], ihi[i], fpa[i], finv[i], fra[i], fga[i], fba[i], frb[i], fgb[i],
                                      fbb[i]);
                        }
                    }
                }
                if (rowwise) {
                    const int y_lo = _mm512_mask_reduce_min_epi32(rowwise, ylo);
                    const int y_hi = _mm512_mask_reduce_max_epi32(rowwise, yhi);
                    for (int yy = y_lo; yy <= y_hi; ++yy) {
                        const __m512i Y = _mm512_set1_epi32(yy);
                        const __mmask16 on =
                            rowwise & _mm512_cmple_epi32_mask(ylo, Y) & _mm512_cmpge_epi32_mask(yhi, Y);
                        const __m512 yc = _mm512_add_ps(_mm512_cvtepi32_ps(Y), half);
                        __m512 t = _mm512_mul_ps(_mm512_sub_ps(yc, pv), inv);
                        t = _mm512_max_ps(zero, _mm512_min_ps(one, t));
                        const __m512 u = _mm512_sub_ps(one, t);
                        auto lerp8 = [&](__m512 a, __m512 b) {
                            return _mm512_cvttps_epi32(
                                _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(a, u), _mm512_mul_ps(b, t)), half));
                        };
                        _mm512_mask_storeu_epi32(out + size_t(oh - 1 - yy) * size_t(ow) + size_t(x), on,
                                                 pack_rgb(lerp8(ra, rb), lerp8(ga, gb), lerp8(ba, bb)));
                    }
                }
            }
            __mmask16 act = todo & __mmask16(~lng);
            for (int it = 0; act; ++it) {
                const __m512i y = _mm512_add_epi32(ylo, _mm512_set1_epi32(it));
                const __m512 yc = _mm512_add_ps(_mm512_cvtepi32_ps(y), half);
                __m512 t = _mm512_mul_ps(_mm512_sub_ps(yc, pv), inv);
                t = _mm512_max_ps(zero, _mm512_min_ps(one, t));
                const __m512 u = _mm512_sub_ps(one, t);
                auto lerp8 = [&](__m512 a, __m512 b) {
                    return _mm512_cvttps_epi32(
                        _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(a, u), _mm512_mul_ps(b, t)), half));
                };
                const __m512i col =
                    _mm512_mask_mov_epi32(pack_rgb(lerp8(ra, rb), lerp8(ga, gb), lerp8(ba, bb)), point, cpoint);
                // Neighbouring columns mostly land on the same output row: one masked row store per distinct row
                // (a 16-lane scatter costs about 35 TSC cycles here, a masked store a few).
                for (__mmask16 left = act; left;) {
                    const int yv = _mm512_cvtsi512_si32(
                        _mm512_permutexvar_epi32(_mm512_set1_epi32(int(_tzcnt_u32(left))), y));
                    const __mmask16 same = left & _mm512_cmpeq_epi32_mask(y, _mm512_set1_epi32(yv));
                    _mm512_mask_storeu_epi32(out + size_t(oh - 1 - yv) * size_t(ow) + size_t(x), same, col);
                    left &= __mmask16(~same);
                }
                act = act & span & _mm512_cmplt_epi32_mask(y, yhi);
            }
        }
    }
};

struct ClipRange {
    const Emitter& emit;
    int x0, x1;  // columns [x0, x1)
    void operator()(int a, int b) const {
        a = imax(a, x0);
        b = imin(b, x1 - 1);
        if (a <= b) emit(a, b);
    }
};

}  // namespace

namespace fast {

void pipelined_part(const PipelinedJob& job, int part, int x0, int x1) {
    const ReliefTexture& t = *job.relief;
    const int h = t.height, ow = job.out->width, oh = job.out->height;
    const int split = job.split_v;
    const int first = part == 0 ? 0 : h - 1, end = part == 0 ? split : split - 1, step = part == 0 ? 1 : -1;
    const int y0 = part == 0 ? 0 : job.ysplit, y1 = part == 0 ? job.ysplit : oh;
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    for (int y = y0; y < y1; ++y)
        std::memset(out + size_t(oh - 1 - y) * size_t(ow) + size_t(x0), 0, size_t(x1 - x0) * 4);
    PipeScratch& sc = pipe_scratch();
    sc.reserve(ow);
    sc.line.reserve(t.width);
    LineSoA& s = sc.line.soa;
    std::memset(sc.prev_ok, 0, size_t(ow));
    const Emitter emit{sc, out, ow, oh, y0, y1};
    long long dropped = 0;
    for (int j = first; j != end; j += step) {
        const int r = h - 1 - j;
        const long long d = prepare_row(t, *job.tables, job.extent, ow, r, s);
        if (x0 == 0) dropped += d;
        std::memset(sc.cur_ok + x0, 0, size_t(x1 - x0));
        warp_line_fast<true>(s, job.split_u, LineOut{sc.row_c, sc.row_v, ow, x0, x1 - 1}, ClipRange{emit, x0, x1});
        std::swap(sc.prev_v, sc.cur_v);
        std::swap(sc.prev_c, sc.cur_c);
        std::swap(sc.prev_ok, sc.cur_ok);
    }
    for (int x = x0; x < x1; ++x) {
        job.seam_v[part][x] = sc.prev_v[x];
        job.seam_c[part][x] = sc.prev_ok[x] ? (sc.prev_c[x] | 0xFF000000u) : 0u;
    }
    if (dropped) *job.dropped += dropped;
}

void pipelined_seam(const PipelinedJob& job) {
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

}  // namespace fast
}  // namespace rtm

#pragma GCC diagnostic pop
#pragma GCC pop_options
