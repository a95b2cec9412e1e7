// The fast two-pass pre-warp kernels (see fast_two_pass.h). Compiled with -ffp-contract=off (warp/CMakeLists.txt):
// the pixel identity with the reference rests on every float operation being the one the reference performs.
//
// Measurements that shaped this file (single thread, CPU time, bumps 1024^2, eye (0.3, 0.2, 1.5), AMD EPYC Zen 4
// under a load of 2 to 5 from other builds; the generic reference takes about 90 ms):
// - intermediate image read column-wise with 16 x 16 transposes straight from the row-major image: vertical pass
//   6.9 ms; from 16-column tiles written by the horizontal pass (one sequential stream per tile): 4.5 ms;
// - the three table lookups per texel as AVX-512 gathers: 40% of the horizontal pass (4.4 cycles a texel); as
//   byte-plane permutes (fast_row.h): horizontal pass 4.35 -> 3.7 ms.
#include "warp/fast_two_pass.h"

#include <immintrin.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>

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

// In-register transpose of a 16 x 16 tile of 32-bit values: row i of `r` becomes column i.
inline void transpose16(__m512i r[16]) {
    __m512i t[16], u[16];
    for (int i = 0; i < 16; i += 2) {
        t[i] = _mm512_unpacklo_epi32(r[i], r[i + 1]);
        t[i + 1] = _mm512_unpackhi_epi32(r[i], r[i + 1]);
    }
    for (int i = 0; i < 16; i += 4) {
        u[i] = _mm512_unpacklo_epi64(t[i], t[i + 2]);
        u[i + 1] = _mm512_unpackhi_epi64(t[i], t[i + 2]);
        u[i + 2] = _mm512_unpacklo_epi64(t[i + 1], t[i + 3]);
        u[i + 3] = _mm512_unpackhi_epi64(t[i + 1], t[i + 3]);
    }
    // u[4g + m], 128-bit lane L: column 4L + m of rows 4g .. 4g + 3.
    for (int m = 0; m < 4; ++m) {
        t[m] = _mm512_shuffle_i32x4(u[m], u[4 + m], 0x88);
        t[4 + m] = _mm512_shuffle_i32x4(u[m], u[4 + m], 0xdd);
        t[8 + m] = _mm512_shuffle_i32x4(u[8 + m], u[12 + m], 0x88);
        t[12 + m] = _mm512_shuffle_i32x4(u[8 + m], u[12 + m], 0xdd);
    }
    for (int m = 0; m < 4; ++m) {
        r[m] = _mm512_shuffle_i32x4(t[m], t[8 + m], 0x88);
        r[4 + m] = _mm512_shuffle_i32x4(t[4 + m], t[12 + m], 0x88);
        r[8 + m] = _mm512_shuffle_i32x4(t[m], t[8 + m], 0xdd);
        r[12 + m] = _mm512_shuffle_i32x4(t[4 + m], t[12 + m], 0xdd);
    }
}

struct ThreadScratch {
    LineStorage line;
    // Horizontal pass: one output row (colour, v), width rounded up to 16.
    uint32_t* row_c = nullptr;
    float* row_v = nullptr;
    size_t row_capacity = 0;
    // Vertical pass: 16 columns of the intermediate image as lines (colour, v) and 16 output lines.
    uint32_t* col_t = nullptr;
    float* v_t = nullptr;
    uint32_t* out_t = nullptr;
    size_t in_stride = 0, out_stride = 0;  // elements per line, multiples of 16

    ThreadScratch() = default;
    ThreadScratch(const ThreadScratch&) = delete;
    ThreadScratch& operator=(const ThreadScratch&) = delete;
    ~ThreadScratch() {
        release_columns();
        std::free(row_c);
        std::free(row_v);
    }
    void release_columns() {
        std::free(col_t);
        std::free(v_t);
        std::free(out_t);
        col_t = nullptr;
        v_t = nullptr;
        out_t = nullptr;
    }
    void reserve_row(int ow) {
        const size_t n = (size_t(ow) + 15) & ~size_t(15);
        if (n <= row_capacity) return;
        std::free(row_c);
        std::free(row_v);
        row_capacity = n;
        row_c = static_cast<uint32_t*>(alloc64(n * 4));
        row_v = static_cast<float*>(alloc64(n * 4));
        std::memset(row_v, 0, n * 4);
    }
    void reserve_columns(int h, int oh) {
        const size_t in = (size_t(h) + 15) & ~size_t(15), o = (size_t(oh) + 15) & ~size_t(15);
        if (in <= in_stride && o <= out_stride) return;
        release_columns();
        in_stride = in > in_stride ? in : in_stride;
        out_stride = o > out_stride ? o : out_stride;
        col_t = static_cast<uint32_t*>(alloc64(16 * in_stride * 4));
        v_t = static_cast<float*>(alloc64(16 * in_stride * 4));
        out_t = static_cast<uint32_t*>(alloc64(16 * out_stride * 4));
    }
};

