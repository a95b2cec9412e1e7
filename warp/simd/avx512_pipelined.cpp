// The fast pipelined pre-warp kernel (see simd/avx512_pipelined.h). Compiled with -ffp-contract=off
// (warp/CMakeLists.txt): the pixel identity with the reference rests on every float operation being the one the
// reference performs.
#include "warp/simd/avx512_pipelined.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <utility>

#include "warp/line_warp.h"
#include "warp/simd/schedule.h"

#include "warp/simd/avx512_target_begin.h"
#include "warp/simd/avx512_line.h"
#include "warp/simd/avx512_row.h"
#include "warp/simd/avx512_columns.h"

namespace rtm {
namespace {

// The emissions of one row in the order of the row warp, 16 adjacent columns x .. x + 15 a chunk (lanes `fin`).
struct EmitLog {
    struct alignas(64) Chunk {
        float v[16];
        uint32_t c[16];
    };
    Chunk* chunk = nullptr;
    int32_t* x = nullptr;
    __mmask16* fin = nullptr;
    size_t n = 0, cap = 0;

    EmitLog() = default;
    EmitLog(const EmitLog&) = delete;
    EmitLog& operator=(const EmitLog&) = delete;
    ~EmitLog() { std::free(chunk); }
    // Grows while the longest row is first seen, never shrinks.
    __attribute__((noinline)) void reserve(size_t want) {
        if (want <= cap) return;
        const size_t c = std::max(want, 2 * cap);
        char* p = static_cast<char*>(alloc64(c * (sizeof(Chunk) + 4 + 2)));
        Chunk* nc = reinterpret_cast<Chunk*>(p);
        int32_t* nx = reinterpret_cast<int32_t*>(p + c * sizeof(Chunk));
        __mmask16* nf = reinterpret_cast<__mmask16*>(p + c * (sizeof(Chunk) + 4));
        if (n) {
            std::memcpy(static_cast<void*>(nc), chunk, n * sizeof(Chunk));
            std::memcpy(nx, x, n * 4);
            std::memcpy(nf, fin, n * 2);
        }
        std::free(chunk);
        chunk = nc, x = nx, fin = nf, cap = c;
    }
};

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
    // Reverse mode (see reverse_rows): the final samples of the row warped last, the output rows already written
    // per column ([clo, chi], empty when clo > chi) or, in columns where that is not one interval (cbits set), a
    // bitmask of them (nw words per column), and two rows' emissions.
    float* fin_v = nullptr;
    uint32_t* fin_c = nullptr;
    uint8_t* fin_ok = nullptr;
    int32_t* clo = nullptr;
    int32_t* chi = nullptr;
    uint8_t* cbits = nullptr;
    uint64_t* bits = nullptr;
    size_t bits_cap = 0;  // words
    int nw = 0;
    EmitLog log[2];
    // Measuring the pixels the spans of a row cover (Emitter).
    bool measure = false;
    __m512 drawn = _mm512_setzero_ps();
    __m512 cap = _mm512_setzero_ps();
    // Row chunks drawing into a scratch image: the range of the finite row coordinates emitted (ClipRange).
    bool track = false;
    __m512 vmin = _mm512_setzero_ps();
    __m512 vmax = _mm512_setzero_ps();

