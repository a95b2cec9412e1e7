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
#pragma GCC target("avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi,avx512vnni,bmi,bmi2,lzcnt,popcnt,prfchw")
#include "warp/fast_line.h"
#include "warp/fast_row.h"
#include "warp/fast_columns.h"

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

// What the reference's put() does for each pixel the row warp emits, for columns [xa, xb] at once: connect the
// column's previous sample to the new one with raster_span (or start with raster_point), writing only output
// v-rows [y0, y1), and make the new sample the column's current one.
struct Emitter {
    PipeScratch& sc;
    ColumnOut o;

    void operator()(int xa, int xb) const {
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
            column_spans(o, x, fin, pok, pv, pc, v, c);
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
    const Emitter emit{sc, ColumnOut{out, ow, oh, y0, y1}};
    long long dropped = 0;
    for (int j = first; j != end; j += step) {
        const int r = h - 1 - j;
        const long long d = prepare_row(t, *job.tables, job.extent, ow, r, s);
        if (x0 == 0) dropped += d;
        std::memset(sc.cur_ok + x0, 0, size_t(x1 - x0));
        LineOut lo{sc.row_c, sc.row_v, ow, x0, x1 - 1};
        lo.copy = job.copy_still;
        warp_line_fast<true>(s, job.split_u, lo, ClipRange{emit, x0, x1});
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
