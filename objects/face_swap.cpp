#include "objects/face_swap.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "warp/line_warp.h"
#include "warp/task_arenas.h"

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
        task_arena_for(threads).execute(loop);
    } else {
        loop();
    }
}

}  // namespace

void parallel_ranges(int n, int threads, const std::function<void(int, int)>& body) {
    if (n <= 0) return;
    if (threads == 1) {
        body(0, n);
        return;
    }
    run_parallel(n, threads, body);
}

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

void AdjacentBuffer::reset(int width, int height, int threads) {
    if (color.width != width || color.height != height) {
        color = ImageRGBA8(width, height);
        depth = ImageF(width, height);
    }
    parallel_ranges(height, threads, [&](int r0, int r1) {
        const size_t i0 = size_t(r0) * size_t(width), i1 = size_t(r1) * size_t(width);
        std::fill(color.pixels.begin() + std::ptrdiff_t(i0), color.pixels.begin() + std::ptrdiff_t(i1), Rgba8{});
        std::fill(depth.pixels.begin() + std::ptrdiff_t(i0), depth.pixels.begin() + std::ptrdiff_t(i1),
                  -std::numeric_limits<float>::infinity());
    });
}

void AdjacentNeed::assign(const Image2D<uint8_t>& needed, int threads, std::array<bool, 2> orientations) {
    width = needed.width;
    height = needed.height;
    pixels.resize(needed.pixels.size());
    count = 0;
    for (size_t i = 0; i < pixels.size(); ++i) count += pixels[i] = needed.pixels[i] != 0;
    index(threads, orientations);
}

void AdjacentNeed::assign_holes(const ImageRGBA8& own, int threads, std::array<bool, 2> orientations) {
    width = own.width;
    height = own.height;
    pixels.resize(own.pixels.size());
    std::atomic<long long> n{0};
    parallel_ranges(height, threads, [&](int r0, int r1) {
        const size_t i0 = size_t(r0) * size_t(width), i1 = size_t(r1) * size_t(width);
        if constexpr (std::endian::native == std::endian::little && sizeof(Rgba8) == 4) {
            // Alpha is each pixel's top byte: a < 128 where its top bit is clear (one word a pixel: vectorized).
            const unsigned char* __restrict src = reinterpret_cast<const unsigned char*>(own.pixels.data());
            uint8_t* __restrict dst = pixels.data();
            for (size_t i = i0; i < i1; ++i) {
                uint32_t v;
                std::memcpy(&v, src + 4 * i, 4);
                dst[i] = uint8_t((~v) >> 31);
            }
        } else {
            for (size_t i = i0; i < i1; ++i) pixels[i] = own.pixels[i].a < 128;
        }
        long long k = 0;
        for (size_t i = i0; i < i1; ++i) k += pixels[i];
        n += k;
    });
    count = n;
    index(threads, orientations);
}

void AdjacentNeed::index(int threads, std::array<bool, 2> orientations) {
    if (width > 65535 || height > 65535)
        throw std::invalid_argument("AdjacentNeed: " + std::to_string(width) + "x" + std::to_string(height) +
                                    " pixels, more than 65535 a side");
    const uint8_t* bottom = pixels.data() + size_t(std::max(height - 1, 0)) * size_t(width);  // F's row j = 0
    built = orientations;
    for (int o = 0; o < 2; ++o) {
        if (!built[size_t(o)]) continue;
        Lines& l = lines[size_t(o)];
        l.n1 = o == 0 ? width : height;
        l.n2 = o == 0 ? height : width;
        l.at = bottom;
        l.step_line = o == 0 ? 1 : -std::ptrdiff_t(width);
        l.step_pos = o == 0 ? -std::ptrdiff_t(width) : 1;
        l.prefix.resize(size_t(l.n1) * size_t(l.n2 + 1));
        l.lo.assign(size_t(l.n1), l.n2);
        l.hi.assign(size_t(l.n1), -1);
    }
    Lines& l0 = lines[0];  // line x, position j = height - 1 - row
    Lines& l1 = lines[1];  // line j, position x
    // lines[0]: F's rows from the bottom, each adding to the columns' counts.
    // (Branch-free over restrict pointers, so that the loops vectorize: the branches and possible aliasing kept them
    // scalar, and building the need was 8% of an object's pre-warp.)
    auto columns = [&] {
        std::fill(l0.prefix.begin(), l0.prefix.begin() + width, uint16_t(0));
        int* __restrict lo0 = l0.lo.data();
        int* __restrict hi0 = l0.hi.data();
        const int none = l0.n2, w = width, h = height;
        for (int j = 0; j < h; ++j) {
            const uint8_t* __restrict v = bottom - std::ptrdiff_t(j) * w;
            const uint16_t* __restrict below = &l0.prefix[size_t(j) * size_t(w)];
            uint16_t* __restrict p0 = &l0.prefix[size_t(j + 1) * size_t(w)];
            for (int x = 0; x < w; ++x) p0[x] = uint16_t(below[x] + v[x]);
            // lo: the first j with a needed pixel (rows come in increasing j), hi: the last.
            for (int x = 0; x < w; ++x) {
                lo0[x] = std::min(lo0[x], v[x] ? j : none);
                hi0[x] = v[x] ? j : hi0[x];
            }
        }
    };
    // lines[1]: running counts along F's rows, position-major, 16 lines at a time so that each position writes one
    // cache line of counts (one line at a time wrote one count per cache line, a store that missed the cache for each
    // pixel).
    auto rows = [&] {
        constexpr int kBlock = 16;
        for (int j0 = 0; j0 < height; j0 += kBlock) {
            const int nb = std::min(kBlock, height - j0);
            int run[kBlock] = {};
            const uint8_t* v[kBlock];
            for (int b = 0; b < nb; ++b) v[b] = bottom - std::ptrdiff_t(j0 + b) * width;
            uint16_t* p1 = l1.prefix.data() + j0;
            for (int b = 0; b < nb; ++b) p1[b] = 0;
            for (int x = 0; x < width; ++x) {
                uint16_t* out = p1 + size_t(x + 1) * size_t(height);
                for (int b = 0; b < nb; ++b) {
                    run[b] += v[b][x];
                    out[b] = uint16_t(run[b]);
                }
            }
            for (int b = 0; b < nb; ++b) {
                // The first and last needed pixel of the line: a search from each end that stops at the first one
                // (the loop it replaced tested every pixel with two branches).
                const uint8_t* first = std::find_if(v[b], v[b] + width, [](uint8_t q) { return q != 0; });
                int last = -1;
                for (int x = width - 1; x >= 0 && first != v[b] + width; --x)
                    if (v[b][x]) {
                        last = x;
                        break;
                    }
                l1.lo[size_t(j0 + b)] = int(first - v[b]);
                l1.hi[size_t(j0 + b)] = last;
            }
        }
    };
    if (threads == 1 || !built[0] || !built[1]) {
        if (built[0]) columns();
        if (built[1]) rows();
    } else {
        auto both = [&] { tbb::parallel_invoke(columns, rows); };
        if (threads > 1)
            task_arena_for(threads).execute(both);
        else
            both();
    }
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
    double threshold = 0;                       // pass 2's discontinuity threshold on G's displacement (0: none)
    int c_lo = 0;                               // pass 2's first column
    const AdjacentNeed::Lines* need = nullptr;  // the needed pixels in the passes' orientation, or null: all
    int chunks = 0;                             // chunks of kRowChunk texels per row of G
    const AdjacentChunks* levels = nullptr;     // G's chunks made once, or null: from its texels
    AdjacentWorkspace* ws = nullptr;
    AdjacentBuffer* out = nullptr;
    long long* dropped_rows = nullptr;
};

