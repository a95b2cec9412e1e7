#include "objects/face_swap.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <type_traits>

#include "warp/line_warp.h"

namespace rtm {

namespace {

// Carried along G's rows: F's final row coordinate, F's displacement d' and G's own displacement.
struct SwapAttr {
    double v = 0, d = 0, g = 0;
};
inline SwapAttr attr_lerp(const SwapAttr& a, const SwapAttr& b, double t) {
    return {a.v * (1 - t) + b.v * t, a.d * (1 - t) + b.d * t, a.g * (1 - t) + b.g * t};
}
// Carried along the intermediate columns: d' and G's displacement.
struct ColAttr {
    double d = 0, g = 0;
};
inline ColAttr attr_lerp(const ColAttr& a, const ColAttr& b, double t) {
    return {a.d * (1 - t) + b.d * t, a.g * (1 - t) + b.g * t};
}

template <class Body>
void run_parallel(int n, int threads, const Body& body) {
    auto loop = [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const auto& r) { body(r.begin(), r.end()); });
    };
    if (threads > 0) {
        tbb::task_arena arena(threads);
        arena.execute(loop);
    } else {
        loop();
    }
}

}  // namespace

int FaceSwap::source_of(int target) const {
    int src = -1;
    for (int i = 0; i < 3; ++i) {
        // glm is column-major: m[column][row]; row `target` of the matrix.
        if (std::abs(m[i][target]) >
            1e-12 * (std::abs(m[0][target]) + std::abs(m[1][target]) + std::abs(m[2][target]))) {
            if (src >= 0) return -1;
            src = i;
        }
    }
    return src;
}

std::string FaceSwap::to_string() const {
    std::ostringstream o;
    o << "FaceSwap{";
    static const char* names[3] = {"u'", "v'", "d'"};
    static const char* src[3] = {"u_s", "v_s", "d"};
    for (int t = 0; t < 3; ++t) {
        o << (t ? ", " : "") << names[t] << " = " << offset[t];
        for (int i = 0; i < 3; ++i)
            if (m[i][t] != 0.0) o << " + " << m[i][t] << "*" << src[i];
    }
    return o.str() + "}";
}

FaceSwap make_face_swap(const ReliefGeometry& src, const ReliefGeometry& dst) {
    // X = o_s + a_s u + b_s v + f_s d = o_d + a_d u' + b_d v' + f_d d'  =>  (u', v', d') = B^-1 (X - o_d).
    const glm::dmat3 b_dst(dst.a, dst.b, dst.f());
    const glm::dmat3 inv = glm::inverse(b_dst);
    FaceSwap s;
    s.offset = inv * (src.origin - dst.origin);
    s.m = inv * glm::dmat3(src.a, src.b, src.f());
    return s;
}

void AdjacentBuffer::reset(int width, int height) {
    if (color.width != width || color.height != height) {
        color = ImageRGBA8(width, height);
        depth = ImageF(width, height);
    }
    std::fill(color.pixels.begin(), color.pixels.end(), Rgba8{});
    std::fill(depth.pixels.begin(), depth.pixels.end(), -std::numeric_limits<float>::infinity());
}

int first_pass_coordinate(const FaceSwap& s) {
    // Column 0 of m is where G's u_s goes (glm: m[column][row]).
    int t = -1;
    for (int i = 0; i < 3; ++i)
        if (s.m[0][i] != 0.0 && (t < 0 || std::abs(s.m[0][i]) > std::abs(s.m[0][t]))) t = i;
    if (t == 0 || t == 1) return t;
    // G's rows run along F's displacement: the row pass computes the coordinate G's displacement feeds.
    return std::abs(s.m[2][0]) >= std::abs(s.m[2][1]) ? 0 : 1;
}

