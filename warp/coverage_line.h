// Coverage-weighted resampling of one warped line, in the manner of Fant's algorithm (the paper, section 3.2.1,
// cites it): each output pixel receives the average colour of what covers it, weighted by the length covered,
// and its alpha is the fraction covered. The point-sampled counterpart is warp_line_to (warp/line_warp.h); both
// take the same samples in the same occlusion-compatible order, and both draw the same signal:
//
// The signal along a line. Between two connected samples A and B (positions pa, pb) colour and attributes are
// linear, as in warp_line_to and as on the surface the ground truths use (truth/raycast.h and
// truth/micromesh.h: bilinear between texel centres). A run of connected samples therefore covers
// [first position, last position]: like the truths, the surface ends at its outermost texel centres. A sample
// with no connected neighbour covers one pixel's width centred on its position (the point filter writes the
// pixel containing it).
//
// Point sampling evaluates that signal at pixel centres; this filter integrates it over each pixel. The two agree
// wherever a pixel holds one linear piece; they differ where the warp compresses (several texels per pixel: the
// point filter picks one and aliases, this one averages) and at the ends of runs (partial coverage instead of a
// whole pixel or none). Consequence: zero displacement is not a copy but the box filter of the linear
// interpolant, (c[k-1] + 6 c[k] + c[k+1]) / 8 inside a run, which is exactly what a supersampled view of the flat
// relief shows.
//
// Occlusion: later pieces are nearer the viewer (occlusion-compatible order). Each pixel keeps a mask of 32
// sub-pixel positions recording which parts of it are covered (a 1-D A-buffer): a piece over [s0, s1) of the
// pixel claims the positions whose centres lie in it, and
// content already there loses the share of its positions the piece claims -- its sums are scaled by the fraction
// of its positions left. Adjacent pieces of one surface claim disjoint positions and simply add up; a piece in
// front of another replaces it where they overlap, and only there. The colour of earlier content is assumed
// uniform over its positions (the approximation).
//
// Alpha of the input samples: 255 for texels (the horizontal pass); the coverage left by the horizontal pass for
// the vertical pass. Colour is interpolated premultiplied, so a half-covered intermediate pixel counts half.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "image.h"

namespace rtm {

// One output pixel's running sums (premultiplied colour and attributes, weighted by opaque covered length).
template <class P, int NA>
struct CoverageCell {
    P r = 0, g = 0, b = 0;
    P cov = 0;  // opaque covered length, in pixels (0..1): the alpha
    std::array<P, NA> attr{};
    uint32_t mask = 0;  // covered sub-pixel positions (bit i: centre (i + 1/2) / 32)
};

template <class P, int NA>
struct CoverageLineInput {
    int n = 0;
    const P* pos = nullptr;                   // final position along the line, output pixels
    const Rgba8* color = nullptr;             // straight colour; alpha = the sample's coverage (255 = whole)
    const std::array<P, NA>* attr = nullptr;  // may be null
    const uint8_t* valid = nullptr;
};

template <class P, int NA>
class CoverageRasterizer {
public:
    using Cell = CoverageCell<P, NA>;
    using Attr = std::array<P, NA>;

    // `cells` holds n_out cells, cleared by the caller.
    CoverageRasterizer(Cell* cells, int n_out) : cells_(cells), n_(n_out) {}

    // Deposits a piece over [lo, hi) (output coordinates, inside pixel x) with alpha a, straight colour
    // (r, g, b) and attributes `at`: opaque length c = (hi - lo) * a.
    void deposit(int x, P lo, P hi, P a, P r, P g, P b, const Attr& at) {
        Cell& cell = cells_[x];
        const uint32_t m = claim(lo - P(x), hi - P(x));
        const uint32_t hit = cell.mask & m;
        if (hit) {
            const P s = P(std::popcount(cell.mask & ~m)) / P(std::popcount(cell.mask));
            cell.r *= s;
            cell.g *= s;
            cell.b *= s;
            cell.cov *= s;
            for (int i = 0; i < NA; ++i) cell.attr[i] *= s;
        }
        cell.mask |= m;
        const P c = (hi - lo) * a;
        cell.r += c * r;
        cell.g += c * g;
        cell.b += c * b;
        cell.cov += c;
        for (int i = 0; i < NA; ++i) cell.attr[i] += c * at[i];
    }

    // The sub-pixel positions whose centres (i + 1/2) / 32 lie in [s0, s1) (0 <= s0 < s1 <= 1). Half-open, so
    // adjacent pieces claim disjoint positions; a piece narrower than a position may claim none (it then adds
    // its colour without hiding anything and cannot be hidden; such pieces are narrower than 1/32 of a pixel).
    static uint32_t claim(P s0, P s1) {
        int i0 = int(std::ceil(s0 * P(32) - P(0.5)));
        int i1 = int(std::ceil(s1 * P(32) - P(0.5)));  // exclusive
        i0 = std::clamp(i0, 0, 32);
        i1 = std::clamp(i1, 0, 32);
        if (i1 <= i0) return 0;
        const uint32_t hi_bits = i1 >= 32 ? ~uint32_t(0) : ((uint32_t(1) << i1) - 1);
        const uint32_t lo_bits = (uint32_t(1) << i0) - 1;  // i0 <= 31 here
        return hi_bits & ~lo_bits;
    }