// One row's inputs to the line warp, per thread: kept in thread-local storage that only grows (row_scratch), since the
// passes run as many small tasks a frame and allocating ten vectors in each was 5% of an object's pre-warp. Not
// inlined (row_scratch, column_scratch): inlined, GCC computed the thread-local's address again inside the passes'
// loops, as a call in position-independent code (adjacent faces 3% to 5% slower).
struct RowScratch {
    std::vector<double> row_v, dt_v, d_v, pos, other;
    std::vector<uint8_t> nonempty, valid, lines;
    std::vector<std::pair<int, int>> ranges;  // the samples to warp (row_chunks)
    std::vector<SwapAttr> attr;
    std::vector<Rgba8> color;
    void fit(int gw, int n1) {
        const size_t w = size_t(gw);
        if (row_v.size() < w) {
            for (auto* v : {&row_v, &dt_v, &d_v, &pos, &other}) v->resize(w);
            nonempty.resize(w), valid.resize(w), attr.resize(w), color.resize(w);
        }
        if (lines.size() < size_t(n1)) lines.resize(size_t(n1));
    }
};
[[gnu::noinline]] RowScratch& row_scratch(int gw, int n1) {
    thread_local RowScratch s;
    s.fit(gw, n1);
    return s;
}

// One intermediate line's inputs to the column pass, per thread (as RowScratch).
struct ColumnScratch {
    std::vector<double> pos;
    std::vector<ColAttr> attr;
    std::vector<Rgba8> color;
    std::vector<uint8_t> valid;
};
[[gnu::noinline]] ColumnScratch& column_scratch(int gh) {
    thread_local ColumnScratch s;
    if (s.pos.size() < size_t(gh)) {
        s.pos.resize(size_t(gh)), s.attr.resize(size_t(gh));
        s.color.resize(size_t(gh)), s.valid.resize(size_t(gh));
    }
    return s;
}