long long warp_adjacent_face_reference(const ReliefTexture& g, const ReliefGeometry& f_geom, int width, int height,
                                       const PrewarpCoefficients& kf, bool exact, AdjacentWorkspace& ws,
                                       AdjacentBuffer& out, int threads) {
    const int gw = g.width, gh = g.height;
    const FaceSwap swap = make_face_swap(g.geometry, f_geom);
    // Which of F's final coordinates the pass along G's rows computes: the one G's rows spread along (u_i for a
    // row that runs along F's u or whose displacement does; else v_i), so that no row collapses onto one pixel.
    const int first = first_pass_coordinate(swap);
    const int n1 = first == 0 ? width : height;  // pass 1's output length (F's columns, or F's rows from the bottom)
    const int n2 = first == 0 ? height : width;  // pass 2's
    // The eye's foot on G's plane, in G's texel units: where G's occlusion-compatible order converges.
    const glm::dvec3 rel = kf.eye - g.geometry.origin;
    const double foot_u = glm::dot(rel, g.geometry.a) / glm::dot(g.geometry.a, g.geometry.a);
    const double foot_v = glm::dot(rel, g.geometry.b) / glm::dot(g.geometry.b, g.geometry.b);
    const int split_u = split_index(foot_u, gw), split_v = split_index(foot_v, gh);
    if (ws.mid_color.width != n1 || ws.mid_color.height != gh) {
        ws.mid_color = ImageRGBA8(n1, gh);
        ws.mid_v = Image2D<double>(n1, gh);
        ws.mid_d = Image2D<double>(n1, gh);
        ws.mid_g = Image2D<double>(n1, gh);
    }
    std::vector<long long> dropped_rows(size_t(gh), 0);

    // Pass 1: along G's rows to F's final coordinate `first`, carrying the other.
    run_parallel(gh, threads, [&](int r0, int r1) {
        std::vector<double> pos(static_cast<size_t>(gw));
        std::vector<SwapAttr> attr(static_cast<size_t>(gw));
        std::vector<Rgba8> color(static_cast<size_t>(gw));
        std::vector<uint8_t> valid(static_cast<size_t>(gw));
        for (int r = r0; r < r1; ++r) {
            const double vs = (gh - 1 - r) + 0.5;
            long long nd = 0;
            for (int x = 0; x < gw; ++x) {
                const ReliefTexel& t = g.texel(x, r);
                color[size_t(x)] = {t.r, t.g, t.b, 255};
                if (t.q == kEmptyIndex) {
                    valid[size_t(x)] = 0;
                    continue;
                }
                const double d = exact ? double(g.displ(x, r)) : g.quant.decode(t.q);
                const glm::dvec3 p = swap.apply(x + 0.5, vs, d);
                const double den = 1.0 + kf.k3 * p.z;
                const bool ok = den > 0.0;
                valid[size_t(x)] = ok;
                nd += !ok;
                const double ui = ok ? (p.x + kf.k1 * p.z) / den : 0.0, vi = ok ? (p.y + kf.k2 * p.z) / den : 0.0;
                pos[size_t(x)] = first == 0 ? ui : vi;
                attr[size_t(x)] = {first == 0 ? vi : ui, p.z, d};
            }
            dropped_rows[size_t(r)] = nd;
            Rgba8* oc = ws.mid_color.row(r);
            double* ov = ws.mid_v.row(r);
            double* od = ws.mid_d.row(r);
            double* og = ws.mid_g.row(r);
            std::fill(oc, oc + n1, Rgba8{});
            const uint8_t* brk = g.breaks.empty() ? nullptr : &g.breaks[size_t(r) * size_t(gw)];
            auto connected = [&](int a, int b) { return !brk || !(brk[std::min(a, b)] & kBreakRight); };
            auto put = [&](int x, Rgba8 c, const SwapAttr& a) {
                oc[x] = c;
                ov[x] = a.v;
                od[x] = a.d;
                og[x] = a.g;
            };
            LineInput<double, SwapAttr> in{gw, pos.data(), color.data(), attr.data(), valid.data()};
            warp_line_to(in, split_u, n1, put, connected);
        }
    });

    // Pass 2: along the intermediate columns (G's rows bottom first) to the other final coordinate, z-tested.
    const double threshold = g.breaks.empty() ? 0.0 : g.discontinuity_threshold;
    run_parallel(n1, threads, [&](int c0, int c1) {
        std::vector<double> pos(static_cast<size_t>(gh));
        std::vector<ColAttr> attr(static_cast<size_t>(gh));
        std::vector<Rgba8> color(static_cast<size_t>(gh));
        std::vector<uint8_t> valid(static_cast<size_t>(gh));
        for (int c = c0; c < c1; ++c) {
            for (int j = 0; j < gh; ++j) {
                const int r = gh - 1 - j;
                const Rgba8 col = ws.mid_color.at(c, r);
                color[size_t(j)] = col;
                valid[size_t(j)] = col.a != 0;
                pos[size_t(j)] = ws.mid_v.at(c, r);
                attr[size_t(j)] = {ws.mid_d.at(c, r), ws.mid_g.at(c, r)};
            }
            auto connected = [&](int a, int b) {
                return !(threshold > 0.0) || std::abs(attr[size_t(a)].g - attr[size_t(b)].g) <= threshold;
            };
            auto put = [&](int j, Rgba8 col, const ColAttr& a) {
                const int x = first == 0 ? c : j;
                const int row = height - 1 - (first == 0 ? j : c);
                float& z = out.depth.at(x, row);
                if (float(a.d) > z) {
                    z = float(a.d);
                    out.color.at(x, row) = col;
                }
            };
            LineInput<double, ColAttr> in{gh, pos.data(), color.data(), attr.data(), valid.data()};
            warp_line_to(in, split_v, n2, put, connected);
        }
    });
    long long dropped = 0;
    for (long long n : dropped_rows) dropped += n;
    return dropped;
}