ThreadScratch& thread_scratch() {
    static thread_local ThreadScratch s;
    return s;
}

struct NoRange {
    void operator()(int, int) const {}
};

}  // namespace

namespace fast {

void horizontal_rows(const TwoPassJob& job, int r0, int r1) {
    const ReliefTexture& t = *job.relief;
    const FastTables& tab = *job.tables;
    const int w = t.width, h = t.height, ow = job.mid_width;
    const int tiles = (ow + 15) / 16;
    ThreadScratch& sc = thread_scratch();
    sc.line.reserve(w);
    sc.reserve_row(ow);
    LineSoA& s = sc.line.soa;
    uint32_t* mid = job.mid;
    float* mid_v = job.mid_v;
    long long dropped = 0;
    for (int r = r0; r < r1; ++r) {
        dropped += prepare_row(t, tab, job.extent, ow, r, s);
        LineOut out{sc.row_c, sc.row_v, ow};
        std::memset(sc.row_c, 0, size_t(tiles) * 64);
        warp_line_fast<true>(s, job.split_u, out, NoRange{});
        // Into the column tiles: one 64-byte line per tile and image.
        for (int b = 0; b < tiles; ++b) {
            const size_t off = (size_t(b) * size_t(h) + size_t(r)) * 16;
            _mm512_store_si512(mid + off, _mm512_load_si512(sc.row_c + 16 * b));
            _mm512_store_ps(mid_v + off, _mm512_load_ps(sc.row_v + 16 * b));
        }
    }
    if (dropped) *job.dropped += dropped;
}

void vertical_columns(const TwoPassJob& job, int x0, int x1) {
    const int h = job.relief->height, ow = job.mid_width, oh = job.out->height;
    ThreadScratch& sc = thread_scratch();
    sc.line.reserve(h);
    sc.reserve_columns(h, oh);
    LineSoA& s = sc.line.soa;
    const size_t is = sc.in_stride, os = sc.out_stride;
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    for (int xb = x0; xb < x1; xb += 16) {
        const int nb = imin(16, x1 - xb);
        const __mmask16 cm = first_lanes(nb);
        const uint32_t* tile_c = job.mid + size_t(xb) * size_t(h);
        const float* tile_v = job.mid_v + size_t(xb) * size_t(h);
        // Transpose in: line c, sample j (v order, j = 0 the bottom row) = intermediate (xb + c, h - 1 - j).
        for (int j0 = 0; j0 < h; j0 += 16) {
            const int nj = imin(16, h - j0);
            __m512i tc[16], tv[16];
            for (int i = 0; i < 16; ++i) {
                if (i < nj) {
                    const size_t off = size_t(h - 1 - j0 - i) * 16;
                    tc[i] = _mm512_load_si512(tile_c + off);
                    tv[i] = _mm512_castps_si512(_mm512_load_ps(tile_v + off));
                } else {
                    tc[i] = _mm512_setzero_si512();
                    tv[i] = _mm512_setzero_si512();
                }
            }
            transpose16(tc);
            transpose16(tv);
            for (int c = 0; c < nb; ++c) {
                _mm512_store_si512(sc.col_t + c * is + j0, tc[c]);
                _mm512_store_si512(reinterpret_cast<int32_t*>(sc.v_t) + c * is + j0, tv[c]);
            }
        }
        for (int c = 0; c < nb; ++c) {
            const uint32_t* lc = sc.col_t + c * is;
            const float* lv = sc.v_t + c * is;
            LineWriter lw(s, h, oh);
            for (int j = 0; j < h; j += 16) {
                const __m512i d = _mm512_load_si512(lc + j);
                // A sample takes part when something landed there (alpha != 0).
                lw.put<false>(_mm512_load_ps(lv + j), d, _mm512_setzero_ps(),
                              _mm512_test_epi32_mask(d, _mm512_set1_epi32(int(0xFF000000))));
            }
            lw.finish();
            LineOut lo{sc.out_t + c * os, nullptr, oh};
            std::memset(lo.color, 0, os * 4);
            warp_line_fast<false>(s, job.split_v, lo, NoRange{});
        }
        // Transpose out: output row oh - 1 - y, columns xb .. xb + nb - 1 = lines 0 .. nb - 1 at y.
        for (int y0 = 0; y0 < oh; y0 += 16) {
            const int ny = imin(16, oh - y0);
            __m512i tc[16];
            for (int c = 0; c < 16; ++c)
                tc[c] = c < nb ? _mm512_load_si512(sc.out_t + c * os + y0) : _mm512_setzero_si512();
            transpose16(tc);
            for (int i = 0; i < ny; ++i)
                _mm512_mask_storeu_epi32(out + size_t(oh - 1 - y0 - i) * size_t(ow) + size_t(xb), cm, tc[i]);
        }
    }
}

}  // namespace fast
}  // namespace rtm

#pragma GCC diagnostic pop
#pragma GCC pop_options