// Row r's coordinates for texels xb .. xe - 1 without branches (the loops vectorize), into s at the texels' indices:
// pos (F's coordinate the row pass computes), other (F's other coordinate), valid, colour, and the d' and G's
// displacement the attributes carry. A texel that is empty or cannot be pre-warped is invalid, so what its lanes
// computed is never read. Returns the number of valid texels; `dropped` (if not null) gets the texels that could not
// be pre-warped.
inline int row_coordinates(const AdjacentJob& j, int r, RowScratch& s, int xb, int xe, long long* dropped) {
    const ReliefTexture& g = *j.g;
    const int gw = g.width, gh = g.height;
    const double k1 = j.k1, k2 = j.k2, k3 = j.k3;
    const double row_term = j.offset_v + j.scale_v * ((gh - 1 - r) + 0.5);
    const ReliefTexel* tr = &g.texels[size_t(r) * size_t(gw)];
    double* __restrict dt = s.dt_v.data();
    double* __restrict dd = s.d_v.data();
    uint8_t* __restrict ne = s.nonempty.data();
    Rgba8* __restrict cl = s.color.data();
    if (j.exact) {
        const float* dr = &g.displacement[size_t(r) * size_t(gw)];
        for (int x = xb; x < xe; ++x) {
            dd[x] = double(dr[x]);
            dt[x] = j.offset_d + j.scale_d * dd[x];
        }
    } else {
        for (int x = xb; x < xe; ++x) {
            dd[x] = j.level_d[tr[x].q];
            dt[x] = j.level_term[tr[x].q];
        }
    }
    for (int x = xb; x < xe; ++x) {
        const ReliefTexel& t = tr[x];
        cl[x] = {t.r, t.g, t.b, 255};
        ne[x] = t.q != kEmptyIndex;
    }
    std::fill(s.row_v.begin() + xb, s.row_v.begin() + xe, row_term);
    const double* srcs[3];
    srcs[j.by_u] = j.col_term;
    srcs[j.by_v] = s.row_v.data();
    srcs[j.by_d] = dt;
    const double* __restrict px = srcs[0];
    const double* __restrict py = srcs[1];
    const double* __restrict pz = srcs[2];
    double* __restrict ps = s.pos.data();
    double* __restrict ot = s.other.data();
    uint8_t* __restrict va = s.valid.data();
    long long nd = 0;
    int n_ok = 0;
    // The reference's operations in its order: den = 1 + k3 d', u_i = (u' + k1 d') / den, v_i likewise.
    // Two loops: the coordinates alone (doubles only: four divisions a vector), then validity and counts (bytes).
    // Together in one loop they did not vectorize, and the scalar divisions were a quarter of the row pass.
    auto coordinates = [&](auto first_is_u, const double* __restrict qx, const double* __restrict qy,
                           const double* __restrict qz, double* __restrict qs, double* __restrict qo) {
        for (int x = xb; x < xe; ++x) {
            const double den = 1.0 + k3 * qz[x];
            const double ui = (qx[x] + k1 * qz[x]) / den, vi = (qy[x] + k2 * qz[x]) / den;
            qs[x] = first_is_u ? ui : vi;
            qo[x] = first_is_u ? vi : ui;
        }
    };
    if (j.first == 0)
        coordinates(std::true_type{}, px, py, pz, ps, ot);
    else
        coordinates(std::false_type{}, px, py, pz, ps, ot);
    for (int x = xb; x < xe; ++x) {
        const bool ok = 1.0 + k3 * pz[x] > 0.0;
        va[x] = uint8_t(ok & (ne[x] != 0));
        nd += ne[x] & !ok;
        n_ok += va[x];
    }
    if (dropped) *dropped = nd;
    if (n_ok > 0)
        for (int x = xb; x < xe; ++x) s.attr[size_t(x)] = {ot[x], pz[x], dd[x]};
    return n_ok;
}

// The pixels a coordinate range [lo, hi] can reach on a line: a span's pixels have their centres in it, a point's
// pixel holds it, so floor(lo) .. floor(hi); widened by 1e-7 of a pixel plus 1e-9 of the value, far more than the
// rounding that separates the bounds from the samples' computed values. Clamped to +-1e9 (beyond any line).
inline int first_pixel(double lo) {
    const double w = lo - (1e-7 + 1e-9 * std::abs(lo));
    return int(std::floor(std::clamp(w, -1e9, 1e9)));
}
inline int last_pixel(double hi) {
    const double w = hi + (1e-7 + 1e-9 * std::abs(hi));
    return int(std::floor(std::clamp(w, -1e9, 1e9)));
}

// The line warp of warp/line_warp.h (warp_line_to) drawing only the pixels clip_lo .. clip_hi of the output (within
// 0 .. n_out - 1) and reading only the samples of `ranges` (sorted, disjoint, inclusive): the same runs, spans and
// points in the same order as over the whole line, each pixel's value from raster_span_pixels as there (a pixel's value
// depends on its index alone), the others left out. Samples outside the ranges are taken as invalid (and not read), so
// a range starts a run at its first sample (a point where the whole line may have drawn a span: the caller makes sure
// such a pixel is not one it keeps). The whole line's order is kept across ranges: every range's part before `split`
// from the first range on, then every range's part from `split` on, from the last range back, then the span joining
// the two parts (warp_line_to's order).
template <class A, class Put, class Connected, class Wanted = AllPixels>
void warp_line_ranges(const LineInput<double, A>& in, int split, int clip_lo, int clip_hi,
                      std::span<const std::pair<int, int>> ranges, Put&& put, Connected&& connected,
                      Wanted&& wanted = {}) {
    const double lo_clip = clip_lo, hi_clip = clip_hi;
    auto point = [&](int k) {
        const double p = in.pos[k];
        if (!(p >= lo_clip && p < hi_clip + 1.0)) return;
        Rgba8 c = in.color[k];
        c.a = 255;
        put(int(p), c, in.attr[k]);
    };
    auto span = [&](int a, int b) {
        const double pa = in.pos[a], pb = in.pos[b];
        if (pa == pb) return;
        double lo, hi;
        if (pb > pa) {
            lo = std::floor(pa - 0.5) + 1.0;
            hi = std::floor(pb - 0.5);
        } else {
            lo = std::ceil(pb - 0.5);
            hi = std::ceil(pa - 0.5) - 1.0;
        }
        lo = std::max(lo, lo_clip);
        hi = std::min(hi, hi_clip);
        if (!(lo <= hi)) return;
        raster_span_pixels(pa, in.color[a], in.attr[a], pb, in.color[b], in.attr[b], int(lo), int(hi), put, wanted);
    };
    auto part = [&](int first, int last, int step) {
        int prev = -1;
        for (int k = first; k != last; k += step) {
            if (!in.valid[k] || !std::isfinite(in.pos[k])) {
                prev = -1;
                continue;
            }
            if (prev < 0 || !connected(prev, k))
                point(k);
            else
                span(prev, k);
            prev = k;
        }
        return prev;
    };
    int left_last = -1, right_last = -1;
    for (const auto& [k_lo, k_hi] : ranges)
        if (k_lo < split) left_last = part(k_lo, std::min(split, k_hi + 1), +1);
    for (size_t i = ranges.size(); i-- > 0;) {
        const auto& [k_lo, k_hi] = ranges[i];
        if (k_hi >= split) right_last = part(k_hi, std::max(split, k_lo) - 1, -1);
    }
    if (left_last >= 0 && right_last >= 0 && left_last == split - 1 && right_last == split &&
        connected(left_last, right_last))
        span(left_last, right_last);
}