    PipeScratch() = default;
    PipeScratch(const PipeScratch&) = delete;
    PipeScratch& operator=(const PipeScratch&) = delete;
    ~PipeScratch() {
        std::free(block);
        std::free(block2);
        std::free(bits);
    }
    void* block2 = nullptr;
    size_t capacity2 = 0;
    void reserve_reverse(int ow, int oh) {
        if (size_t(ow) > capacity2) {
            std::free(block2);
            capacity2 = (size_t(ow) + 63) & ~size_t(63);
            const size_t n = capacity2 + 64;
            block2 = alloc64(n * 4 * 4 + n * 2);
            std::memset(block2, 0, n * 4 * 4 + n * 2);
            char* p = static_cast<char*>(block2);
            fin_v = reinterpret_cast<float*>(p);
            fin_c = reinterpret_cast<uint32_t*>(p + n * 4);
            clo = reinterpret_cast<int32_t*>(p + n * 8);
            chi = reinterpret_cast<int32_t*>(p + n * 12);
            fin_ok = reinterpret_cast<uint8_t*>(p + n * 16);
            cbits = reinterpret_cast<uint8_t*>(p + n * 17);
        }
        nw = (oh + 63) / 64;
        const size_t words = size_t(ow) * size_t(nw);
        if (words > bits_cap) {
            std::free(bits);
            bits = static_cast<uint64_t*>(alloc64(words * 8));
            bits_cap = words;
        }
        for (EmitLog& l : log) l.reserve(size_t(ow) / 8 + 64);
    }
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

// Whether every lane of `fin` is a still step: connected (pok) to the column's previous sample exactly one row
// before (|v - pv| == 1), the new sample on the centre of v-row y = v - 0.5, the same y in every lane, inside
// [y0, y1). raster_span then writes the one pixel y of each column with t = 1 exactly, lerp8 at t = 1 gives the
// new colour: the step is a copy (the Highway kernels' StillStep, warp/simd/hwy_columns-inl.h, says why).
inline bool still_step(const ColumnOut& o, __mmask16 fin, __mmask16 pok, __m512 pv, __m512 v, int& y) {
    if (pok != fin) return false;
    const float v0 = _mm_cvtss_f32(_mm512_castps512_ps128(_mm512_permutexvar_ps(_mm512_set1_epi32(int(_tzcnt_u32(fin))),
                                                                                v)));
    const __mmask16 step = _mm512_mask_cmp_ps_mask(fin, _mm512_abs_ps(_mm512_sub_ps(v, pv)), _mm512_set1_ps(1.0f),
                                                   _CMP_EQ_OQ);
    if ((step & _mm512_mask_cmp_ps_mask(fin, v, _mm512_set1_ps(v0), _CMP_EQ_OQ)) != fin) return false;
    const float yf = v0 - 0.5f;
    if (!(yf >= float(o.y0) && yf < float(o.y1)) || std::floor(yf) != yf) return false;
    y = int(yf);
    return float(y) + 0.5f == v0;  // the pixel centre the span's arithmetic computes is v itself
}

// What the reference's put() does for each pixel the row warp emits, for columns [xa, xb] at once: connect the
// column's previous sample to the new one with raster_span (or start with raster_point), writing only output
// v-rows [y0, y1), and make the new sample the column's current one.
// With `copy` (PrewarpOptions::copy_still_runs), still steps are copies (still_step).
struct Emitter {
    PipeScratch& sc;
    ColumnOut o;
    bool copy = false;

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
            int ys;
            if (copy && still_step(o, fin, pok, pv, v, ys))
                _mm512_mask_storeu_epi32(o.vline(ys) + x, fin, _mm512_or_si512(c, _mm512_set1_epi32(int(0xFF000000u))));
            else
                column_spans(o, x, fin, pok, pv, pc, v, c);
            if (sc.measure) [[unlikely]]
                sc.drawn = _mm512_mask_add_ps(sc.drawn, pok, sc.drawn,
                                              _mm512_min_ps(_mm512_abs_ps(_mm512_sub_ps(v, pv)), sc.cap));
        }
    }
};

// A row whose spans cover more than this many pixels per column switches the rest of the part to reverse mode
// (reverse_rows).
constexpr float kReverseDrawn = 3.0f;

// Reverse mode: the row's emissions into a log, and each column's last one into fin_*.
struct Logger {
    PipeScratch& sc;
    EmitLog& log;

    void operator()(int xa, int xb) const {
        const size_t want = log.n + size_t((xb - xa) / 16 + 1);
        if (want > log.cap) [[unlikely]]
            log.reserve(want);
        for (int x = xa; x <= xb; x += 16) {
            const __mmask16 m = first_lanes(xb - x + 1);
            const __m512 v = _mm512_maskz_loadu_ps(m, sc.row_v + x);
            const __m512i c = _mm512_maskz_loadu_epi32(m, sc.row_c + x);
            const __mmask16 fin = m & ~nonfinite(v);
            if (!fin) continue;
            EmitLog::Chunk& k = log.chunk[log.n];
            _mm512_store_ps(k.v, v);
            _mm512_store_si512(k.c, c);
            log.x[log.n] = x;
            log.fin[log.n] = fin;
            ++log.n;
            _mm512_mask_storeu_ps(sc.fin_v + x, fin, v);
            _mm512_mask_storeu_epi32(sc.fin_c + x, fin, c);
            _mm_mask_storeu_epi8(sc.fin_ok + x, fin, _mm_set1_epi8(1));
        }
    }
};

