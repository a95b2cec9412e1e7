// The reference kernels (see reference_prewarp.h).
#include "warp/reference/reference_prewarp.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <array>
#include <cmath>
#include <vector>

#include "warp/coverage_line.h"
#include "warp/line_warp.h"
#include "warp/task_arenas.h"

namespace rtm {

namespace {

// What the horizontal pass carries along a row besides colour: the final row coordinate and the displacement
// (for the vertical pass's discontinuity test and for depth correction).
template <class P>
struct RowAttr {
    P v = 0;
    P d = 0;
};

template <class P>
inline RowAttr<P> attr_lerp(const RowAttr<P>& a, const RowAttr<P>& b, P t) {
    return {a.v * (P(1) - t) + b.v * t, a.d * (P(1) - t) + b.d * t};
}

// Scratch for one line, reused within a task.
template <class P>
struct LineScratch {
    std::vector<P> pos;
    std::vector<RowAttr<P>> attr;
    std::vector<P> d;
    std::vector<Rgba8> color;
    std::vector<uint8_t> valid;
    std::vector<uint8_t> still;  // valid and exactly on the centre of its own output pixel (copy_still_runs)
    int n_still = 0;             // how many (0: the line is warped as usual, no copy to look for)
    void resize(int n) {
        pos.resize(size_t(n));
        attr.resize(size_t(n));
        d.resize(size_t(n));
        color.resize(size_t(n));
        valid.resize(size_t(n));
        still.resize(size_t(n));
    }
};

// The output frame: margins around the quad and the output size; and whether the point-filter kernels copy runs
// of still texels (PrewarpOptions::copy_still_runs, warp_line_still_to).
struct Frame {
    int w = 0, h = 0;  // source size
    PrewarpExtent e;
    bool copy_still = false;
    int out_w() const { return w + e.left + e.right; }
    int out_h() const { return h + e.bottom + e.top; }
};

// The horizontal warp's input for storage row r: final column (pos, in output pixels) and final row coordinate
// (attr.v, in output v-lines) of every texel, its displacement, and validity (non-empty and 1 + k3*d > 0).
// Returns the number of texels dropped for 1 + k3*d <= 0.
//
// With `still` (copy_still_runs), texels at zero displacement (a still level of the tables, or an exact
// displacement of 0.0 on the exact path) skip the arithmetic: with d = 0 both equations give u_i = u_s and
// v_i = v_s exactly (k*0 = +-0, 1 / (1 + k3*0) = 1), so pos = us + ou and v = vs + ov are the very values the
// arithmetic would produce, and s.still marks them for the run copy (warp_line_still_to).
template <class P>
long long row_samples(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                      const Frame& fr, int r, LineScratch<P>& s, bool still = false) {
    const int w = t.width, h = t.height;
    const P vs = P(h - 1 - r) + P(0.5);
    const P ou = P(fr.e.left), ov = P(fr.e.bottom);
    const ReliefTexel* src = &t.texels[size_t(r) * size_t(w)];
    const float* dsrc = exact ? &t.displacement[size_t(r) * size_t(w)] : nullptr;
    long long nd = 0;
    s.n_still = 0;
    for (int x = 0; x < w; ++x) {
        const ReliefTexel tx = src[x];
        s.color[x] = {tx.r, tx.g, tx.b, 255};
        const P us = P(x) + P(0.5);
        if (still) {
            const bool st = exact ? tx.q != kEmptyIndex && dsrc[x] == 0.0f : tab.still[tx.q] != 0;
            s.still[x] = st;
            s.n_still += st;
            if (st) {
                s.valid[x] = 1;
                s.pos[x] = us + ou;
                s.attr[x] = {vs + ov, exact ? P(dsrc[x]) : P(tab.displ[tx.q])};
                continue;
            }
        }
        if (exact) {
            const double d = t.displ(x, r);
            const double den = 1.0 + k.k3 * d;
            const bool ok = tx.q != kEmptyIndex && den > 0.0;
            s.valid[x] = ok;
            s.pos[x] = ok ? P((double(us) + k.k1 * d) / den) + ou : P(0);
            s.attr[x] = {ok ? P((double(vs) + k.k2 * d) / den) + ov : P(0), P(d)};
            nd += tx.q != kEmptyIndex && !ok;
        } else {
            s.valid[x] = tab.valid[tx.q];
            s.pos[x] = (us + P(tab.k1d[tx.q])) * P(tab.rcp[tx.q]) + ou;
            s.attr[x] = {(vs + P(tab.k2d[tx.q])) * P(tab.rcp[tx.q]) + ov, P(tab.displ[tx.q])};
            nd += tx.q != kEmptyIndex && !tab.valid[tx.q];
        }
    }
    return nd;
}

// Connectivity along storage row r: texels k and k+1 are connected unless marked.
struct RowConnected {
    const uint8_t* breaks;  // row's marks, or null
    bool operator()(int a, int b) const { return !breaks || !(breaks[std::min(a, b)] & kBreakRight); }
};

// Connectivity of two samples carried into the vertical direction: displacements within the threshold.
template <class P>
struct DisplConnected {
    const P* d;
    P threshold;  // 0 = always connected
    bool operator()(int a, int b) const { return displacements_joined(d[a], d[b], threshold); }
};

// Copying texels that do not move (paper section 5: on the brick wall, skipping the transformation of
// zero-displacement texels more than doubled the speed). The row warp looks for them when asked to, when the
// coefficients are finite (then d = 0 is exactly the identity) and when some texel can be still (a zero level in
// the tables; on the exact path any texel may be exactly 0). Reliefs without any pay nothing.
inline bool look_for_still(const Frame& fr, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact) {
    return fr.copy_still && std::isfinite(k.k1) && std::isfinite(k.k2) && std::isfinite(k.k3) &&
           (exact || std::find(tab.still.begin(), tab.still.end(), uint8_t(1)) != tab.still.end());
}

// warp_line_to (warp/line_warp.h) with runs of still samples copied instead of rasterized: still[k] says sample k
// is valid and its position is exactly the centre of output pixel k + offset (pos[k] == k + 0.5 + offset, which
// lies in [0, n_out)). Same pixels, bit for bit, because such a sample is written the same whichever way it comes:
//   - after an invalid or unconnected sample, raster_point puts it at floor(pos[k]) = k + offset as it is;
//   - after a still neighbour (connected or not), the span from pos[k -+ 1] to pos[k] is one pixel long, holds the
//     one centre k + offset + 0.5 = pos[k], and t = (pos[k] - pos[k -+ 1]) * (1 / 1) = 1 exactly, so lerp8 gives
//     the sample's colour (lerp8(a, b, 1) == b) and attr_lerp its attribute (a*0 + b*1: up to the sign of a zero,
//     which no output depends on).
// Only a still sample after a connected moving one needs its span (the pixels between them are interpolated).
// The pixels of one run are distinct, so a run is copied in memory order; runs keep their place in the
// occlusion-compatible order, so the painter's overwrites between them and moving samples stay as they were.
// Returns the number of samples copied.
template <class P, class A, class Put, class Connected>
long long warp_line_still_to(const LineInput<P, A>& in, const uint8_t* still, int offset, int split, int n_out,
                             Put&& put, Connected&& connected) {
    auto attr = [&](int k) { return in.attr ? in.attr[k] : A{}; };
    auto copy = [&](int k) {
        Rgba8 c = in.color[k];
        c.a = 255;
        put(k + offset, c, attr(k));
    };
    long long copied = 0;
    auto part = [&](int first, int last, int step) {
        int prev = -1;
        for (int k = first; k != last; k += step) {
            if (still[k] && (prev < 0 || still[prev] || !connected(prev, k))) {
                int e = k;  // the run: k .. e in processing order
                while (e + step != last && still[e + step]) e += step;
                for (int j = std::min(k, e), je = std::max(k, e); j <= je; ++j) copy(j);
                copied += std::abs(e - k) + 1;
                prev = k = e;
                continue;
            }
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
    if (left_last >= 0 && right_last >= 0 && left_last == split - 1 && right_last == split &&
        connected(left_last, right_last)) {
        if (still[left_last] && still[right_last])
            copy(right_last);  // the one-pixel seam span writes the sample nearest the split again
        else
            raster_span(in.pos[left_last], in.color[left_last], attr(left_last), in.pos[right_last],
                        in.color[right_last], attr(right_last), n_out, put);
    }
    return copied;
}

// Horizontal pass over storage rows [r0, r1): colour, final row coordinate and displacement interpolated along
// each row into the intermediate image (output width x source height).
template <class P>
void horizontal_pass(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                     const Frame& fr, int r0, int r1, ImageRGBA8& mid, Image2D<P>& mid_v, Image2D<P>& mid_d,
                     std::atomic<long long>& dropped, std::atomic<long long>& copied,
                     std::atomic<long long>& row_pixels) {
    const int w = t.width, ow = fr.out_w();
    LineScratch<P> s;
    s.resize(w);
    const int split = split_index(k.epipole_u, w);
    const bool still = look_for_still(fr, k, tab, exact);
    long long nd = 0, nc = 0, np = 0;
    for (int r = r0; r < r1; ++r) {
        nd += row_samples(t, k, tab, exact, fr, r, s, still);
        Rgba8* oc = mid.row(r);
        P* ov = mid_v.row(r);
        P* od = mid_d.row(r);
        std::fill(oc, oc + ow, Rgba8{});
        LineInput<P, RowAttr<P>> in{w, s.pos.data(), s.color.data(), s.attr.data(), s.valid.data()};
        const RowConnected conn{t.breaks.empty() ? nullptr : &t.breaks[size_t(r) * size_t(w)]};
        auto put = [&](int x, Rgba8 c, const RowAttr<P>& a) {
            oc[x] = c;
            ov[x] = a.v;
            od[x] = a.d;
            ++np;
        };
        if (still && s.n_still > 0)
            nc += warp_line_still_to(in, s.still.data(), fr.e.left, split, ow, put, conn);
        else
            warp_line_to(in, split, ow, put, conn);
    }
    dropped += nd;
    copied += nc;
    row_pixels += np;
}

// The vertical pass's input for intermediate column x, in v order (bottom row first): colour, validity, final
// row and carried displacement; and the output column cleared (displacement to empty).
template <class P>
void column_samples(const ImageRGBA8& mid, const Image2D<P>& mid_v, const Image2D<P>& mid_d, int x, LineScratch<P>& s,
                    ImageRGBA8& out, Image2D<uint8_t>* displ_out) {
    const int h = mid.height;
    for (int j = 0; j < h; ++j) {
        const int r = h - 1 - j;
        const Rgba8 c = mid.at(x, r);
        s.color[j] = c;
        s.valid[j] = c.a != 0;
        s.pos[j] = mid_v.at(x, r);
        s.d[j] = mid_d.at(x, r);
    }
    for (int y = 0; y < out.height; ++y) out.at(x, y) = Rgba8{};
    if (displ_out)
        for (int y = 0; y < out.height; ++y) displ_out->at(x, y) = kEmptyIndex;
}

// Writes the quantized displacement of an output pixel (depth correction).
inline void put_displ(Image2D<uint8_t>* displ_out, const Quantizer& q, int x, int row, double d) {
    if (displ_out) displ_out->at(x, row) = q.encode(d);
}

// Vertical pass over intermediate columns [x0, x1): intermediate pixels move to their final rows. Lines run in
// v order (bottom row first), so storage rows are addressed as oh - 1 - y.
template <class P>
void vertical_pass(const ReliefTexture& t, const PrewarpCoefficients& k, const Frame& fr, int x0, int x1,
                   const ImageRGBA8& mid, const Image2D<P>& mid_v, const Image2D<P>& mid_d, ImageRGBA8& out,
                   Image2D<uint8_t>* displ_out, std::atomic<long long>& sampled) {
    const int h = fr.h, oh = fr.out_h();
    const bool copy_still = fr.copy_still;
    long long ns = 0;
    LineScratch<P> s;
    s.resize(h);
    const int split = split_index(k.epipole_v, h);
    const DisplConnected<P> conn{s.d.data(), P(t.discontinuity_threshold)};
    const P ob = P(fr.e.bottom);
    for (int x = x0; x < x1; ++x) {
        column_samples(mid, mid_v, mid_d, x, s, out, displ_out);
        // Still in this direction: on the centre of its own output row, as every texel at zero displacement
        // (and any pixel whose interpolated row happens to land there) is; the copy is exact all the same.
        for (int j = 0; j < h; ++j) {
            s.still[j] = copy_still && s.valid[j] && s.pos[j] == P(j) + P(0.5) + ob;
            ns += s.valid[j] && std::isfinite(s.pos[j]);
        }
        LineInput<P, P> in{h, s.pos.data(), s.color.data(), s.d.data(), s.valid.data()};
        auto put = [&](int y, Rgba8 c, P d) {
            out.at(x, oh - 1 - y) = c;
            put_displ(displ_out, t.quant, x, oh - 1 - y, d);
        };
        if (copy_still)
            warp_line_still_to(in, s.still.data(), fr.e.bottom, split, oh, put, conn);
        else
            warp_line_to(in, split, oh, put, conn);
    }
    sampled += ns;
}

// Coverage-weighted filtering (PrewarpOptions::filter == Filter::coverage, warp/coverage_line.h): the same two
// passes with Fant-style resampling instead of point sampling. Alpha leaves the horizontal pass as the covered
// fraction of each intermediate pixel and the vertical pass weighs colour by it.
template <class P>
void horizontal_pass_coverage(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab,
                              bool exact, const Frame& fr, int r0, int r1, ImageRGBA8& mid, Image2D<P>& mid_v,
                              Image2D<P>& mid_d, std::atomic<long long>& dropped) {
    const int w = t.width, ow = fr.out_w();
    LineScratch<P> s;
    s.resize(w);
    std::vector<std::array<P, 2>> attr(size_t(w), std::array<P, 2>{});
    std::vector<CoverageCell<P, 2>> cells(size_t(ow), CoverageCell<P, 2>{});
    const int split = split_index(k.epipole_u, w);
    long long nd = 0;
    for (int r = r0; r < r1; ++r) {
        nd += row_samples(t, k, tab, exact, fr, r, s);
        for (int x = 0; x < w; ++x) attr[size_t(x)] = {s.attr[size_t(x)].v, s.attr[size_t(x)].d};
        Rgba8* oc = mid.row(r);
        P* ov = mid_v.row(r);
        P* od = mid_d.row(r);
        std::fill(oc, oc + ow, Rgba8{});
        std::fill(cells.begin(), cells.end(), CoverageCell<P, 2>{});
        const CoverageLineInput<P, 2> in{w, s.pos.data(), s.color.data(), attr.data(), s.valid.data()};
        const RowConnected conn{t.breaks.empty() ? nullptr : &t.breaks[size_t(r) * size_t(w)]};
        coverage_warp_line(in, split, cells.data(), ow, conn);
        coverage_resolve(cells.data(), ow, [&](int x, Rgba8 c, const std::array<P, 2>& a) {
            oc[x] = c;
            ov[x] = a[0];
            od[x] = a[1];
        });
    }
    dropped += nd;
}

template <class P>
void vertical_pass_coverage(const ReliefTexture& t, const PrewarpCoefficients& k, const Frame& fr, int x0, int x1,
                            const ImageRGBA8& mid, const Image2D<P>& mid_v, const Image2D<P>& mid_d, ImageRGBA8& out,
                            Image2D<uint8_t>* displ_out) {
    const int h = fr.h, oh = fr.out_h();
    LineScratch<P> s;
    s.resize(h);
    std::vector<std::array<P, 1>> attr(size_t(h), std::array<P, 1>{});
    std::vector<CoverageCell<P, 1>> cells(size_t(oh), CoverageCell<P, 1>{});
    const int split = split_index(k.epipole_v, h);
    const DisplConnected<P> conn{s.d.data(), P(t.discontinuity_threshold)};
    for (int x = x0; x < x1; ++x) {
        column_samples(mid, mid_v, mid_d, x, s, out, displ_out);
        for (int j = 0; j < h; ++j) attr[size_t(j)] = {s.d[j]};
        std::fill(cells.begin(), cells.end(), CoverageCell<P, 1>{});
        const CoverageLineInput<P, 1> in{h, s.pos.data(), s.color.data(), attr.data(), s.valid.data()};
        coverage_warp_line(in, split, cells.data(), oh, conn);
        coverage_resolve(cells.data(), oh, [&](int y, Rgba8 c, const std::array<P, 1>& a) {
            out.at(x, oh - 1 - y) = c;
            put_displ(displ_out, t.quant, x, oh - 1 - y, a[0]);
        });
    }
}

template <class Body>
void run(int threads, int n, int grain, const Body& body) {
    auto loop = [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, n, grain),
                          [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
    };
    if (threads > 0) {
        task_arena_for(threads).execute(loop);  // the kept arena of this thread count (warp/task_arenas.h)
    } else {
        loop();
    }
}

template <class P>
PrewarpStats two_pass(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                      const Frame& fr, int threads, ImageRGBA8& mid, Image2D<P>& mid_v, Image2D<P>& mid_d,
                      ImageRGBA8& out, Image2D<uint8_t>* displ_out, Filter filter) {
    const int ow = fr.out_w();
    mid.resize(ow, t.height);
    mid_v.resize(ow, t.height);
    mid_d.resize(ow, t.height);
    std::atomic<long long> dropped{0};
    if (filter == Filter::coverage) {
        run(threads, t.height, 16, [&](int r0, int r1) {
            horizontal_pass_coverage<P>(t, k, tab, exact, fr, r0, r1, mid, mid_v, mid_d, dropped);
        });
        run(threads, ow, 16,
            [&](int x0, int x1) { vertical_pass_coverage<P>(t, k, fr, x0, x1, mid, mid_v, mid_d, out, displ_out); });
        return {(long long)t.width * t.height, dropped.load(), fr.e};
    }
    std::atomic<long long> copied{0}, row_pixels{0}, column_samples{0};
    run(threads, t.height, 16, [&](int r0, int r1) {
        horizontal_pass<P>(t, k, tab, exact, fr, r0, r1, mid, mid_v, mid_d, dropped, copied, row_pixels);
    });
    // The vertical pass looks for pixels on their own rows' centres where the horizontal pass copied at least an
    // eighth of the texels: a relief with only a few still texels does not pay for the search (bumps 256^2, 34
    // still texels: 4% slower than without the copy when the vertical pass searched too, 2% now; bricks 256^2, 68%
    // still: 2.25 -> 1.50 ms, 1 thread).
    Frame fv = fr;
    fv.copy_still = fr.copy_still && copied.load() * 8 >= (long long)t.width * t.height;
    run(threads, ow, 16,
        [&](int x0, int x1) { vertical_pass<P>(t, k, fv, x0, x1, mid, mid_v, mid_d, out, displ_out, column_samples); });
    return {(long long)t.width * t.height, dropped.load(), fr.e, copied.load(), row_pixels.load(),
            column_samples.load()};
}

// Pipelined reconstruction (paper section 3.2.2, Figure 11): rows are warped in occlusion-compatible order and
// every pixel the horizontal warp produces is rasterized into its column at once, connected to the last pixel
// that column received from the previous row. No intermediate image exists, so nothing a later texel of the same
// row overwrites is lost: any number of foldovers is handled without depth comparison.
template <class P>
struct ColumnSample {
    P v;
    P d;
    Rgba8 c;
};

template <class P>
struct PipelinedPart {
    std::vector<ColumnSample<P>> prev, cur;
    std::vector<uint8_t> prev_ok, cur_ok;
    long long dropped = 0;
    long long copied = 0;                          // still texels copied (warp_line_still_to)
    long long row_pixels = 0, column_samples = 0;  // PrewarpStats
};

template <class P>
inline bool column_connected(const ColumnSample<P>& a, const ColumnSample<P>& b, P threshold) {
    return displacements_joined(a.d, b.d, threshold);
}

// Rows j (v order, bottom = 0) from `first` towards `last` (exclusive) by `step`; writes only output v-lines in
// [y0, y1), the part of the output on this part's side of the epipole, so the two parts never touch the same
// pixel and can run concurrently with a result independent of the schedule.
template <class P>
void pipelined_part(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                    const Frame& fr, int first, int last, int step, int y0, int y1, PipelinedPart<P>& part,
                    ImageRGBA8& out, Image2D<uint8_t>* displ_out) {
    const int w = t.width, ow = fr.out_w(), oh = fr.out_h();
    const P thr = P(t.discontinuity_threshold);
    LineScratch<P> s;
    s.resize(w);
    const int split = split_index(k.epipole_u, w);
    part.prev.assign(size_t(ow), {});
    part.cur.assign(size_t(ow), {});
    part.prev_ok.assign(size_t(ow), 0);
    part.cur_ok.assign(size_t(ow), 0);
    const bool still = look_for_still(fr, k, tab, exact);
    const P ob = P(fr.e.bottom);
    for (int j = first; j != last; j += step) {
        const int r = t.height - 1 - j;
        part.dropped += row_samples(t, k, tab, exact, fr, r, s, still);
        std::fill(part.cur_ok.begin(), part.cur_ok.end(), uint8_t(0));
        LineInput<P, RowAttr<P>> in{w, s.pos.data(), s.color.data(), s.attr.data(), s.valid.data()};
        const RowConnected conn{t.breaks.empty() ? nullptr : &t.breaks[size_t(r) * size_t(w)]};
        // The centres of this row's and the previous row's own output lines: a pixel on the first, coming after
        // one on the second (or after nothing, or unconnected), is copied into its column (warp_line_still_to
        // says why that is exact).
        const P v_here = P(j) + P(0.5) + ob, v_prev = P(j - step) + P(0.5) + ob;
        auto row_put = [&](int x, Rgba8 c, const RowAttr<P>& a) {
            auto put = [&](int y, Rgba8 cc, P d) {
                if (y < y0 || y >= y1) return;
                out.at(x, oh - 1 - y) = cc;
                put_displ(displ_out, t.quant, x, oh - 1 - y, d);
            };
            const ColumnSample<P> now{a.v, a.d, c};
            ++part.row_pixels;
            if (!std::isfinite(a.v)) return;
            ++part.column_samples;
            const bool connected = part.prev_ok[x] && column_connected(part.prev[x], now, thr);
            if (still && a.v == v_here && (!connected || part.prev[x].v == v_prev))
                put(j + fr.e.bottom, Rgba8{c.r, c.g, c.b, 255}, a.d);
            else if (connected)
                raster_span(part.prev[x].v, part.prev[x].c, part.prev[x].d, a.v, c, a.d, oh, put);
            else
                raster_point(a.v, c, a.d, oh, put);
            part.cur[x] = now;
            part.cur_ok[x] = 1;
        };
        if (still && s.n_still > 0)
            part.copied += warp_line_still_to(in, s.still.data(), fr.e.left, split, ow, row_put, conn);
        else
            warp_line_to(in, split, ow, row_put, conn);
        std::swap(part.prev, part.cur);
        std::swap(part.prev_ok, part.cur_ok);
    }
}

template <class P>
PrewarpStats pipelined(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpTables& tab, bool exact,
                       const Frame& fr, int threads, ImageRGBA8& out, Image2D<uint8_t>* displ_out) {
    const int ow = fr.out_w(), oh = fr.out_h(), h = t.height;
    std::fill(out.pixels.begin(), out.pixels.end(), Rgba8{});
    if (displ_out) std::fill(displ_out->pixels.begin(), displ_out->pixels.end(), kEmptyIndex);
    const int split = split_index(k.epipole_v, h);
    const int ysplit = split_index(k.epipole_v + fr.e.bottom, oh);
    PipelinedPart<P> bottom, top;
    auto run_bottom = [&] { pipelined_part<P>(t, k, tab, exact, fr, 0, split, +1, 0, ysplit, bottom, out, displ_out); };
    auto run_top = [&] {
        pipelined_part<P>(t, k, tab, exact, fr, h - 1, split - 1, -1, ysplit, oh, top, out, displ_out);
    };
    if (threads == 1) {
        run_bottom();
        run_top();
    } else {
        tbb::parallel_invoke(run_bottom, run_top);
    }
    // The seam between the last rows of the two parts (rows split - 1 and split).
    const P thr = P(t.discontinuity_threshold);
    if (split > 0 && split < h) {
        for (int x = 0; x < ow; ++x) {
            if (!bottom.prev_ok[x] || !top.prev_ok[x]) continue;
            const ColumnSample<P>& a = bottom.prev[x];
            const ColumnSample<P>& b = top.prev[x];
            if (!column_connected(a, b, thr)) continue;
            raster_span(a.v, a.c, a.d, b.v, b.c, b.d, oh, [&](int y, Rgba8 c, P d) {
                out.at(x, oh - 1 - y) = c;
                put_displ(displ_out, t.quant, x, oh - 1 - y, d);
            });
        }
    }
    PrewarpStats st;
    st.texels = (long long)t.width * h;
    st.dropped = bottom.dropped + top.dropped;
    st.extent = fr.e;
    st.still_copied = bottom.copied + top.copied;
    st.row_pixels = bottom.row_pixels + top.row_pixels;
    st.column_samples = bottom.column_samples + top.column_samples;
    return st;
}

}  // namespace

namespace reference {

PrewarpStats prewarp(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options,
                     const PrewarpExtent& e, PrewarpWorkspace& ws, ImageRGBA8& out, Image2D<uint8_t>* displ_out) {
    Frame fr{relief.width, relief.height, {}};
    fr.copy_still = options.copy_still_runs && options.filter == Filter::point;
    fr.e = e;
    out.resize(fr.out_w(), fr.out_h());
    if (displ_out) displ_out->resize(fr.out_w(), fr.out_h(), kEmptyIndex);
    if (k.side == ViewSide::on_plane || relief.width == 0 || relief.height == 0) return {0, 0, fr.e};
    const PrewarpTables tab = PrewarpTables::build(k, relief.quant);
    if (options.method == Reconstruction::pipelined) {
        if (options.exact) return pipelined<double>(relief, k, tab, true, fr, options.threads, out, displ_out);
        return pipelined<float>(relief, k, tab, false, fr, options.threads, out, displ_out);
    }
    if (options.exact)
        return two_pass<double>(relief, k, tab, true, fr, options.threads, ws.mid_color, ws.mid_v_exact, ws.mid_d_exact,
                                out, displ_out, options.filter);
    return two_pass<float>(relief, k, tab, false, fr, options.threads, ws.mid_color, ws.mid_v, ws.mid_d, out, displ_out,
                           options.filter);
}

}  // namespace reference
}  // namespace rtm
