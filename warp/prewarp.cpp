#include "warp/prewarp.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <vector>

#include "warp/line_warp.h"

namespace rtm {

std::string to_string(Reconstruction m) { return m == Reconstruction::two_pass ? "two-pass" : "pipelined"; }

namespace {

// Scratch for one line, reused within a task.
template <class P>
struct LineScratch {
    std::vector<P> pos, attr;
    std::vector<Rgba8> color;
    std::vector<uint8_t> valid;
    void resize(int n) {
        pos.resize(size_t(n));
        attr.resize(size_t(n));
        color.resize(size_t(n));
        valid.resize(size_t(n));
    }
};

// Horizontal pass over storage rows [r0, r1): final column and final row coordinate of every texel, colour and
// final row interpolated along the row.
template <class P>
void horizontal_pass(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                     int r0, int r1, ImageRGBA8& mid, Image2D<P>& mid_v, std::atomic<long long>& dropped) {
    const int w = t.width, h = t.height;
    LineScratch<P> s;
    s.resize(w);
    const int split = split_index(k.epipole_u, w);
    long long nd = 0;
    for (int r = r0; r < r1; ++r) {
        const P vs = P(h - 1 - r) + P(0.5);
        const ReliefTexel* src = &t.texels[size_t(r) * size_t(w)];
        for (int x = 0; x < w; ++x) {
            const ReliefTexel tx = src[x];
            s.color[x] = {tx.r, tx.g, tx.b, 255};
            const P us = P(x) + P(0.5);
            if (exact) {
                const double d = t.displ(x, r);
                const double den = 1.0 + k.k3 * d;
                const bool ok = tx.q != kEmptyIndex && den > 0.0;
                s.valid[x] = ok;
                s.pos[x] = ok ? P((double(us) + k.k1 * d) / den) : P(0);
                s.attr[x] = ok ? P((double(vs) + k.k2 * d) / den) : P(0);
                nd += tx.q != kEmptyIndex && !ok;
            } else {
                s.valid[x] = tab.valid[tx.q];
                s.pos[x] = (us + P(tab.k1d[tx.q])) * P(tab.rcp[tx.q]);
                s.attr[x] = (vs + P(tab.k2d[tx.q])) * P(tab.rcp[tx.q]);
                nd += tx.q != kEmptyIndex && !tab.valid[tx.q];
            }
        }
        Rgba8* out = mid.row(r);
        std::fill(out, out + w, Rgba8{});
        LineInput<P> in{w, s.pos.data(), s.color.data(), s.attr.data(), s.valid.data()};
        LineOutput<P> lo{w, out, 1, mid_v.row(r), 1};
        warp_line(in, split, lo);
    }
    dropped += nd;
}

// Vertical pass over columns [x0, x1): intermediate pixels move to their final rows. Lines run in v order
// (bottom row first), so the output is written from storage row h-1 upwards (negative stride).
template <class P>
void vertical_pass(const PrewarpCoefficients& k, int x0, int x1, const ImageRGBA8& mid, const Image2D<P>& mid_v,
                   ImageRGBA8& out) {
    const int w = mid.width, h = mid.height;
    LineScratch<P> s;
    s.resize(h);
    const int split = split_index(k.epipole_v, h);
    for (int x = x0; x < x1; ++x) {
        for (int j = 0; j < h; ++j) {
            const int r = h - 1 - j;
            const Rgba8 c = mid.at(x, r);
            s.color[j] = c;
            s.valid[j] = c.a != 0;
            s.pos[j] = mid_v.at(x, r);
        }
        for (int j = 0; j < h; ++j) out.at(x, j) = Rgba8{};
        LineInput<P> in{h, s.pos.data(), s.color.data(), nullptr, s.valid.data()};
        LineOutput<P> lo{h, &out.at(x, h - 1), -std::ptrdiff_t(w), nullptr, 0};
        warp_line(in, split, lo);
    }
}

template <class Body>
void run(int threads, int n, int grain, const Body& body) {
    auto loop = [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, n, grain),
                          [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
    };
    if (threads > 0) {
        tbb::task_arena arena(threads);
        arena.execute(loop);
    } else {
        loop();
    }
}

template <class P>
PrewarpStats two_pass(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                      int threads, ImageRGBA8& mid, Image2D<P>& mid_v, ImageRGBA8& out) {
    const int w = t.width, h = t.height;
    mid.resize(w, h);
    mid_v.resize(w, h);
    std::atomic<long long> dropped{0};
    run(threads, h, 16, [&](int r0, int r1) { horizontal_pass<P>(t, k, tab, exact, r0, r1, mid, mid_v, dropped); });
    run(threads, w, 16, [&](int x0, int x1) { vertical_pass<P>(k, x0, x1, mid, mid_v, out); });
    return {(long long)w * h, dropped.load()};
}

}  // namespace

PrewarpStats prewarp(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options,
                     PrewarpWorkspace& ws, ImageRGBA8& out) {
    out.resize(relief.width, relief.height);
    if (k.side == ViewSide::on_plane || relief.width == 0 || relief.height == 0) return {};
    const PrewarpTables tab = PrewarpTables::build(k, relief.quant);
    if (options.exact)
        return two_pass<double>(relief, k, tab, true, options.threads, ws.mid_color, ws.mid_v_exact, out);
    return two_pass<float>(relief, k, tab, false, options.threads, ws.mid_color, ws.mid_v, out);
}

ImageRGBA8 prewarp(const ReliefTexture& relief, const glm::dvec3& eye, const PrewarpOptions& options) {
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    prewarp(relief, compute_coefficients(relief.geometry, eye), options, ws, out);
    return out;
}

}  // namespace rtm