// Reverse mode, for the lanes `fb` of column_spans_rev whose pixels ylo .. yhi (lanes `span`: of a span, else a
// point) are not one interval with the rows their column already has: the column's bitmask (made from its interval
// the first time), and the runs of pixels not yet written one lane at a time.
__attribute__((noinline)) void column_bits(const ColumnOut& o, PipeScratch& sc, int x, __mmask16 fb, __mmask16 span,
                                           const __m512i& ylo, const __m512i& yhi, const __m512& pv, const __m512i& pc,
                                           const __m512& v, const __m512i& c) {
    alignas(64) int32_t lo[16], hi[16];
    _mm512_store_si512(lo, ylo);
    _mm512_store_si512(hi, yhi);
    for (__mmask16 l = fb; l; l &= __mmask16(l - 1)) {
        const int i = int(_tzcnt_u32(l));
        const __mmask16 lane = __mmask16(1u << i);
        uint64_t* w = sc.bits + size_t(x + i) * size_t(sc.nw);
        auto set_range = [&](int a, int b, bool draw) {  // rows a .. b (a <= b) set; the ones that were not drawn
            for (int q = a >> 6; q <= b >> 6; ++q) {
                const int s = imax(a, q * 64) - q * 64, e = imin(b, q * 64 + 63) - q * 64;
                const uint64_t rm = (~uint64_t(0) >> (63 - e)) & (~uint64_t(0) << s);
                uint64_t todo = draw ? rm & ~w[q] : 0;
                w[q] |= rm;
                while (todo) {
                    const int r0 = int(_tzcnt_u64(todo));
                    const uint64_t rest = ~(todo >> r0);
                    const int len = rest ? int(_tzcnt_u64(rest)) : 64 - r0;
                    column_pixels(o, x, span & lane, lane & __mmask16(~span), _mm512_set1_epi32(q * 64 + r0),
                                  _mm512_set1_epi32(q * 64 + r0 + len - 1), pv, pc, v, c);
                    todo &= len == 64 ? 0 : ~(((uint64_t(1) << len) - 1) << r0);
                }
            }
        };
        if (!sc.cbits[x + i]) {
            sc.cbits[x + i] = 1;
            std::memset(w, 0, size_t(sc.nw) * 8);
            if (sc.clo[x + i] <= sc.chi[x + i]) set_range(sc.clo[x + i], sc.chi[x + i], false);
        }
        set_range(lo[i], hi[i], true);
    }
}

