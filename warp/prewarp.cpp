#include "warp/prewarp.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
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

// The horizontal warp's input for storage row r: final column (pos) and final row coordinate (attr) of every
// texel, with validity (non-empty and 1 + k3*d > 0). Returns the number of texels dropped for 1 + k3*d <= 0.
template <class P>
long long row_samples(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                      int r, LineScratch<P>& s) {
    const int w = t.width, h = t.height;
    const P vs = P(h - 1 - r) + P(0.5);
    const ReliefTexel* src = &t.texels[size_t(r) * size_t(w)];
    long long nd = 0;
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
    return nd;
}

// Horizontal pass over storage rows [r0, r1): colour and final row coordinate interpolated along each row.
template <class P>
void horizontal_pass(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                     int r0, int r1, ImageRGBA8& mid, Image2D<P>& mid_v, std::atomic<long long>& dropped) {
    const int w = t.width;
    LineScratch<P> s;
    s.resize(w);
    const int split = split_index(k.epipole_u, w);
    long long nd = 0;
    for (int r = r0; r < r1; ++r) {
        nd += row_samples(t, k, tab, exact, r, s);
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

// Pipelined reconstruction (paper section 3.2.2, Figure 11): rows are warped in occlusion-compatible order and
// every pixel the horizontal warp produces is rasterized into its column at once, connected to the last pixel
// that column received from the previous row. No intermediate image exists, so nothing a later texel of the same
// row overwrites is lost: any number of foldovers is handled without depth comparison.
template <class P>
struct ColumnSample {
    P v;
    Rgba8 c;
};

template <class P>
struct PipelinedPart {
    std::vector<ColumnSample<P>> prev, cur;
    std::vector<uint8_t> prev_ok, cur_ok;
    long long dropped = 0;
};

// Rows j (v order, bottom = 0) from `first` towards `last` (exclusive) by `step`; writes only output v-rows in
// [y0, y1), the half of the texture on this part's side of the epipole, so the two parts never touch the same
// pixel and can run concurrently with a result independent of the schedule.
template <class P>
void pipelined_part(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                    int first, int last, int step, int y0, int y1, PipelinedPart<P>& part, ImageRGBA8& out) {
    const int w = t.width, h = t.height;
    LineScratch<P> s;
    s.resize(w);
    const int split = split_index(k.epipole_u, w);
    part.prev.assign(size_t(w), {});
    part.cur.assign(size_t(w), {});
    part.prev_ok.assign(size_t(w), 0);
    part.cur_ok.assign(size_t(w), 0);
    for (int j = first; j != last; j += step) {
        const int r = h - 1 - j;
        part.dropped += row_samples(t, k, tab, exact, r, s);
        std::fill(part.cur_ok.begin(), part.cur_ok.end(), uint8_t(0));
        LineInput<P> in{w, s.pos.data(), s.color.data(), s.attr.data(), s.valid.data()};
        warp_line_to(in, split, w, [&](int x, Rgba8 c, P v) {
            auto put = [&](int y, Rgba8 cc, P) {
                if (y >= y0 && y < y1) out.at(x, h - 1 - y) = cc;
            };
            if (part.prev_ok[x])
                raster_span(part.prev[x].v, part.prev[x].c, P(0), v, c, P(0), h, put);
            else if (std::isfinite(v))
                raster_point(v, c, P(0), h, put);
            part.cur[x] = {v, c};
            part.cur_ok[x] = std::isfinite(v);
        });
        std::swap(part.prev, part.cur);
        std::swap(part.prev_ok, part.cur_ok);
    }
}

template <class P>
PrewarpStats pipelined(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                       int threads, ImageRGBA8& out) {
    const int w = t.width, h = t.height;
    std::fill(out.pixels.begin(), out.pixels.end(), Rgba8{});
    const int split = split_index(k.epipole_v, h);
    PipelinedPart<P> bottom, top;
    auto run_bottom = [&] { pipelined_part<P>(t, k, tab, exact, 0, split, +1, 0, split, bottom, out); };
    auto run_top = [&] { pipelined_part<P>(t, k, tab, exact, h - 1, split - 1, -1, split, h, top, out); };
    if (threads == 1) {
        run_bottom();
        run_top();
    } else {
        tbb::parallel_invoke(run_bottom, run_top);
    }
    // The seam between the last rows of the two parts (rows split - 1 and split).
    if (split > 0 && split < h) {
        for (int x = 0; x < w; ++x) {
            if (!bottom.prev_ok[x] || !top.prev_ok[x]) continue;
            raster_span(bottom.prev[x].v, bottom.prev[x].c, P(0), top.prev[x].v, top.prev[x].c, P(0), h,
                        [&](int y, Rgba8 c, P) { out.at(x, h - 1 - y) = c; });
        }
    }
    return {(long long)w * h, bottom.dropped + top.dropped};
}

}  // namespace

PrewarpStats prewarp(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options,
                     PrewarpWorkspace& ws, ImageRGBA8& out) {
    out.resize(relief.width, relief.height);
    if (k.side == ViewSide::on_plane || relief.width == 0 || relief.height == 0) return {};
    const PrewarpTables tab = PrewarpTables::build(k, relief.quant);
    if (options.method == Reconstruction::pipelined) {
        if (options.exact) return pipelined<double>(relief, k, tab, true, options.threads, out);
        return pipelined<float>(relief, k, tab, false, options.threads, out);
    }
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