namespace {

// For the faces of one box every component of the map has a single source: component i = offset[i] +
// m[src[i]][i] * (G's coordinate src[i]), every other entry of m exactly 0 (make_face_swap inverts a signed
// permutation with scales, whose cofactors are exact). False for any other pair of frames.
bool single_source_terms(const FaceSwap& s, std::array<int, 3>& src) {
    for (int i = 0; i < 3; ++i) {
        src[size_t(i)] = -1;
        for (int j = 0; j < 3; ++j) {
            if (s.m[j][i] == 0.0) continue;
            if (src[size_t(i)] >= 0) return false;
            src[size_t(i)] = j;
        }
        if (src[size_t(i)] < 0) return false;
    }
    return src[0] != src[1] && src[1] != src[2] && src[0] != src[2];
}

}  // namespace

namespace {

// What the fast schedule's two passes share.
struct AdjacentJob {
    const ReliefTexture* g = nullptr;
    bool exact = false;
    int first = 0, n1 = 0, n2 = 0, height = 0, split_u = 0, split_v = 0;
    int by_u = 0, by_v = 0, by_d = 0;  // the component of p each of G's coordinates feeds
    double k1 = 0, k2 = 0, k3 = 0;
    double offset_d = 0, scale_d = 0;  // the term of G's displacement: offset_d + scale_d * d
    double offset_v = 0, scale_v = 0;  // the term of G's row coordinate
    const double *col_term = nullptr, *level_term = nullptr, *level_d = nullptr;
    double threshold = 0;  // pass 2's discontinuity threshold on G's displacement (0: none)
    int c_lo = 0;          // pass 2's first column
    AdjacentWorkspace* ws = nullptr;
    AdjacentBuffer* out = nullptr;
    long long* dropped_rows = nullptr;
};

// Pass 1 over rows r0 .. r1 - 1 of G: as the reference's, into one array of intermediate samples. The coordinates
// of a row are computed first, all of them and without branches (the loop vectorizes), then the row is warped; a
// texel that is empty or cannot be pre-warped is invalid, so what its lanes computed is never read.
inline void adjacent_row_pass(const AdjacentJob& j, int r0, int r1) {
    const ReliefTexture& g = *j.g;
    const int gw = g.width, gh = g.height;
    AdjacentWorkspace& ws = *j.ws;
    std::vector<double> row_v(static_cast<size_t>(gw)), dt_v(static_cast<size_t>(gw)), d_v(static_cast<size_t>(gw));
    std::vector<double> pos(static_cast<size_t>(gw)), other(static_cast<size_t>(gw));
    std::vector<uint8_t> nonempty(static_cast<size_t>(gw)), valid(static_cast<size_t>(gw));
    std::vector<SwapAttr> attr(static_cast<size_t>(gw));
    std::vector<Rgba8> color(static_cast<size_t>(gw));
    const double k1 = j.k1, k2 = j.k2, k3 = j.k3;
    for (int r = r0; r < r1; ++r) {
        AdjacentSample* o = ws.mid.row(r);
        int& lo = ws.mid_lo[size_t(r)];
        int& hi = ws.mid_hi[size_t(r)];
        if (hi >= lo) std::fill(o + lo, o + hi + 1, AdjacentSample{});
        lo = 0, hi = -1;
        const double row_term = j.offset_v + j.scale_v * ((gh - 1 - r) + 0.5);
        const ReliefTexel* tr = &g.texels[size_t(r) * size_t(gw)];
        double* __restrict dt = dt_v.data();
        double* __restrict dd = d_v.data();
        uint8_t* __restrict ne = nonempty.data();
        Rgba8* __restrict cl = color.data();
        if (j.exact) {
            const float* dr = &g.displacement[size_t(r) * size_t(gw)];
            for (int x = 0; x < gw; ++x) {
                dd[x] = double(dr[x]);
                dt[x] = j.offset_d + j.scale_d * dd[x];
            }
        } else {
            for (int x = 0; x < gw; ++x) {
                dd[x] = j.level_d[tr[x].q];
                dt[x] = j.level_term[tr[x].q];
            }
        }
        for (int x = 0; x < gw; ++x) {
            const ReliefTexel& t = tr[x];
            cl[x] = {t.r, t.g, t.b, 255};
            ne[x] = t.q != kEmptyIndex;
        }
        std::fill(row_v.begin(), row_v.end(), row_term);
        const double* srcs[3];
        srcs[j.by_u] = j.col_term;
        srcs[j.by_v] = row_v.data();
        srcs[j.by_d] = dt;
        const double* __restrict px = srcs[0];
        const double* __restrict py = srcs[1];
        const double* __restrict pz = srcs[2];
        double* __restrict ps = pos.data();
        double* __restrict ot = other.data();
        uint8_t* __restrict va = valid.data();
        long long nd = 0;
        int n_ok = 0;
        // The reference's operations in its order: den = 1 + k3 d', u_i = (u' + k1 d') / den, v_i likewise.
        auto coordinates = [&](auto first_is_u) {
            for (int x = 0; x < gw; ++x) {
                const double den = 1.0 + k3 * pz[x];
                const double ui = (px[x] + k1 * pz[x]) / den, vi = (py[x] + k2 * pz[x]) / den;
                const bool ok = den > 0.0;
                ps[x] = first_is_u ? ui : vi;
                ot[x] = first_is_u ? vi : ui;
                va[x] = uint8_t(ok & (ne[x] != 0));
                nd += ne[x] & !ok;
                n_ok += va[x];
            }
        };
        if (j.first == 0)
            coordinates(std::true_type{});
        else
            coordinates(std::false_type{});
        j.dropped_rows[r] = nd;
        if (n_ok == 0) continue;
        for (int x = 0; x < gw; ++x) attr[size_t(x)] = {ot[x], pz[x], dd[x]};
        const uint8_t* brk = g.breaks.empty() ? nullptr : &g.breaks[size_t(r) * size_t(gw)];
        auto connected = [&](int a, int b) { return !brk || !(brk[std::min(a, b)] & kBreakRight); };
        int wlo = j.n1, whi = -1;
        auto put = [&](int x, Rgba8 c, const SwapAttr& a) {
            o[x] = {a.v, a.d, a.g, c};
            wlo = std::min(wlo, x);
            whi = std::max(whi, x);
        };
        LineInput<double, SwapAttr> in{gw, pos.data(), color.data(), attr.data(), valid.data()};
        warp_line_to(in, j.split_u, j.n1, put, connected);
        lo = wlo, hi = whi;
    }
}

// Pass 2 over intermediate columns c_lo + i0 .. c_lo + i1 - 1: as the reference's, gathering each column from the
// one array, only from the rows whose extent holds it (the others hold the empty sample there), z-tested into out.
inline void adjacent_column_pass(const AdjacentJob& j, int i0, int i1) {
    const int gh = j.g->height;
    const AdjacentWorkspace& ws = *j.ws;
    AdjacentBuffer& out = *j.out;
    std::vector<double> pos(static_cast<size_t>(gh));
    std::vector<ColAttr> attr(static_cast<size_t>(gh));
    std::vector<Rgba8> color(static_cast<size_t>(gh));
    std::vector<uint8_t> valid(static_cast<size_t>(gh));
    const double threshold = j.threshold;
    for (int c = j.c_lo + i0; c < j.c_lo + i1; ++c) {
        bool any = false;
        for (int k = 0; k < gh; ++k) {
            const int r = gh - 1 - k;
            if (c < ws.mid_lo[size_t(r)] || c > ws.mid_hi[size_t(r)]) {
                color[size_t(k)] = Rgba8{};
                valid[size_t(k)] = 0;
                continue;
            }
            const AdjacentSample& s = ws.mid.at(c, r);
            color[size_t(k)] = s.c;
            valid[size_t(k)] = s.c.a != 0;
            any |= s.c.a != 0;
            pos[size_t(k)] = s.v;
            attr[size_t(k)] = {s.d, s.g};
        }
        if (!any) continue;
        auto connected = [&](int a, int b) {
            return !(threshold > 0.0) || std::abs(attr[size_t(a)].g - attr[size_t(b)].g) <= threshold;
        };
        auto put = [&](int k, Rgba8 col, const ColAttr& a) {
            const int x = j.first == 0 ? c : k;
            const int row = j.height - 1 - (j.first == 0 ? k : c);
            float& z = out.depth.at(x, row);
            if (float(a.d) > z) {
                z = float(a.d);
                out.color.at(x, row) = col;
            }
        };
        LineInput<double, ColAttr> in{gh, pos.data(), color.data(), attr.data(), valid.data()};
        warp_line_to(in, j.split_v, j.n2, put, connected);
    }
}

// The two passes compiled for several instruction sets, chosen by the pre-warp's target (PrewarpOptions::isa,
// warp/isa.h): from SSE4.1 on the line warp's floor and ceil are one instruction (a dozen without), and with AVX2
// the coordinate loop's divisions run 4 to a vector. `flatten` inlines the passes and the line warp
// (warp/line_warp.h) into each variant: left as a call, the line warp is one instance compiled for the baseline, and
// the variants gained 10% instead of 30% (docs/perf-history.md). Every variant computes the same values: the same
// IEEE operations in the same order, never contracted into an FMA (face_swap.cpp is compiled with -ffp-contract=off
// and no variant enables FMA); tests/objects/face_swap_test.cpp runs each against the reference.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define RTM_ADJACENT_VARIANTS 1
__attribute__((target("avx2"), flatten)) void row_pass_avx2(const AdjacentJob& j, int r0, int r1) {
    adjacent_row_pass(j, r0, r1);
}
__attribute__((target("avx2"), flatten)) void column_pass_avx2(const AdjacentJob& j, int i0, int i1) {
    adjacent_column_pass(j, i0, i1);
}
__attribute__((target("sse4.2"), flatten)) void row_pass_sse4(const AdjacentJob& j, int r0, int r1) {
    adjacent_row_pass(j, r0, r1);
}
__attribute__((target("sse4.2"), flatten)) void column_pass_sse4(const AdjacentJob& j, int i0, int i1) {
    adjacent_column_pass(j, i0, i1);
}
#endif
#if defined(__GNUC__) || defined(__clang__)
#define RTM_FLATTEN __attribute__((flatten))
#else
#define RTM_FLATTEN
#endif
RTM_FLATTEN void row_pass_baseline(const AdjacentJob& j, int r0, int r1) { adjacent_row_pass(j, r0, r1); }
RTM_FLATTEN void column_pass_baseline(const AdjacentJob& j, int i0, int i1) { adjacent_column_pass(j, i0, i1); }

using PassFn = void (*)(const AdjacentJob&, int, int);
void choose_passes(Isa isa, PassFn& rows, PassFn& columns) {
    rows = row_pass_baseline;
    columns = column_pass_baseline;
#ifdef RTM_ADJACENT_VARIANTS
    const Isa target = resolve_isa(isa);
    if (target == Isa::avx512 || target == Isa::avx2) {
        rows = row_pass_avx2;
        columns = column_pass_avx2;
    } else if (target == Isa::sse4) {
        rows = row_pass_sse4;
        columns = column_pass_sse4;
    }
#else
    (void)isa;
#endif
}

}  // namespace