// The same over the samples k_lo .. k_hi (k_hi < 0: to the end).
template <class A, class Put, class Connected, class Wanted = AllPixels>
void warp_line_clipped(const LineInput<double, A>& in, int split, int clip_lo, int clip_hi, Put&& put,
                       Connected&& connected, int k_lo = 0, int k_hi = -1, Wanted&& wanted = {}) {
    const std::pair<int, int> range{k_lo, k_hi < 0 ? in.n - 1 : k_hi};
    warp_line_ranges(in, split, clip_lo, clip_hi, std::span<const std::pair<int, int>>(&range, 1),
                     std::forward<Put>(put), std::forward<Connected>(connected), std::forward<Wanted>(wanted));
}

constexpr int kRowChunk = kAdjacentChunk;

// Chunk c of a row of n samples (kRowChunk samples, read with one neighbour on each side) whose samples' positions lie
// in [mn, mx]: appended to `out` (merged with the last range when they meet) if the pixels that range reaches hold a
// line to draw (lines[x] for x in cl .. ch).
inline void keep_chunk(int c, int n, double mn, double mx, int cl, int ch, const uint8_t* lines,
                       std::vector<std::pair<int, int>>& out) {
    const int c0 = std::max(first_pixel(mn), cl), c1 = std::min(last_pixel(mx), ch);
    bool keep = false;
    for (int x = c0; x <= c1 && !keep; ++x) keep = lines[x] != 0;
    if (!keep) return;
    const int a = std::max(0, c * kRowChunk - 1), b = std::min(n - 1, (c + 1) * kRowChunk);
    if (!out.empty() && out.back().second >= a - 1)
        out.back().second = b;
    else
        out.emplace_back(a, b);
}

// The range of (p + k z) / (1 + k3 z) over the box [lo[i], hi[i]] x [lo[2], hi[2]] where its denominator is positive:
// increasing in p and monotone in z, so its extremes are at the corners; all of the line when not finite.
inline void corner_bound(const double* lo, const double* hi, int i, double k, double k3, double& mn, double& mx) {
    const double inf = std::numeric_limits<double>::infinity();
    mn = inf, mx = -inf;
    for (double pz : {lo[2], hi[2]})
        for (double pp : {lo[i], hi[i]}) {
            const double val = (pp + k * pz) / (1.0 + k3 * pz);
            mn = std::min(mn, val), mx = std::max(mx, val);
        }
    if (!std::isfinite(mn) || !std::isfinite(mx)) mn = -inf, mx = inf;
}

// The samples of a row worth warping, given the intermediate lines it must draw: chunks of kRowChunk samples, each
// read as the samples x0 - 1 .. x0 + kRowChunk (its own and one neighbour on each side), kept when the range of their
// positions reaches a line to draw (pixels first_pixel .. last_pixel of that range, as for a row). Every span of the
// line warp joins two samples of one chunk so read, and every point is one chunk's sample: a span or point drawing a
// kept line belongs to a kept chunk. A kept chunk's range starts and ends one sample into its neighbours, so its spans
// are drawn as over the whole row; the runs it starts at its ends draw (as points) only within a dropped chunk's range,
// which holds no line drawn. Ranges that meet are merged. Appends to `out`, sorted.
inline void row_chunks(const double* pos, const uint8_t* valid, int n, int cl, int ch, const uint8_t* lines,
                       std::vector<std::pair<int, int>>& out) {
    for (int c = 0; c * kRowChunk < n; ++c) {
        const int a = std::max(0, c * kRowChunk - 1), b = std::min(n - 1, (c + 1) * kRowChunk);
        double mn = std::numeric_limits<double>::infinity(), mx = -mn;
        for (int x = a; x <= b; ++x)
            if (valid[x] && std::isfinite(pos[x])) mn = std::min(mn, pos[x]), mx = std::max(mx, pos[x]);
        if (mn <= mx) keep_chunk(c, n, mn, mx, cl, ch, lines, out);
    }
}

