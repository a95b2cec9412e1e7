// The 1-D forward warp and resampling of one line (a row in the horizontal pass, a column in the vertical pass),
// paper section 3.2.1 and Figure 10. One kernel serves rows and columns: the output is strided.
//
// Input: n samples at source positions k + 0.5 (k = 0..n-1), each with a final position pos[k] along the line, a
// colour, an optional attribute carried along (the final row coordinate in the horizontal pass), and a validity
// flag (empty texels and texels that cannot be pre-warped are invalid).
//
// Order: samples with source position < split_pos (the epipole's coordinate along the line) are processed from
// the first towards the split, the others from the last towards the split; later samples overwrite earlier ones
// (painter's algorithm, correct because the order is occlusion-compatible). Finally the span between the two
// samples nearest the split is filled like any other span, so there is no seam at the epipole.
//
// Spans: between consecutive valid samples A (earlier) and B (later) every output pixel x whose centre
// c = x + 0.5 lies between A.pos (excluded) and B.pos (included) gets colour and attribute linearly interpolated
// at c. A valid sample whose predecessor is invalid (or the first of a part) is written to the pixel containing
// its position, floor(pos). Pixels outside [0, n) are dropped. Written pixels get alpha 255.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "image.h"

namespace rtm {

// Attributes carried along a line and interpolated like colour: a scalar, a struct with attr_lerp, or nothing.
struct NoAttr {};
template <class P>
inline NoAttr attr_lerp(NoAttr, NoAttr, P) {
    return {};
}
inline float attr_lerp(float a, float b, float t) { return a * (1.0f - t) + b * t; }
inline double attr_lerp(double a, double b, double t) { return a * (1.0 - t) + b * t; }

template <class P, class A = P>
struct LineInput {
    int n = 0;
    const P* pos = nullptr;
    const Rgba8* color = nullptr;
    const A* attr = nullptr;  // may be null (then A{} is carried)
    const uint8_t* valid = nullptr;
};

template <class P, class A = P>
struct LineOutput {
    int n = 0;                        // number of output pixels along the line
    Rgba8* color = nullptr;           // pixel 0
    std::ptrdiff_t color_stride = 1;  // in pixels, may be negative
    A* attr = nullptr;                // may be null
    std::ptrdiff_t attr_stride = 1;
};

// Index of the first sample whose source position k + 0.5 is >= split_pos, clamped to [0, n].
int split_index(double split_pos, int n);

// ---- Building blocks, generic over where pixels go: put(int x, Rgba8 colour, A attr). ----

// One channel at parameter t in [0, 1], in fixed point: b's weight is w / 2^14 with w = floor(t * 2^14) made odd
// (the centre of t's 2^-13 bin) and at most 2^14 - 1 (NaN gives that too), and the channel is
// (a * (2^14 - w) + b * w + 2^13) >> 14, i.e. a + (b - a) * w / 2^14 rounded. An odd w never makes a tie
// ((b - a) * w is never an odd multiple of 2^13), so the result is the nearest integer to a + (b - a) * w / 2^14. The
// vector kernels (warp/simd/hwy_columns-inl.h) do the same with integer dot products on packed colours, a third of the
// work of the float formula uint8_t(a * (1 - t) + b * t + 0.5) it replaced (docs/perf-history.md). Against that
// formula: |t - w / 2^14| <= 2^-14 moves the exact value a + (b - a) * t by at most 255 / 2^14 < 0.016, and each result
// rounds its own value (the float one with an error far below that), so the two differ by at most 1 level, and only
// where the exact value lies within 0.016 of a rounding boundary (tests/warp/fast_kernels_test.cpp checks both). t = 0
// and t = 1 still give a and b exactly (the value moves by less than 1/2).
template <class P>
inline uint8_t lerp8(uint8_t a, uint8_t b, P t) {
    const int w = t >= P(0) ? std::min(int(t * P(16384)) | 1, 16383) : 16383;
    return uint8_t((int(a) * (16384 - w) + int(b) * w + 8192) >> 14);
}

// A sample that starts a run goes to the pixel containing its position.
template <class P, class A, class Put>
inline void raster_point(P p, Rgba8 c, const A& attr, int n, Put&& put) {
    if (!(p >= P(0) && p < P(n))) return;
    c.a = 255;
    put(int(p), c, attr);
}

struct AllPixels {
    bool operator()(int) const { return true; }
};

// Pixels x0 .. x1 of the span from pa to pb (pa != pb), colour and attribute interpolated at each centre. A pixel's
// value depends on x alone, so any part of a span gives the same pixels as the whole (the fast kernels' backward
// rows, warp/simd/hwy_row-inl.h, draw only the parts no later span covers), and so does any subset: with `wanted`,
// only the pixels it accepts are interpolated and put (objects/face_swap.cpp: the pixels an object reads).
template <class P, class A, class Put, class Wanted = AllPixels>
inline void raster_span_pixels(P pa, Rgba8 ca, const A& aa, P pb, Rgba8 cb, const A& ab, int x0, int x1, Put&& put,
                               Wanted&& wanted = {}) {
    const P inv = P(1) / (pb - pa);
    for (int x = x0; x <= x1; ++x) {
        if (!wanted(x)) continue;
        P t = (P(x) + P(0.5) - pa) * inv;
        t = std::clamp(t, P(0), P(1));
        const Rgba8 c{lerp8(ca.r, cb.r, t), lerp8(ca.g, cb.g, t), lerp8(ca.b, cb.b, t), 255};
        put(x, c, attr_lerp(aa, ab, t));
    }
}

// Pixels with centres between pa (excluded) and pb (included), colour and attribute interpolated at the centre.
template <class P, class A, class Put>
inline void raster_span(P pa, Rgba8 ca, const A& aa, P pb, Rgba8 cb, const A& ab, int n, Put&& put) {
    if (pa == pb) return;
    P lo, hi;  // inclusive range of x, as reals, before clamping
    if (pb > pa) {
        lo = std::floor(pa - P(0.5)) + P(1);
        hi = std::floor(pb - P(0.5));
    } else {
        lo = std::ceil(pb - P(0.5));
        hi = std::ceil(pa - P(0.5)) - P(1);
    }
    lo = std::max(lo, P(0));
    hi = std::min(hi, P(n - 1));
    if (!(lo <= hi)) return;
    raster_span_pixels(pa, ca, aa, pb, cb, ab, int(lo), int(hi), put);
}

struct AlwaysConnected {
    bool operator()(int, int) const { return true; }
};

// Two samples carried across the other direction belong to one surface where their displacements differ by at most
// the discontinuity threshold (paper section 4.1.1); a threshold of 0 joins every pair.
template <class P>
inline bool displacements_joined(P da, P db, P threshold) {
    return !(threshold > P(0)) || std::abs(da - db) <= threshold;
}

// The whole line in occlusion-compatible order (see the top of this file), pixels to put(). connected(a, b)
// says whether two adjacent valid samples belong to one surface (false across a marked discontinuity: then no
// span is drawn and b starts a new run).
template <class P, class A, class Put, class Connected = AlwaysConnected>
void warp_line_to(const LineInput<P, A>& in, int split, int n_out, Put&& put, Connected&& connected = {}) {
    auto attr = [&](int k) { return in.attr ? in.attr[k] : A{}; };
    auto part = [&](int first, int last, int step) {
        int prev = -1;
        for (int k = first; k != last; k += step) {
            if (!in.valid[k] || !std::isfinite(in.pos[k])) {
                prev = -1;
                continue;
            }
            if (prev < 0 || !connected(prev, k))
                raster_point(in.pos[k], in.color[k], attr(k), n_out, put);
            else
                raster_span(in.pos[prev], in.color[prev], attr(prev), in.pos[k], in.color[k], attr(k), n_out, put);
            prev = k;
        }
        return prev;
    };
    const int left_last = part(0, split, +1);
    const int right_last = part(in.n - 1, split - 1, -1);
    // The seam: the two samples nearest the split are adjacent (split - 1 and split) when both are valid.
    if (left_last >= 0 && right_last >= 0 && left_last == split - 1 && right_last == split &&
        connected(left_last, right_last))
        raster_span(in.pos[left_last], in.color[left_last], attr(left_last), in.pos[right_last], in.color[right_last],
                    attr(right_last), n_out, put);
}

// The line into a strided buffer.
template <class P>
void warp_line(const LineInput<P>& in, int split, const LineOutput<P>& out);

extern template void warp_line<float>(const LineInput<float>&, int, const LineOutput<float>&);
extern template void warp_line<double>(const LineInput<double>&, int, const LineOutput<double>&);

}  // namespace rtm