long long warp_adjacent_face(const ReliefTexture& g, const ReliefGeometry& f_geom, int width, int height,
                             const PrewarpCoefficients& kf, bool exact, AdjacentWorkspace& ws, AdjacentBuffer& out,
                             int threads, Isa isa) {
    const FaceSwap swap = make_face_swap(g.geometry, f_geom);
    std::array<int, 3> src{};
    if (!single_source_terms(swap, src))
        return warp_adjacent_face_reference(g, f_geom, width, height, kf, exact, ws, out, threads);
    const int gw = g.width, gh = g.height;
    AdjacentJob j;
    j.g = &g;
    j.exact = exact;
    j.first = first_pass_coordinate(swap);
    j.n1 = j.first == 0 ? width : height;
    j.n2 = j.first == 0 ? height : width;
    j.height = height;
    const glm::dvec3 rel = kf.eye - g.geometry.origin;
    const double foot_u = glm::dot(rel, g.geometry.a) / glm::dot(g.geometry.a, g.geometry.a);
    const double foot_v = glm::dot(rel, g.geometry.b) / glm::dot(g.geometry.b, g.geometry.b);
    j.split_u = split_index(foot_u, gw);
    j.split_v = split_index(foot_v, gh);
    // Two samples (64 bytes) of padding per row: with a row of 2^k samples the column pass's reads, one row apart,
    // would all fall in the same few cache sets and evict each other before the next column reads the same lines.
    const int stride = j.n1 + 2;
    if (ws.mid.width != stride || ws.mid.height != gh || ws.mid_lo.size() != size_t(gh)) {
        ws.mid = Image2D<AdjacentSample>(stride, gh);  // every sample empty
        ws.mid_lo.assign(size_t(gh), 0);
        ws.mid_hi.assign(size_t(gh), -1);
    }

    // The reference's p = offset + m * (u_s, v_s, d), term by term: each component is offset[i] + m[j][i] * source j
    // (the zero entries add zeros, which change no value), so the terms of G's columns, of a row and of each
    // quantization level are computed once, with the same operations.
    auto term = [&](int i, double c) { return swap.offset[i] + swap.m[src[size_t(i)]][i] * c; };
    for (int i = 0; i < 3; ++i) (src[size_t(i)] == 0 ? j.by_u : src[size_t(i)] == 1 ? j.by_v : j.by_d) = i;
    j.offset_d = swap.offset[j.by_d];
    j.scale_d = swap.m[2][j.by_d];
    j.offset_v = swap.offset[j.by_v];
    j.scale_v = swap.m[1][j.by_v];
    std::vector<double> col_term(static_cast<size_t>(gw)), level_term(256), level_d(256);
    for (int x = 0; x < gw; ++x) col_term[size_t(x)] = term(j.by_u, x + 0.5);
    for (int q = 0; q < 256; ++q) {
        level_d[size_t(q)] = g.quant.decode(uint8_t(q));
        level_term[size_t(q)] = term(j.by_d, level_d[size_t(q)]);
    }
    j.col_term = col_term.data();
    j.level_term = level_term.data();
    j.level_d = level_d.data();
    j.k1 = kf.k1, j.k2 = kf.k2, j.k3 = kf.k3;
    j.ws = &ws;
    j.out = &out;
    std::vector<long long> dropped_rows(size_t(gh), 0);
    j.dropped_rows = dropped_rows.data();

    PassFn row_pass = nullptr, column_pass = nullptr;
    choose_passes(isa, row_pass, column_pass);
    j.threshold = g.breaks.empty() ? 0.0 : g.discontinuity_threshold;
    // Both passes in one task arena (one thread: none): an object pre-warps four to six adjacent faces a frame, and
    // each arena wakes its threads afresh.
    auto passes = [&] {
        auto over = [&](int n, PassFn pass) {
            if (threads == 1)
                pass(j, 0, n);
            else
                tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const auto& r) { pass(j, r.begin(), r.end()); });
        };
        over(gh, row_pass);
        // The columns any row wrote to; the others hold nothing.
        int c_lo = j.n1, c_hi = -1;
        for (int r = 0; r < gh; ++r)
            if (ws.mid_hi[size_t(r)] >= ws.mid_lo[size_t(r)]) {
                c_lo = std::min(c_lo, ws.mid_lo[size_t(r)]);
                c_hi = std::max(c_hi, ws.mid_hi[size_t(r)]);
            }
        j.c_lo = c_lo;
        if (c_hi >= c_lo) over(c_hi - c_lo + 1, column_pass);
    };
    if (threads > 1) {
        tbb::task_arena arena(threads);
        arena.execute(passes);
    } else {
        passes();
    }
    long long dropped = 0;
    for (long long n : dropped_rows) dropped += n;
    return dropped;
}

}  // namespace rtm