// column_spans in reverse mode: writes only the pixels no emission replayed before has written, and records them.
// With `copy`, still steps (still_step) whose row lies in, or next to, every column's interval (no bitmask) are one
// masked row store of the lanes whose interval does not hold the row yet.
inline void column_spans_rev(const ColumnOut& o, PipeScratch& sc, int x, bool copy, __mmask16 fin, __mmask16 pok,
                             __m512 pv, __m512i pc, __m512 v, __m512i c) {
    int ys;
    if (copy && still_step(o, fin, pok, pv, v, ys)) {
        const __m512i y = _mm512_set1_epi32(ys), one = _mm512_set1_epi32(1);
        const __m512i clo = _mm512_loadu_si512(sc.clo + x), chi = _mm512_loadu_si512(sc.chi + x);
        const __m128i cb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(sc.cbits + x));
        const __mmask16 emp = _mm512_cmpgt_epi32_mask(clo, chi);
        const __mmask16 inside = __mmask16(~emp) & _mm512_cmple_epi32_mask(clo, y) & _mm512_cmple_epi32_mask(y, chi);
        const __mmask16 next_to = emp | _mm512_cmpeq_epi32_mask(y, _mm512_sub_epi32(clo, one)) |
                                  _mm512_cmpeq_epi32_mask(y, _mm512_add_epi32(chi, one));
        if (!(_mm_test_epi8_mask(cb, cb) & fin) && ((inside | next_to) & fin) == fin) {
            const __mmask16 go = fin & __mmask16(~inside);
            _mm512_mask_storeu_epi32(sc.clo + x, go, _mm512_mask_mov_epi32(_mm512_min_epi32(y, clo), emp, y));
            _mm512_mask_storeu_epi32(sc.chi + x, go, _mm512_mask_mov_epi32(_mm512_max_epi32(y, chi), emp, y));
            _mm512_mask_storeu_epi32(o.vline(ys) + x, go, _mm512_or_si512(c, _mm512_set1_epi32(int(0xFF000000u))));
            return;
        }
    }
    const auto [span, point, ylo, yhi] = column_rows(o, fin, pok, pv, v);
    const __mmask16 todo = (span | point) & _mm512_cmple_epi32_mask(ylo, yhi);
    if (!todo) return;
    const __m512i clo = _mm512_loadu_si512(sc.clo + x), chi = _mm512_loadu_si512(sc.chi + x);
    const __m128i cb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(sc.cbits + x));
    const __m512i one_i = _mm512_set1_epi32(1);
    const __mmask16 emp = _mm512_cmpgt_epi32_mask(clo, chi);
    const __mmask16 inside = _mm512_mask_cmpge_epi32_mask(__mmask16(~emp), ylo, clo) &
                             _mm512_cmple_epi32_mask(yhi, chi);
    const __mmask16 apart = __mmask16(~emp) & (_mm512_cmplt_epi32_mask(yhi, _mm512_sub_epi32(clo, one_i)) |
                                               _mm512_cmpgt_epi32_mask(ylo, _mm512_add_epi32(chi, one_i)));
    const __mmask16 fb = todo & (_mm_test_epi8_mask(cb, cb) | apart);
    const __mmask16 go = todo & __mmask16(~fb) & __mmask16(~inside);
    if (go) {
        _mm512_mask_storeu_epi32(sc.clo + x, go, _mm512_mask_mov_epi32(_mm512_min_epi32(ylo, clo), emp, ylo));
        _mm512_mask_storeu_epi32(sc.chi + x, go, _mm512_mask_mov_epi32(_mm512_max_epi32(yhi, chi), emp, yhi));
        // Below the interval (everything where the column has none), above it, or both.
        const __mmask16 low = go & (emp | _mm512_cmplt_epi32_mask(ylo, clo));
        const __mmask16 high = go & __mmask16(~emp) & _mm512_cmpgt_epi32_mask(yhi, chi);
        if (low)
            column_pixels(o, x, span & low, point & low, ylo,
                          _mm512_mask_mov_epi32(_mm512_min_epi32(yhi, _mm512_sub_epi32(clo, one_i)), emp, yhi), pv, pc,
                          v, c);
        if (high)
            column_pixels(o, x, span & high, point & high, _mm512_max_epi32(ylo, _mm512_add_epi32(chi, one_i)), yhi, pv,
                          pc, v, c);
    }
    if (fb) [[unlikely]]
        column_bits(o, sc, x, fb, span, ylo, yhi, pv, pc, v, c);
}

// Widens sc.vmin and sc.vmax by the finite row coordinates of columns a .. b of the row buffer: the rows a scratch
// chunk may have written, so that the composite reads only those (1024^2: 505 to 659 of the 1024 rows for the
// second of two chunks). Called by ClipRange, not in the Emitter, so that the code without chunks is unchanged.
__attribute__((noinline)) void track_rows(PipeScratch& sc, int a, int b) {
    for (int x = a; x <= b; x += 16) {
        const __mmask16 m = first_lanes(b - x + 1);
        const __m512 v = _mm512_maskz_loadu_ps(m, sc.row_v + x);
        const __mmask16 fin = m & ~nonfinite(v);
        sc.vmin = _mm512_mask_min_ps(sc.vmin, fin, sc.vmin, v);
        sc.vmax = _mm512_mask_max_ps(sc.vmax, fin, sc.vmax, v);
    }
}

template <class E>
struct ClipRange {
    const E& emit;
    int x0, x1;                    // columns [x0, x1)
    PipeScratch* track = nullptr;  // records the emitted row coordinates (track_rows) when not null
    void operator()(int a, int b) const {
        a = imax(a, x0);
        b = imin(b, x1 - 1);
        if (a > b) return;
        if (track) track_rows(*track, a, b);
        emit(a, b);
    }
};

// The rows a task warps: first, first + step, .. up to end (exclusive) of part `part` (step 1 for part 0, -1 for
// part 1), columns [x0, x1); `seam`: the task holds the part's last rows and records the seam.
struct RowTask {
    int part = 0;
    int first = 0, end = 0, step = 1;
    int x0 = 0, x1 = 0;
    bool seam = true;
};

// A part's rows and output rows: part 0 warps relief rows 0, 1, .. split_v - 1 into output v-rows [0, ysplit),
// part 1 rows h - 1, h - 2, .. split_v into [ysplit, out height); `count` rows in all.
struct PartRows {
    int first, step, count;
    int y0, y1;
};