// Row r's chunks of relief t (AdjacentChunks): per chunk, the first and last non-empty texel of the samples it reads
// and the extremes of their levels and (with `exact`) displacements.
inline void chunk_row(const ReliefTexture& t, int r, int per_row, bool exact, AdjacentChunks::Chunk* out) {
    for (int k = 0; k < per_row; ++k) {
        AdjacentChunks::Chunk c;
        const int a = std::max(0, k * kAdjacentChunk - 1), b = std::min(t.width - 1, (k + 1) * kAdjacentChunk);
        for (int x = a; x <= b; ++x) {
            const size_t i = size_t(r) * size_t(t.width) + size_t(x);
            const uint8_t q = t.texels[i].q;
            if (q == kEmptyIndex) continue;
            const float d = exact ? t.displacement[i] : 0.0f;
            if (c.first > c.last) {
                c = {x, x, q, q, d, d};
                continue;
            }
            c.last = x;
            c.qmin = std::min(c.qmin, q), c.qmax = std::max(c.qmax, q);
            c.dmin = std::min(c.dmin, d), c.dmax = std::max(c.dmax, d);
        }
        out[k] = c;
    }
}

// With a need: bounds of each row's two coordinates over its valid texels (warp_adjacent_face in face_swap.h), from
// the extremes of the terms the row's non-empty texels combine, without a division per texel. Each coordinate is
// (P + k Z) / (1 + k3 Z), P and Z two different terms (G's column, row or displacement term); with 1 + k3 Z > 0 over
// the box [P] x [Z] it is increasing in P and monotone in Z, so its extremes are at the box's corners. Otherwise (the
// box reaches behind the eye's plane; never for a box seen from outside) the row is bounded texel by texel.
inline void adjacent_row_ranges(const AdjacentJob& j, int r0, int r1) {
    const ReliefTexture& g = *j.g;
    const int gw = g.width, gh = g.height;
    AdjacentWorkspace& ws = *j.ws;
    const double inf = std::numeric_limits<double>::infinity();
    for (int r = r0; r < r1; ++r) {
        // The extremes of the column and displacement terms over the row's non-empty texels.
        // Also per chunk of the row (row_chunk_bounds), over the chunk's texels and one neighbour on each side: from
        // the relief's chunks (made once, or here for this row). The column term is monotone in the column and the
        // displacement term in the level (Quantizer::decode is non-decreasing) and in the displacement, so the
        // extremes over a chunk's non-empty texels are the terms at its first and last one and at its extreme levels
        // (or displacements).
        double cmin = inf, cmax = -inf, dmin = inf, dmax = -inf;
        const double* ct = j.col_term;
        const AdjacentChunks::Chunk* lv;
        if (j.levels) {
            lv = &j.levels->chunks[size_t(r) * size_t(j.chunks)];
        } else {
            AdjacentChunks::Chunk* own = &ws.own_chunks[size_t(r) * size_t(j.chunks)];
            chunk_row(g, r, j.chunks, j.exact, own);
            lv = own;
        }
        ChunkTerms* chunks = &ws.chunk_terms[size_t(r) * size_t(j.chunks)];
        for (int k = 0; k < j.chunks; ++k) {
            const AdjacentChunks::Chunk& c = lv[k];
            if (c.first > c.last) {
                chunks[k] = {inf, -inf, inf, -inf};
                continue;
            }
            const double ca = ct[c.first], cb = ct[c.last];
            const double da = j.exact ? j.offset_d + j.scale_d * double(c.dmin) : j.level_term[c.qmin];
            const double db = j.exact ? j.offset_d + j.scale_d * double(c.dmax) : j.level_term[c.qmax];
            chunks[k] = {std::min(ca, cb), std::max(ca, cb), std::min(da, db), std::max(da, db)};
            cmin = std::min(cmin, chunks[k].cmin), cmax = std::max(cmax, chunks[k].cmax);
            dmin = std::min(dmin, chunks[k].dmin), dmax = std::max(dmax, chunks[k].dmax);
        }
        double& umin = ws.row_umin[size_t(r)];
        double& umax = ws.row_umax[size_t(r)];
        double& vmin = ws.row_vmin[size_t(r)];
        double& vmax = ws.row_vmax[size_t(r)];
        umin = vmin = inf, umax = vmax = -inf;
        j.dropped_rows[r] = 0;
        ws.row_cornered[size_t(r)] = 0;
        if (!(cmin <= cmax)) continue;  // no non-empty texel
        const double row_term = j.offset_v + j.scale_v * ((gh - 1 - r) + 0.5);
        double lo[3], hi[3];  // per component of p = (u', v', d')
        lo[j.by_u] = cmin, hi[j.by_u] = cmax;
        lo[j.by_v] = hi[j.by_v] = row_term;
        lo[j.by_d] = dmin, hi[j.by_d] = dmax;
        const double den_lo = 1.0 + j.k3 * lo[2], den_hi = 1.0 + j.k3 * hi[2];
        if (den_lo > 0.0 && den_hi > 0.0 && std::isfinite(den_lo) && std::isfinite(den_hi)) {
            // Coordinate i of F (0: u with k1, 1: v with k2) at the four corners.
            double u0, u1, v0, v1;
            corner_bound(lo, hi, 0, j.k1, j.k3, u0, u1);
            corner_bound(lo, hi, 1, j.k2, j.k3, v0, v1);
            if (j.first == 0)
                umin = u0, umax = u1, vmin = v0, vmax = v1;
            else
                umin = v0, umax = v1, vmin = u0, vmax = u1;
            ws.row_cornered[size_t(r)] = 1;
            continue;
        }
        // Texel by texel: the coordinates themselves.
        RowScratch& s = row_scratch(gw, j.n1);
        if (row_coordinates(j, r, s, 0, gw, &j.dropped_rows[r]) == 0) continue;
        bool finite = true;
        for (int x = 0; x < gw; ++x) {
            if (!s.valid[size_t(x)]) continue;
            finite = finite && std::isfinite(s.pos[size_t(x)]) && std::isfinite(s.other[size_t(x)]);
            umin = std::min(umin, s.pos[size_t(x)]), umax = std::max(umax, s.pos[size_t(x)]);
            vmin = std::min(vmin, s.other[size_t(x)]), vmax = std::max(vmax, s.other[size_t(x)]);
        }
        if (!finite) umin = vmin = -inf, umax = vmax = inf;
    }
}