    // The linear span from sample A to sample B (straight colours, alpha = coverage 0..255). Each covered piece
    // gets the mean of the signal over it, which for a linear signal is its value at the piece's middle.
    void span(P pa, Rgba8 ca, const Attr& aa, P pb, Rgba8 cb, const Attr& ab) {
        if (!(pa != pb)) return;
        const P inv = P(1) / (pb - pa);
        const P lo = std::min(pa, pb), hi = std::max(pa, pb);
        const P ala = P(ca.a) / P(255), alb = P(cb.a) / P(255);
        const int x0 = int(std::max(std::floor(lo), P(0)));
        const int x1 = int(std::min(std::ceil(hi), P(n_))) - 1;
        for (int x = x0; x <= x1; ++x) {
            const P w = std::min(P(x + 1), hi) - std::max(P(x), lo);
            if (!(w > P(0))) continue;
            const P mid = (std::max(P(x), lo) + std::min(P(x + 1), hi)) * P(0.5);
            const P t = std::clamp((mid - pa) * inv, P(0), P(1));
            // Premultiplied interpolation: colour weighted by alpha, then back to straight for the sums.
            const P a = ala + (alb - ala) * t;
            if (!(a > P(0))) continue;
            const P wa = ala * (P(1) - t), wb = alb * t;
            auto ch = [&](uint8_t u, uint8_t v) { return (P(u) * wa + P(v) * wb) / a; };
            Attr at;
            for (int i = 0; i < NA; ++i) at[i] = aa[i] + (ab[i] - aa[i]) * t;
            deposit(x, std::max(P(x), lo), std::min(P(x + 1), hi), a, ch(ca.r, cb.r), ch(ca.g, cb.g), ch(ca.b, cb.b),
                    at);
        }
    }

    // A sample alone: one pixel's width of its colour centred on p.
    void single(P p, Rgba8 c, const Attr& at) {
        const P lo = p - P(0.5), hi = p + P(0.5);
        const P a = P(c.a) / P(255);
        const int x0 = int(std::max(std::floor(lo), P(0)));
        const int x1 = int(std::min(std::ceil(hi), P(n_))) - 1;
        for (int x = x0; x <= x1; ++x) {
            const P s0 = std::max(P(x), lo), s1 = std::min(P(x + 1), hi);
            if (s1 > s0 && a > P(0)) deposit(x, s0, s1, a, P(c.r), P(c.g), P(c.b), at);
        }
    }

private:
    Cell* cells_;
    int n_;
};

// The whole line in occlusion-compatible order (the order of warp_line_to: each part from its border towards the
// split, then the seam), into `cells` (n_out of them, cleared by the caller). connected(a, b) as in warp_line_to.
template <class P, int NA, class Connected>
void coverage_warp_line(const CoverageLineInput<P, NA>& in, int split, CoverageCell<P, NA>* cells, int n_out,
                        Connected&& connected) {
    CoverageRasterizer<P, NA> R(cells, n_out);
    using Attr = std::array<P, NA>;
    auto attr = [&](int k) { return in.attr ? in.attr[k] : Attr{}; };
    struct Run {
        int last = -1;
        bool single = true;  // no span drawn yet
    };
    auto end_run = [&](const Run& run) {
        if (run.last >= 0 && run.single) R.single(in.pos[run.last], in.color[run.last], attr(run.last));
    };
    auto part = [&](int first, int last, int step) {
        Run run;
        for (int k = first; k != last; k += step) {
            if (!in.valid[k] || !std::isfinite(in.pos[k])) {
                end_run(run);
                run = {};
                continue;
            }
            if (run.last >= 0 && connected(run.last, k)) {
                R.span(in.pos[run.last], in.color[run.last], attr(run.last), in.pos[k], in.color[k], attr(k));
                run = {k, false};
            } else {
                end_run(run);
                run = {k, true};
            }
        }
        return run;
    };
    const Run left = part(0, split, +1);
    const Run right = part(in.n - 1, split - 1, -1);
    if (left.last >= 0 && right.last >= 0 && left.last == split - 1 && right.last == split &&
        connected(left.last, right.last)) {
        R.span(in.pos[left.last], in.color[left.last], attr(left.last), in.pos[right.last], in.color[right.last],
               attr(right.last));
        return;
    }
    end_run(left);
    end_run(right);
}

// Turns a line's sums into pixels: alpha = covered fraction (rounded to 8 bits), colour = the weighted average
// (straight, rounded), attributes = their weighted averages. put(x, Rgba8, attr) is called for pixels whose alpha
// rounds to at least 1; the others stay as the caller cleared them.
template <class P, int NA, class Put>
void coverage_resolve(const CoverageCell<P, NA>* cells, int n, Put&& put) {
    for (int x = 0; x < n; ++x) {
        const CoverageCell<P, NA>& c = cells[x];
        const int a8 = int(std::min(c.cov, P(1)) * P(255) + P(0.5));
        if (a8 < 1) continue;
        const P inv = P(1) / c.cov;
        auto ch = [&](P v) { return uint8_t(std::clamp(v * inv + P(0.5), P(0), P(255))); };
        std::array<P, NA> at;
        for (int i = 0; i < NA; ++i) at[i] = c.attr[i] * inv;
        put(x, Rgba8{ch(c.r), ch(c.g), ch(c.b), uint8_t(a8)}, at);
    }
}

}  // namespace rtm
