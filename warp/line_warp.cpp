#include "warp/line_warp.h"

#include <algorithm>
#include <cmath>

namespace rtm {

int split_index(double split_pos, int n) {
    // Sample k is in the first part when k + 0.5 < split_pos, i.e. k < split_pos - 0.5.
    const double s = std::ceil(split_pos - 0.5);
    if (!(s > 0.0)) return 0;  // also NaN
    if (s >= double(n)) return n;
    return int(s);
}

namespace {

template <class P>
struct Writer {
    const LineInput<P>& in;
    const LineOutput<P>& out;

    void put(int x, Rgba8 c, P attr) const {
        c.a = 255;
        out.color[std::ptrdiff_t(x) * out.color_stride] = c;
        if (out.attr) out.attr[std::ptrdiff_t(x) * out.attr_stride] = attr;
    }

    static uint8_t lerp8(uint8_t a, uint8_t b, P t) {
        return uint8_t(P(a) * (P(1) - t) + P(b) * t + P(0.5));
    }

    // The pixel containing pos, for a sample that starts a run.
    void point(int k) const {
        const P p = in.pos[k];
        if (!(p >= P(0) && p < P(out.n))) return;
        put(int(p), in.color[k], in.attr ? in.attr[k] : P(0));
    }

    // Pixels with centres between pos[a] (excluded) and pos[b] (included).
    void span(int a, int b) const {
        const P pa = in.pos[a], pb = in.pos[b];
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
        hi = std::min(hi, P(out.n - 1));
        if (!(lo <= hi)) return;
        const Rgba8 ca = in.color[a], cb = in.color[b];
        const P aa = in.attr ? in.attr[a] : P(0), ab = in.attr ? in.attr[b] : P(0);
        const P inv = P(1) / (pb - pa);
        const int x0 = int(lo), x1 = int(hi);
        for (int x = x0; x <= x1; ++x) {
            P t = (P(x) + P(0.5) - pa) * inv;
            t = std::clamp(t, P(0), P(1));
            Rgba8 c{lerp8(ca.r, cb.r, t), lerp8(ca.g, cb.g, t), lerp8(ca.b, cb.b, t), 255};
            put(x, c, aa * (P(1) - t) + ab * t);
        }
    }

    // One part of the line in processing order; returns the last sample processed, or -1 if it was invalid.
    int part(int first, int last, int step) const {
        int prev = -1;
        for (int k = first; k != last; k += step) {
            if (!in.valid[k] || !std::isfinite(in.pos[k])) {
                prev = -1;
                continue;
            }
            if (prev < 0)
                point(k);
            else
                span(prev, k);
            prev = k;
        }
        return prev;
    }
};

}  // namespace

template <class P>
void warp_line(const LineInput<P>& in, int split, const LineOutput<P>& out) {
    Writer<P> w{in, out};
    const int left_last = w.part(0, split, +1);            // borders towards the split: left part
    const int right_last = w.part(in.n - 1, split - 1, -1);  // right part, from the last sample down to split
    // The seam: the two samples nearest the split are adjacent (split - 1 and split) when both are valid.
    if (left_last >= 0 && right_last >= 0 && left_last == split - 1 && right_last == split) w.span(left_last, right_last);
}

template void warp_line<float>(const LineInput<float>&, int, const LineOutput<float>&);
template void warp_line<double>(const LineInput<double>&, int, const LineOutput<double>&);

}  // namespace rtm