// With a need, for row r bounded by its corners (adjacent_row_ranges): the chunks (read as row_chunks reads them)
// whose bound of the row pass's coordinate reaches a line to draw (lines[c] for c in cl .. ch), as merged ranges of
// samples appended to `out`. Each chunk's bound is the row's, over the box of the chunk's terms (ChunkTerms): within
// the row's box, so its denominators are positive and the same monotonicity holds.
inline void row_chunk_bounds(const AdjacentJob& j, int r, int cl, int ch, const uint8_t* lines,
                             std::vector<std::pair<int, int>>& out) {
    const int gw = j.g->width, gh = j.g->height;
    const double row_term = j.offset_v + j.scale_v * ((gh - 1 - r) + 0.5);
    const int i = j.first;  // F's coordinate the row pass computes: 0 (u, with k1) or 1 (v, with k2)
    const double k = i == 0 ? j.k1 : j.k2;
    const ChunkTerms* chunks = &j.ws->chunk_terms[size_t(r) * size_t(j.chunks)];
    for (int c = 0; c < j.chunks; ++c) {
        const ChunkTerms& t = chunks[c];
        if (!(t.cmin <= t.cmax)) continue;  // no non-empty texel
        double lo[3], hi[3];
        lo[j.by_u] = t.cmin, hi[j.by_u] = t.cmax;
        lo[j.by_v] = hi[j.by_v] = row_term;
        lo[j.by_d] = t.dmin, hi[j.by_d] = t.dmax;
        double mn, mx;
        corner_bound(lo, hi, i, k, j.k3, mn, mx);
        keep_chunk(c, gw, mn, mx, cl, ch, lines, out);
    }
}

// Pass 1 over rows r0 .. r1 - 1 of G: as the reference's, into one array of intermediate samples. With a need, a row
// draws only the intermediate lines its samples can carry to a needed pixel (face_swap.h, warp_adjacent_face).
inline void adjacent_row_pass(const AdjacentJob& j, int r0, int r1) {
    const ReliefTexture& g = *j.g;
    const int gw = g.width, gh = g.height;
    AdjacentWorkspace& ws = *j.ws;
    RowScratch& s = row_scratch(gw, j.n1);
    uint8_t* lines = s.lines.data();
    for (int r = r0; r < r1; ++r) {
        AdjacentSample* o = ws.mid.row(r);
        int& lo = ws.mid_lo[size_t(r)];
        int& hi = ws.mid_hi[size_t(r)];
        if (hi >= lo) std::fill(o + lo, o + hi + 1, AdjacentSample{});
        lo = 0, hi = -1;
        int cl = 0, ch = j.n1 - 1;
        if (j.need) {
            // The lines this row writes (its range of the row pass's coordinate) that hold a needed pixel within the
            // range of the other coordinate its samples can reach through the column pass (its own row's and its
            // neighbours'). None: the row is not warped (dropped_rows is the bounds' count).
            double vlo = ws.row_vmin[size_t(r)], vhi = ws.row_vmax[size_t(r)];
            if (!(vlo <= vhi)) continue;
            for (int n : {r - 1, r + 1})
                if (n >= 0 && n < gh && ws.row_vmin[size_t(n)] <= ws.row_vmax[size_t(n)]) {
                    vlo = std::min(vlo, ws.row_vmin[size_t(n)]);
                    vhi = std::max(vhi, ws.row_vmax[size_t(n)]);
                }
            const int k0 = first_pixel(vlo), k1 = last_pixel(vhi);
            const int c0 = std::max(first_pixel(ws.row_umin[size_t(r)]), 0);
            const int c1 = std::min(last_pixel(ws.row_umax[size_t(r)]), j.n1 - 1);
            cl = j.n1, ch = -1;
            const int kk0 = std::max(k0, 0), kk1 = std::min(k1, j.n2 - 1);
            if (kk0 > kk1) continue;
            const uint16_t* below = &j.need->prefix[size_t(kk0) * size_t(j.n1)];
            const uint16_t* upto = &j.need->prefix[size_t(kk1 + 1) * size_t(j.n1)];
            for (int c = c0; c <= c1; ++c) lines[c] = upto[c] > below[c];
            for (int c = c0; c <= c1; ++c)
                if (lines[c]) {
                    cl = c;
                    break;
                }
            for (int c = c1; c >= c0; --c)
                if (lines[c]) {
                    ch = c;
                    break;
                }
            if (ch < cl) continue;
        }
        // With a need, a row bounded by its corners computes only the chunks whose bounds reach a line to draw;
        // another (bounded texel by texel) computes all its coordinates and keeps the chunks they reach it with.
        s.ranges.clear();
        if (j.need && ws.row_cornered[size_t(r)]) {
            row_chunk_bounds(j, r, cl, ch, lines, s.ranges);
            int n_ok = 0;
            for (const auto& [a, b] : s.ranges) n_ok += row_coordinates(j, r, s, a, b + 1, nullptr);
            if (n_ok == 0) continue;
        } else {
            if (row_coordinates(j, r, s, 0, gw, &j.dropped_rows[r]) == 0) continue;
            if (j.need) row_chunks(s.pos.data(), s.valid.data(), gw, cl, ch, lines, s.ranges);
        }
        const uint8_t* brk = g.breaks.empty() ? nullptr : &g.breaks[size_t(r) * size_t(gw)];
        auto connected = [&](int a, int b) { return !brk || !(brk[std::min(a, b)] & kBreakRight); };
        int wlo = j.n1, whi = -1;
        LineInput<double, SwapAttr> in{gw, s.pos.data(), s.color.data(), s.attr.data(), s.valid.data()};
        if (!j.need) {
            auto put = [&](int x, Rgba8 c, const SwapAttr& a) {
                o[x] = {a.v, a.d, a.g, c};
                wlo = std::min(wlo, x);
                whi = std::max(whi, x);
            };
            warp_line_to(in, j.split_u, j.n1, put, connected);
        } else {
            auto wanted = [&](int x) { return lines[x] != 0; };
            auto put = [&](int x, Rgba8 c, const SwapAttr& a) {
                if (!wanted(x)) return;  // a point (spans interpolate only the wanted pixels)
                o[x] = {a.v, a.d, a.g, c};
                wlo = std::min(wlo, x);
                whi = std::max(whi, x);
            };
            warp_line_ranges(in, j.split_u, cl, ch, std::span<const std::pair<int, int>>(s.ranges), put, connected,
                             wanted);
        }
        lo = wlo, hi = whi;
    }
}