PartRows part_rows(const fast::PipelinedJob& job, int part) {
    const int h = job.relief->height, s = job.split_v;
    if (part == 0) return {0, 1, s, 0, job.ysplit};
    return {h - 1, -1, h - s, job.ysplit, job.out->height};
}

// The task of rows [r0, r1) of a part, counted in the part's order, columns [x0, x1).
RowTask part_task(const fast::PipelinedJob& job, int part, int r0, int r1, int x0, int x1) {
    const PartRows p = part_rows(job, part);
    RowTask k;
    k.part = part;
    k.step = p.step;
    k.first = p.first + p.step * r0;
    k.end = p.first + p.step * r1;
    k.x0 = x0;
    k.x1 = x1;
    k.seam = r1 == p.count;
    return k;
}

// Prepares row j and warps it into the row buffer, the emissions in columns [x0, x1) going to `emit`; returns the
// texels prepare_row dropped. Row `next` (the one warped after it) is prefetched.
template <class E>
long long warp_row(const fast::PipelinedJob& job, PipeScratch& sc, int j, int next, int x0, int x1, const E& emit) {
    const ReliefTexture& t = *job.relief;
    const int ow = job.out->width;
    prefetch_relief_row(t, t.height - 1 - next);
    const long long d = prepare_row(t, *job.tables, job.extent, ow, t.height - 1 - j, sc.line.soa);
    LineOut lo{sc.row_c, sc.row_v, ow, x0, x1 - 1};
    lo.copy = job.copy_still;
    warp_line_fast<true>(sc.line.soa, job.split_u, lo, ClipRange<E>{emit, x0, x1, sc.track ? &sc : nullptr});
    return d;
}

// The seam's samples of columns [x0, x1): each column's last sample of the part, alpha 0 where it has none.
void record_seam(const fast::PipelinedJob& job, int part, int x0, int x1, const float* v, const uint32_t* c,
                 const uint8_t* ok) {
    for (int x = x0; x < x1; ++x) {
        job.seam_v[part][x] = v[x];
        job.seam_c[part][x] = ok[x] ? (c[x] | 0xFF000000u) : 0u;
    }
}

// Reverse mode for rows `from` .. end - step (by `step`) of a part, the last ones: the painter's algorithm
// backwards. Row j's emissions are replayed in reverse order after row j - step has been warped (its final samples
// are the ones row j's spans start from), the rows from the last one back to `from` (whose spans start from the
// final samples in prev_*, of the rows before, drawn forwards), and each pixel is written only by the first
// emission that reaches it, which is the last in the forward order: the same image, each pixel written once where
// the forward order writes it again and again. Each column keeps the interval of output rows written so far: the
// spans of a row all start at the sample the next row's spans start from, so they usually extend it; columns
// where a span lands apart from it (points, gaps, a sample on a pixel centre with spans on both sides) switch to a
// bitmask of the rows written (column_bits).
// Why: the forward order wrote ridges 1024^2's 1.04 M output pixels 77 M times, mostly by long spans that later
// rows overwrite. Measured (1 thread, median ms of 3 interleaved rounds of `rtm bench --no-exact --no-reference`,
// before -> after; two-pass, unchanged, for comparison): bumps 256^2 0.160 -> 0.146, 1024^2 4.17 -> 3.96 (5 rounds,
// noise about +-0.5; bumps never switches); bricks 256^2 0.299 -> 0.285, 1024^2 4.39 -> 3.43 (two-pass 2.6 to 2.8);
// ridges 256^2 1.03 -> 0.51 (two-pass 0.40), 1024^2 56.9 -> 8.2 (two-pass 6.7 to 7.0).
__attribute__((noinline)) void reverse_rows(const fast::PipelinedJob& job, PipeScratch& sc, const ColumnOut& o_fwd,
                                            const RowTask& k, int from, long long& dropped) {
    // The rows move the other way (prefetching ahead of them, behind them or not at all measured the same on ridges
    // 256^2 and 1024^2).
    ColumnOut o = o_fwd;
    o.ahead = -o.ahead;
    const int step = k.step, x0 = k.x0, x1 = k.x1;
    sc.reserve_reverse(o.ow, o.oh);
    std::fill(sc.clo + x0, sc.clo + x1, 1 << 30);
    std::fill(sc.chi + x0, sc.chi + x1, -(1 << 30));
    std::memset(sc.cbits + x0, 0, size_t(x1 - x0));
    auto warp = [&](int j, EmitLog& log) {
        std::memset(sc.fin_ok + x0, 0, size_t(x1 - x0));
        log.n = 0;
        const long long d = warp_row(job, sc, j, j - step, x0, x1, Logger{sc, log});
        if (x0 == 0) dropped += d;
    };
    const int last = k.end - step;
    warp(last, sc.log[0]);
    if (k.seam) record_seam(job, k.part, x0, x1, sc.fin_v, sc.fin_c, sc.fin_ok);
    int cur = 0;
    for (int j = last;; j -= step) {
        const float* pv = sc.prev_v;
        const uint32_t* pc = sc.prev_c;
        const uint8_t* pok = sc.prev_ok;
        if (j != from) {
            warp(j - step, sc.log[cur ^ 1]);
            pv = sc.fin_v, pc = sc.fin_c, pok = sc.fin_ok;
        }
        const EmitLog& log = sc.log[cur];
        for (size_t i = log.n; i-- > 0;) {
            const int x = log.x[i];
            const __mmask16 fin = log.fin[i];
            const __m128i okb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(pok + x));
            column_spans_rev(o, sc, x, job.copy_still, fin, fin & _mm_test_epi8_mask(okb, okb), _mm512_loadu_ps(pv + x),
                             _mm512_loadu_si512(pc + x), _mm512_load_ps(log.chunk[i].v),
                             _mm512_load_si512(log.chunk[i].c));
        }
        if (j == from) break;
        cur ^= 1;
    }
}

