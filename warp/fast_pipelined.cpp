// The fast pipelined pre-warp kernel (see fast_pipelined.h). Compiled with -ffp-contract=off (warp/CMakeLists.txt):
// the pixel identity with the reference rests on every float operation being the one the reference performs.
#include "warp/fast_pipelined.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "warp/line_warp.h"

#include "warp/fast_target_begin.h"
#include "warp/fast_line.h"
#include "warp/fast_row.h"
#include "warp/fast_columns.h"

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
        if (want > log.cap) [[unlikely]] log.reserve(want);
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
                                           const __m512i& ylo, const __m512i& yhi, const __m512& pv,
                                           const __m512i& pc, const __m512& v, const __m512i& c) {
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
inline void column_spans_rev(const ColumnOut& o, PipeScratch& sc, int x, __mmask16 fin, __mmask16 pok, __m512 pv,
                             __m512i pc, __m512 v, __m512i c) {
    const auto [span, point, ylo, yhi] = column_rows(o, fin, pok, pv, v);
    const __mmask16 todo = (span | point) & _mm512_cmple_epi32_mask(ylo, yhi);
    if (!todo) return;
    const __m512i clo = _mm512_loadu_si512(sc.clo + x), chi = _mm512_loadu_si512(sc.chi + x);
    const __m128i cb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(sc.cbits + x));
    const __m512i one_i = _mm512_set1_epi32(1);
    const __mmask16 emp = _mm512_cmpgt_epi32_mask(clo, chi);
    const __mmask16 inside =
        _mm512_mask_cmpge_epi32_mask(__mmask16(~emp), ylo, clo) & _mm512_cmple_epi32_mask(yhi, chi);
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
            column_pixels(o, x, span & high, point & high, _mm512_max_epi32(ylo, _mm512_add_epi32(chi, one_i)), yhi,
                          pv, pc, v, c);
    }
    if (fb) [[unlikely]] column_bits(o, sc, x, fb, span, ylo, yhi, pv, pc, v, c);
}

template <class E>
struct ClipRange {
    const E& emit;
    int x0, x1;  // columns [x0, x1)
    void operator()(int a, int b) const {
        a = imax(a, x0);
        b = imin(b, x1 - 1);
        if (a <= b) emit(a, b);
    }
};

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
__attribute__((noinline)) void reverse_rows(const fast::PipelinedJob& job, PipeScratch& sc, const ColumnOut& o,
                                            int part, int from, int end, int step, int x0, int x1,
                                            long long& dropped) {
    const ReliefTexture& t = *job.relief;
    const int h = t.height, ow = o.ow;
    LineSoA& s = sc.line.soa;
    sc.reserve_reverse(ow, o.oh);
    std::fill(sc.clo + x0, sc.clo + x1, 1 << 30);
    std::fill(sc.chi + x0, sc.chi + x1, -(1 << 30));
    std::memset(sc.cbits + x0, 0, size_t(x1 - x0));
    auto warp = [&](int j, EmitLog& log) {
        const long long d = prepare_row(t, *job.tables, job.extent, ow, h - 1 - j, s);
        if (x0 == 0) dropped += d;
        std::memset(sc.fin_ok + x0, 0, size_t(x1 - x0));
        log.n = 0;
        LineOut lo{sc.row_c, sc.row_v, ow, x0, x1 - 1};
        lo.copy = job.copy_still;
        const Logger lg{sc, log};
        warp_line_fast<true>(s, job.split_u, lo, ClipRange<Logger>{lg, x0, x1});
    };
    const int last = end - step;
    warp(last, sc.log[0]);
    for (int x = x0; x < x1; ++x) {
        job.seam_v[part][x] = sc.fin_v[x];
        job.seam_c[part][x] = sc.fin_ok[x] ? (sc.fin_c[x] | 0xFF000000u) : 0u;
    }
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
            column_spans_rev(o, sc, x, fin, fin & _mm_test_epi8_mask(okb, okb), _mm512_loadu_ps(pv + x),
                             _mm512_loadu_si512(pc + x), _mm512_load_ps(log.chunk[i].v),
                             _mm512_load_si512(log.chunk[i].c));
        }
        if (j == from) break;
        cur ^= 1;
    }
}

}  // namespace

namespace fast {

int pipelined_reverse = 0;

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
    sc.cap = _mm512_set1_ps(float(oh));
    const Emitter emit{sc, ColumnOut{out, ow, oh, y0, y1}};
    long long dropped = 0;
    if (first != end && pipelined_reverse == 1) {
        reverse_rows(job, sc, emit.o, part, first, end, step, x0, x1, dropped);
        if (dropped) *job.dropped += dropped;
        return;
    }
    for (int j = first; j != end; j += step) {
        const int r = h - 1 - j;
        const long long d = prepare_row(t, *job.tables, job.extent, ow, r, s);
        if (x0 == 0) dropped += d;
        std::memset(sc.cur_ok + x0, 0, size_t(x1 - x0));
        LineOut lo{sc.row_c, sc.row_v, ow, x0, x1 - 1};
        lo.copy = job.copy_still;
        // Every 4th row measures how many pixels its spans cover per column (at most oh each).
        sc.measure = pipelined_reverse != 2 && (j & 3) == 0 && j + step != end;
        sc.drawn = _mm512_setzero_ps();
        warp_line_fast<true>(s, job.split_u, lo, ClipRange<Emitter>{emit, x0, x1});
        const bool rev = sc.measure && _mm512_reduce_add_ps(sc.drawn) > kReverseDrawn * float(x1 - x0);
        sc.measure = false;
        std::swap(sc.prev_v, sc.cur_v);
        std::swap(sc.prev_c, sc.cur_c);
        std::swap(sc.prev_ok, sc.cur_ok);
        if (rev) {
            reverse_rows(job, sc, emit.o, part, j + step, end, step, x0, x1, dropped);
            if (dropped) *job.dropped += dropped;
            return;
        }
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

#include "warp/fast_target_end.h"