// Pass 2 over intermediate columns c_lo + i0 .. c_lo + i1 - 1: as the reference's, gathering each column from the
// one array, only from the rows whose extent holds it (the others hold the empty sample there), z-tested into out.
// With a need, only the needed pixels.
inline void adjacent_column_pass(const AdjacentJob& j, int i0, int i1) {
    const int gh = j.g->height;
    const AdjacentWorkspace& ws = *j.ws;
    AdjacentBuffer& out = *j.out;
    ColumnScratch& scratch = column_scratch(gh);
    std::vector<double>& pos = scratch.pos;
    std::vector<ColAttr>& attr = scratch.attr;
    std::vector<Rgba8>& color = scratch.color;
    std::vector<uint8_t>& valid = scratch.valid;
    const double threshold = j.threshold;
    for (int c = j.c_lo + i0; c < j.c_lo + i1; ++c) {
        // With a need: only the column's needed pixels, and only the rows that wrote to it (the others hold
        // nothing there, as samples outside k_lo .. k_hi would).
        int k_lo = 0, k_hi = gh - 1;
        if (j.need) {
            if (j.need->hi[size_t(c)] < j.need->lo[size_t(c)]) continue;
            const int r_lo = ws.col_rows[2 * size_t(c)], r_hi = ws.col_rows[2 * size_t(c) + 1];
            if (r_hi < r_lo) continue;
            k_lo = gh - 1 - r_hi, k_hi = gh - 1 - r_lo;
        }
        bool any = false;
        double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
        for (int k = k_lo; k <= k_hi; ++k) {
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
            if (s.c.a != 0) vmin = std::min(vmin, s.v), vmax = std::max(vmax, s.v);
        }
        if (!any) continue;
        // With a need: every span and point of the line lies within the range of its samples' positions, so a line
        // whose samples reach no needed pixel draws none (the pixels first_pixel .. last_pixel of that range, as
        // for a row). In views where the adjacent faces land inside the face's own silhouette, most lines.
        if (j.need && std::isfinite(vmin) && std::isfinite(vmax) &&
            !j.need->any(c, first_pixel(vmin), last_pixel(vmax)))
            continue;
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
        if (!j.need) {
            warp_line_to(in, j.split_v, j.n2, put, connected);
        } else {
            const uint8_t* m = j.need->at + c * j.need->step_line;
            const std::ptrdiff_t step = j.need->step_pos;
            auto wanted = [&](int k) { return m[k * step] != 0; };
            auto put_needed = [&](int k, Rgba8 col, const ColAttr& a) {
                if (wanted(k)) put(k, col, a);  // a point (spans interpolate only the needed pixels)
            };
            warp_line_clipped(in, j.split_v, j.need->lo[size_t(c)], j.need->hi[size_t(c)], put_needed, connected, k_lo,
                              k_hi, wanted);
        }
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
__attribute__((target("avx2"), flatten)) void row_ranges_avx2(const AdjacentJob& j, int r0, int r1) {
    adjacent_row_ranges(j, r0, r1);
}
__attribute__((target("avx2"), flatten)) void column_pass_avx2(const AdjacentJob& j, int i0, int i1) {
    adjacent_column_pass(j, i0, i1);
}
__attribute__((target("sse4.2"), flatten)) void row_pass_sse4(const AdjacentJob& j, int r0, int r1) {
    adjacent_row_pass(j, r0, r1);
}
__attribute__((target("sse4.2"), flatten)) void row_ranges_sse4(const AdjacentJob& j, int r0, int r1) {
    adjacent_row_ranges(j, r0, r1);
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
RTM_FLATTEN void row_ranges_baseline(const AdjacentJob& j, int r0, int r1) { adjacent_row_ranges(j, r0, r1); }
RTM_FLATTEN void column_pass_baseline(const AdjacentJob& j, int i0, int i1) { adjacent_column_pass(j, i0, i1); }

using PassFn = void (*)(const AdjacentJob&, int, int);
struct Passes {
    PassFn ranges = row_ranges_baseline, rows = row_pass_baseline, columns = column_pass_baseline;
};
Passes choose_passes(Isa isa) {
    Passes p;
#ifdef RTM_ADJACENT_VARIANTS
    const Isa target = resolve_isa(isa);
    if (target == Isa::avx512 || target == Isa::avx3 || target == Isa::avx2)
        p = {row_ranges_avx2, row_pass_avx2, column_pass_avx2};
    else if (target == Isa::sse4)
        p = {row_ranges_sse4, row_pass_sse4, column_pass_sse4};
#else
    (void)isa;
#endif
    return p;
}

}  // namespace

AdjacentChunks AdjacentChunks::make(const ReliefTexture& t) {
    AdjacentChunks out;
    out.width = t.width;
    out.height = t.height;
    out.per_row = (t.width + kAdjacentChunk - 1) / kAdjacentChunk;
    out.chunks.resize(size_t(out.height) * size_t(out.per_row));
    const bool exact = t.displacement.size() == t.texels.size();
    for (int r = 0; r < t.height; ++r)
        chunk_row(t, r, out.per_row, exact, &out.chunks[size_t(r) * size_t(out.per_row)]);
    return out;
}

int adjacent_pass_orientation(const ReliefGeometry& g, const ReliefGeometry& f) {
    const FaceSwap swap = make_face_swap(g, f);
    std::array<int, 3> src{};
    return single_source_terms(swap, src) ? first_pass_coordinate(swap) : -1;
}

long long warp_adjacent_face(const ReliefTexture& g, const ReliefGeometry& f_geom, int width, int height,
                             const PrewarpCoefficients& kf, bool exact, AdjacentWorkspace& ws, AdjacentBuffer& out,
                             int threads, Isa isa, const AdjacentNeed* need, const AdjacentChunks* chunks) {
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
    if (need) {
        if (need->width != width || need->height != height)
            throw std::invalid_argument("warp_adjacent_face: the need is " + std::to_string(need->width) + "x" +
                                        std::to_string(need->height) + ", the face " + std::to_string(width) + "x" +
                                        std::to_string(height));
        if (!need->built[size_t(j.first)])
            throw std::invalid_argument("warp_adjacent_face: the need was not indexed for pass orientation " +
                                        std::to_string(j.first) + " (adjacent_pass_orientation)");
        j.need = &need->lines[size_t(j.first)];
        j.chunks = (gw + kRowChunk - 1) / kRowChunk;
        if (chunks && (chunks->width != gw || chunks->height != gh || chunks->per_row != j.chunks ||
                       chunks->chunks.size() != size_t(gh) * size_t(j.chunks)))
            throw std::invalid_argument("warp_adjacent_face: the chunks are of a " + std::to_string(chunks->width) +
                                        "x" + std::to_string(chunks->height) + " relief, the face is " +
                                        std::to_string(gw) + "x" + std::to_string(gh));
        j.levels = chunks;
        ws.chunk_terms.resize(size_t(gh) * size_t(j.chunks));
        if (!chunks) ws.own_chunks.resize(size_t(gh) * size_t(j.chunks));
        ws.row_cornered.resize(size_t(gh));
        ws.row_umin.resize(size_t(gh));
        ws.row_umax.resize(size_t(gh));
        ws.row_vmin.resize(size_t(gh));
        ws.row_vmax.resize(size_t(gh));
    }

    const Passes fn = choose_passes(isa);
    j.threshold = g.breaks.empty() ? 0.0 : g.discontinuity_threshold;
    // Both passes (with a need, the three) in one task arena (one thread: none), kept per thread count (arena_for).
    auto passes = [&] {
        auto over = [&](int n, PassFn pass) {
            if (threads == 1)
                pass(j, 0, n);
            else
                tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const auto& r) { pass(j, r.begin(), r.end()); });
        };
        if (j.need) over(gh, fn.ranges);
        over(gh, fn.rows);
        // The columns any row wrote to; the others hold nothing.
        int c_lo = j.n1, c_hi = -1;
        for (int r = 0; r < gh; ++r)
            if (ws.mid_hi[size_t(r)] >= ws.mid_lo[size_t(r)]) {
                c_lo = std::min(c_lo, ws.mid_lo[size_t(r)]);
                c_hi = std::max(c_hi, ws.mid_hi[size_t(r)]);
            }
        j.c_lo = c_lo;
        if (j.need) {
            // Per intermediate line, the rows that wrote to it.
            ws.col_rows.resize(2 * size_t(j.n1));
            for (int c = 0; c < j.n1; ++c) ws.col_rows[2 * size_t(c)] = gh, ws.col_rows[2 * size_t(c) + 1] = -1;
            for (int r = 0; r < gh; ++r)
                for (int c = ws.mid_lo[size_t(r)]; c <= ws.mid_hi[size_t(r)]; ++c) {
                    int& a = ws.col_rows[2 * size_t(c)];
                    int& b = ws.col_rows[2 * size_t(c) + 1];
                    a = std::min(a, r), b = std::max(b, r);
                }
        }
        if (c_hi >= c_lo) over(c_hi - c_lo + 1, fn.columns);
    };
    if (threads > 1) {
        task_arena_for(threads).execute(passes);
    } else {
        passes();
    }
    long long dropped = 0;
    for (long long n : dropped_rows) dropped += n;
    return dropped;
}

}  // namespace rtm