void swap_rows(PipeScratch& sc) {
    std::swap(sc.prev_v, sc.cur_v);
    std::swap(sc.prev_c, sc.cur_c);
    std::swap(sc.prev_ok, sc.cur_ok);
}

// The range of finite row coordinates a task emitted (lo > hi: none).
struct RowRange {
    float lo, hi;
};

// Runs task k, drawing into `pixels` (the output's size; output v-rows of the part only). A task that does not
// start at its part's first row starts from the row before it, warped without drawing: the column state after it
// (each column's last emission of that row) is exactly the one the forward order carries into the task's first
// row, forwards or in reverse mode. With `track`, returns the range of row coordinates emitted, the row before
// included.
RowRange run_rows(const fast::PipelinedJob& job, const RowTask& k, uint32_t* pixels, bool track) {
    const int ow = job.out->width, oh = job.out->height;
    const PartRows part = part_rows(job, k.part);
    const int y0 = part.y0, y1 = part.y1;
    PipeScratch& sc = pipe_scratch();
    sc.reserve(ow);
    sc.line.reserve(job.relief->width);
    std::memset(sc.prev_ok, 0, size_t(ow));
    sc.cap = _mm512_set1_ps(float(oh));
    sc.track = track;
    sc.vmin = _mm512_set1_ps(std::numeric_limits<float>::infinity());
    sc.vmax = _mm512_set1_ps(-std::numeric_limits<float>::infinity());
    // The output lines 8 rows ahead of the ones written are prefetched, as in the two-pass kernel: bumps 4096^2, one
    // thread (an output of 64 MiB, past the caches), median of 7 pre-warps, 3 interleaved runs: 129 to 133 -> 113
    // to 118 ms; 2, 16 and 32 rows ahead in between; 256^2 and 1024^2 within the noise.
    const Emitter emit{sc, ColumnOut{pixels, ow, oh, y0, y1, 8 * k.step}, job.copy_still};
    if (k.first != part.first) {
        // The row before, drawn into no output rows (y0 to y0).
        std::memset(sc.cur_ok + k.x0, 0, size_t(k.x1 - k.x0));
        warp_row(job, sc, k.first - k.step, k.first, k.x0, k.x1, Emitter{sc, ColumnOut{pixels, ow, oh, y0, y0}});
        swap_rows(sc);
    }
    long long dropped = 0;
    bool reversed = false;
    if (job.reverse == KernelChoice::always) {
        reverse_rows(job, sc, emit.o, k, k.first, dropped);
        reversed = true;
    }
    for (int j = k.first; !reversed && j != k.end; j += k.step) {
        std::memset(sc.cur_ok + k.x0, 0, size_t(k.x1 - k.x0));
        // Every 4th row measures how many pixels its spans cover per column (at most oh each).
        sc.measure = job.reverse == KernelChoice::automatic && (j & 3) == 0 && j + k.step != k.end;
        sc.drawn = _mm512_setzero_ps();
        const long long d = warp_row(job, sc, j, j + k.step, k.x0, k.x1, emit);
        if (k.x0 == 0) dropped += d;
        const bool rev = sc.measure && _mm512_reduce_add_ps(sc.drawn) > kReverseDrawn * float(k.x1 - k.x0);
        sc.measure = false;
        swap_rows(sc);
        if (rev) {
            reverse_rows(job, sc, emit.o, k, j + k.step, dropped);
            reversed = true;
        }
    }
    if (!reversed && k.seam) record_seam(job, k.part, k.x0, k.x1, sc.prev_v, sc.prev_c, sc.prev_ok);
    if (dropped) *job.dropped += dropped;
    sc.track = false;
    return {_mm512_reduce_min_ps(sc.vmin), _mm512_reduce_max_ps(sc.vmax)};
}

// Clears output v-rows of the part, columns [x0, x1).
void clear_part(const fast::PipelinedJob& job, int part, int x0, int x1) {
    const int ow = job.out->width, oh = job.out->height;
    const PartRows p = part_rows(job, part);
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    for (int y = p.y0; y < p.y1; ++y)
        std::memset(out + size_t(oh - 1 - y) * size_t(ow) + size_t(x0), 0, size_t(x1 - x0) * 4);
}

}  // namespace

namespace fast {

void pipelined_part(const PipelinedJob& job, int part, int x0, int x1) {
    clear_part(job, part, x0, x1);
    run_rows(job, part_task(job, part, 0, part_rows(job, part).count, x0, x1),
             reinterpret_cast<uint32_t*>(job.out->pixels.data()), false);
}

void pipelined_chunk(const PipelinedJob& job, PipelinedChunk& c) {
    const int ow = job.out->width;
    const RowTask k = part_task(job, c.part, c.r0, c.r1, 0, ow);
    if (c.r0 == 0) {
        clear_part(job, c.part, 0, ow);
        run_rows(job, k, reinterpret_cast<uint32_t*>(job.out->pixels.data()), false);
        c.ylo = c.yhi = 0;
        return;
    }
    const RowRange r = run_rows(job, k, reinterpret_cast<uint32_t*>(c.scratch->pixels.data()), true);
    // Every pixel written lies in v-rows floor(lo) .. floor(hi) (column_rows: a span's rows between its ends'
    // centres, a point's int(v)); one row more on each side for safety.
    const PartRows p = part_rows(job, c.part);
    const int y0 = p.y0, y1 = p.y1;
    auto clamp_row = [&](double y) { return int(std::clamp(y, double(y0), double(y1))); };
    c.ylo = r.lo <= r.hi ? clamp_row(std::floor(double(r.lo)) - 1.0) : y0;
    c.yhi = r.lo <= r.hi ? clamp_row(std::floor(double(r.hi)) + 2.0) : y0;
}

void pipelined_composite(const PipelinedJob& job, const PipelinedChunk* chunks, int n, int y0, int y1) {
    const int ow = job.out->width, oh = job.out->height;
    uint32_t* out = reinterpret_cast<uint32_t*>(job.out->pixels.data());
    const __m512i alpha = _mm512_set1_epi32(int(0xFF000000u));
    for (int i = 0; i < n; ++i) {
        const PipelinedChunk& c = chunks[i];
        if (c.r0 == 0) continue;
        uint32_t* scratch = reinterpret_cast<uint32_t*>(c.scratch->pixels.data());
        for (int y = imax(y0, c.ylo); y < imin(y1, c.yhi); ++y) {
            uint32_t* o = out + size_t(oh - 1 - y) * size_t(ow);
            uint32_t* q = scratch + size_t(oh - 1 - y) * size_t(ow);
            for (int x = 0; x < ow; x += 16) {
                const __m512i p = _mm512_maskz_loadu_epi32(first_lanes(ow - x), q + x);
                // Only the pixels written are stored, and cleared in the scratch: the rest are 0 already.
                const __mmask16 written = _mm512_test_epi32_mask(p, alpha);
                _mm512_mask_storeu_epi32(o + x, written, p);
                _mm512_mask_storeu_epi32(q + x, written, _mm512_setzero_si512());
            }
        }
    }
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

#include "warp/simd/avx512_target_end.h"
