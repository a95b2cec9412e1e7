// Exact CPU ray caster of the bilinear height field of a relief texture (ground truth).
//
// Coordinates. A world point P = origin + a*u + b*v + f*d has coordinates (u, v, d) = M^-1 (P - origin) with
// M = [a b f] (columns; f unit, so d is a world distance along f). The map is affine, so a ray o + t*dir stays a
// straight line q0 + t*qd in (u, v, d), with the same parameter t: dir is a unit vector, so t is the world
// distance along the ray (the depth output). a and b may be non-orthogonal and of different lengths.
//
// Surface. Cell (i, j) (j counts v-rows from the bottom, so the texel of v-row j is image row h-1-j) spans
// u in [i+0.5, i+1.5], v in [j+0.5, j+1.5]; with s = u-(i+0.5), r = v-(j+0.5) in [0, 1] the surface is
//     d = H(s, r) = h00 + hs*s + hr*r + e*s*r,  hs = h10-h00, hr = h01-h00, e = h00-h10-h01+h11,
// hXY the exact displacement of the texel at (i+X, j+Y). Along the ray s, r and d are linear in t, so
// F(t) = H - d is a quadratic A t^2 + B t + C (A = e*su*rv: linear when the cell is planar along the ray).
// A cell with an empty texel is a hole.
//
// Walk. The ray is clipped to t >= 0, to the rectangle of texel centres u in [0.5, w-0.5], v in [0.5, h-0.5]
// and to the slab of displacements. A quadtree of per-cell [min, max] of the four corner heights (the min/max
// mipmap) is walked front to back: a node's segment [ta, tb] of the ray is split where the ray crosses the node's
// two mid lines and the children are visited in ray order; a node whose height range does not meet the ray's
// d-range over the segment is skipped whole. Every crossing time of a line u = const (or v = const) is computed
// by one formula, so neighbouring segments share their end points bit for bit (no cracks).
//
// Cell solve. The quadratic is set up relative to the segment start ta (small parameters, no cancellation from
// a far-away eye), solved with the stable form q = -(B + sign(B) sqrt(B^2-4AC))/2, roots q/A and C/q (the
// linear root -C/B when A == 0), and the first root in [0, tb-ta] (with a relative tolerance of 1e-9, so a root
// on a shared cell border is found in one of the two cells) is the hit. If rounding loses a root that a sign
// change of F over the segment proves, bisection finds it. Grazing tangencies (discriminant < 0 by rounding) are
// misses, a set of measure zero. Colour: bilinear interpolation of the four texel colours at the hit, rounded.
//
// Speed: media/bumps (256x256 texels) at 512x512 pixels, --orbit 20,35,1.6: 80 ms on one thread, 43 ms on two
// (2-core machine shared with other jobs, so two threads measure anywhere between 43 and 80 ms); facade 80 ms,
// ridges 110 ms on one thread. The quadtree keeps a ray to about log2(256) node tests plus the cells it really
// passes close to.
#include "truth/raycast.h"
#include "warp/task_arenas.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace rtm {

// A named namespace, not an anonymous one: ReliefRaycaster::Impl (declared in the header) holds a Caster, and a field
// of a type from an anonymous namespace is what -Wsubobject-linkage warns of (in the unity build, where this file is
// not the main one).
namespace raycast_detail {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRelTol = 1e-9;

// Per-cell [lo, hi] of the four corner heights, and coarser levels over 2x2 blocks. Holes: lo = +inf, hi = -inf.
struct MinMaxPyramid {
    struct Level {
        int w = 0, h = 0;
        std::vector<double> lo, hi;
    };
    std::vector<Level> levels;  // levels[0]: cells; levels.back(): one node over everything
};

struct Hit {
    double t = kInf;
    int i = 0, j = 0;     // cell
    double s = 0, r = 0;  // position in the cell
};

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Time at which the line q0 + t*qd crosses coordinate `line` (+inf when it runs parallel to it).
inline double crossing(double line, double o, double d) { return d == 0.0 ? kInf : (line - o) / d; }

// Roots of A t^2 + B t + C, ascending; returns how many (0..2).
int solve_quadratic(double A, double B, double C, double roots[2]) {
    if (A == 0.0) {
        if (B == 0.0) {
            if (C != 0.0) return 0;
            roots[0] = 0.0;  // F == 0 along the ray: it lies in the surface; take the segment start
            return 1;
        }
        roots[0] = -C / B;
        return 1;
    }
    const double disc = B * B - 4.0 * A * C;
    if (!(disc >= 0.0)) return 0;
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    if (q == 0.0) {  // B == 0 and disc == 0, so C == 0: double root at 0
        roots[0] = 0.0;
        return 1;
    }
    double r0 = q / A, r1 = C / q;
    if (r1 < r0) std::swap(r0, r1);
    roots[0] = r0;
    roots[1] = r1;
    return 2;
}

class Caster {
public:
    explicit Caster(const ReliefTexture& t) : t_(t), w_(t.width), h_(t.height) {
        const ReliefGeometry& g = t.geometry;
        f_ = g.f();
        minv_ = glm::inverse(glm::dmat3(g.a, g.b, f_));
        heights_.assign(size_t(w_) * size_t(h_), 0.0);
        valid_.assign(size_t(w_) * size_t(h_), 0);
        for (int j = 0; j < h_; ++j)
            for (int i = 0; i < w_; ++i) {
                const int row = h_ - 1 - j;
                if (t.empty_at(i, row)) continue;
                heights_[idx(i, j)] = double(t.displ(i, row));
                valid_[idx(i, j)] = 1;
            }
        build_pyramid();
        if (!pyr_.levels.empty()) {
            const auto& top = pyr_.levels.back();
            dmin_ = top.lo[0];
            dmax_ = top.hi[0];
        }
        scale_ = std::max({std::abs(dmin_), std::abs(dmax_), glm::length(g.a), glm::length(g.b)});
        cell_len_ = std::min(glm::length(g.a), glm::length(g.b));
    }

    bool has_surface() const { return dmin_ <= dmax_; }

    ReliefRayHit cast(const glm::dvec3& origin, const glm::dvec3& dir, bool brute_force) const {
        ReliefRayHit out;
        if (!has_surface()) return out;
        RayState ray;
        ray.q0 = minv_ * (origin - t_.geometry.origin);
        ray.qd = minv_ * dir;
        if (!finite(ray.q0) || !finite(ray.qd) || (ray.qd.x == 0.0 && ray.qd.y == 0.0 && ray.qd.z == 0.0)) return out;
        ray.eps = kRelTol * (scale_ + std::abs(ray.q0.z));
        // Clip to t >= 0, the rectangle of texel centres and the displacement slab.
        double t0 = 0.0, t1 = kInf;
        const double lo[3] = {0.5, 0.5, dmin_ - ray.eps}, hi[3] = {w_ - 0.5, h_ - 0.5, dmax_ + ray.eps};
        for (int k = 0; k < 3; ++k) {
            const double o = ray.q0[k], d = ray.qd[k];
            if (d == 0.0) {
                if (o < lo[k] || o > hi[k]) return out;
                continue;
            }
            double a = (lo[k] - o) / d, b = (hi[k] - o) / d;
            if (a > b) std::swap(a, b);
            t0 = std::max(t0, a);
            t1 = std::min(t1, b);
        }
        if (!(t0 <= t1)) return out;
        Hit hit;
        const bool found = brute_force ? cast_brute_force(ray, t0, t1, hit)
                                       : visit(ray, int(pyr_.levels.size()) - 1, 0, 0, t0, t1, hit);
        if (!found) return out;
        out.hit = true;
        out.t = hit.t;
        out.u = hit.i + 0.5 + hit.s;
        out.v = hit.j + 0.5 + hit.r;
        out.color = shade(hit);
        return out;
    }

private:
    struct RayState {
        glm::dvec3 q0, qd;
        double eps = 0;  // tolerance on d for the node tests
    };

    size_t idx(int i, int j) const { return size_t(j) * size_t(w_) + size_t(i); }

    void build_pyramid() {
        const int cw = w_ - 1, ch = h_ - 1;
        if (cw < 1 || ch < 1) return;  // no cell: the surface through the texel centres has no area
        MinMaxPyramid::Level l0;
        l0.w = cw;
        l0.h = ch;
        l0.lo.assign(size_t(cw) * size_t(ch), kInf);
        l0.hi.assign(size_t(cw) * size_t(ch), -kInf);
        for (int j = 0; j < ch; ++j)
            for (int i = 0; i < cw; ++i) {
                if (!(valid_[idx(i, j)] && valid_[idx(i + 1, j)] && valid_[idx(i, j + 1)] && valid_[idx(i + 1, j + 1)]))
                    continue;
                const double c[4] = {heights_[idx(i, j)], heights_[idx(i + 1, j)], heights_[idx(i, j + 1)],
                                     heights_[idx(i + 1, j + 1)]};
                l0.lo[size_t(j) * size_t(cw) + size_t(i)] = std::min({c[0], c[1], c[2], c[3]});
                l0.hi[size_t(j) * size_t(cw) + size_t(i)] = std::max({c[0], c[1], c[2], c[3]});
            }
        pyr_.levels.push_back(std::move(l0));
        while (pyr_.levels.back().w > 1 || pyr_.levels.back().h > 1) {
            const MinMaxPyramid::Level& f = pyr_.levels.back();
            MinMaxPyramid::Level c;
            c.w = (f.w + 1) / 2;
            c.h = (f.h + 1) / 2;
            c.lo.assign(size_t(c.w) * size_t(c.h), kInf);
            c.hi.assign(size_t(c.w) * size_t(c.h), -kInf);
            for (int y = 0; y < f.h; ++y)
                for (int x = 0; x < f.w; ++x) {
                    const size_t fi = size_t(y) * size_t(f.w) + size_t(x);
                    const size_t ci = size_t(y / 2) * size_t(c.w) + size_t(x / 2);
                    c.lo[ci] = std::min(c.lo[ci], f.lo[fi]);
                    c.hi[ci] = std::max(c.hi[ci], f.hi[fi]);
                }
            pyr_.levels.push_back(std::move(c));
        }
    }

    // Front-to-back walk of node (x, y) at `level` over the ray segment [ta, tb].
    bool visit(const RayState& ray, int level, int x, int y, double ta, double tb, Hit& hit) const {
        const MinMaxPyramid::Level& L = pyr_.levels[size_t(level)];
        const size_t n = size_t(y) * size_t(L.w) + size_t(x);
        const double lo = L.lo[n], hi = L.hi[n];
        if (!(lo <= hi)) return false;  // only holes below
        const double da = ray.q0.z + ta * ray.qd.z, db = ray.q0.z + tb * ray.qd.z;
        if (std::max(da, db) < lo - ray.eps || std::min(da, db) > hi + ray.eps) return false;
        if (level == 0) return solve_cell(ray, x, y, ta, tb, hit);

        const int half = 1 << (level - 1);
        const double um = double((x << level) + half) + 0.5, vm = double((y << level) + half) + 0.5;
        const double tu = crossing(um, ray.q0.x, ray.qd.x), tv = crossing(vm, ray.q0.y, ray.qd.y);
        double bounds[4];
        int nb = 0;
        bounds[nb++] = ta;
        const double c1 = std::min(tu, tv), c2 = std::max(tu, tv);
        if (c1 > ta && c1 < tb) bounds[nb++] = c1;
        if (c2 > ta && c2 < tb && c2 != c1) bounds[nb++] = c2;
        bounds[nb++] = tb;
        const MinMaxPyramid::Level& C = pyr_.levels[size_t(level - 1)];
        for (int k = 0; k + 1 < nb; ++k) {
            const double t0 = bounds[k], t1 = bounds[k + 1];
            const double tm = 0.5 * (t0 + t1);
            const int cx = 2 * x + (ray.q0.x + tm * ray.qd.x >= um ? 1 : 0);
            const int cy = 2 * y + (ray.q0.y + tm * ray.qd.y >= vm ? 1 : 0);
            if (cx >= C.w || cy >= C.h) continue;  // beyond the grid (the ray was clipped to it; rounding only)
            if (visit(ray, level - 1, cx, cy, t0, t1, hit)) return true;
        }
        return false;
    }

    // Reference: every cell, its own clip of the ray, nearest hit.
    bool cast_brute_force(const RayState& ray, double t0, double t1, Hit& best) const {
        const MinMaxPyramid::Level& L = pyr_.levels[0];
        bool found = false;
        for (int j = 0; j < L.h; ++j)
            for (int i = 0; i < L.w; ++i) {
                if (!(L.lo[size_t(j) * size_t(L.w) + size_t(i)] <= L.hi[size_t(j) * size_t(L.w) + size_t(i)])) continue;
                double ta = t0, tb = t1;
                const double lo[2] = {i + 0.5, j + 0.5}, hi[2] = {i + 1.5, j + 1.5};
                bool miss = false;
                for (int k = 0; k < 2 && !miss; ++k) {
                    const double o = ray.q0[k], d = ray.qd[k];
                    if (d == 0.0) {
                        miss = o < lo[k] || o > hi[k];
                        continue;
                    }
                    double a = crossing(lo[k], o, d), b = crossing(hi[k], o, d);
                    if (a > b) std::swap(a, b);
                    ta = std::max(ta, a);
                    tb = std::min(tb, b);
                }
                if (miss || !(ta <= tb)) continue;
                Hit h;
                if (solve_cell(ray, i, j, ta, tb, h) && h.t < best.t) {
                    best = h;
                    found = true;
                }
            }
        return found;
    }

    bool solve_cell(const RayState& ray, int i, int j, double ta, double tb, Hit& hit) const {
        const double h00 = heights_[idx(i, j)], h10 = heights_[idx(i + 1, j)];
        const double h01 = heights_[idx(i, j + 1)], h11 = heights_[idx(i + 1, j + 1)];
        const double hs = h10 - h00, hr = h01 - h00, e = h00 - h10 - h01 + h11;
        const double su = ray.qd.x, rv = ray.qd.y, dd = ray.qd.z;
        const double s0 = ray.q0.x + ta * su - (i + 0.5);
        const double r0 = ray.q0.y + ta * rv - (j + 0.5);
        const double d0 = ray.q0.z + ta * dd;
        const double A = e * su * rv;
        const double B = hs * su + hr * rv + e * (s0 * rv + r0 * su) - dd;
        const double C = h00 + hs * s0 + hr * r0 + e * s0 * r0 - d0;
        const double len = tb - ta;
        const double tol = kRelTol * (len + cell_len_);
        double roots[2];
        const int n = solve_quadratic(A, B, C, roots);
        double tau = kInf;
        for (int k = 0; k < n; ++k)
            if (roots[k] >= -tol && roots[k] <= len + tol) {
                tau = roots[k];
                break;
            }
        if (tau == kInf) {
            // Rounding lost a root that a sign change proves: bisect.
            const auto F = [&](double x) { return (A * x + B) * x + C; };
            double lo = 0.0, hi = len, flo = F(0.0);
            const double fhi = F(len);
            if (!((flo < 0.0 && fhi > 0.0) || (flo > 0.0 && fhi < 0.0))) return false;
            for (int it = 0; it < 200 && hi - lo > 0.0; ++it) {
                const double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi) break;
                const double fm = F(mid);
                if ((fm < 0.0) == (flo < 0.0)) {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            tau = 0.5 * (lo + hi);
        }
        tau = std::clamp(tau, 0.0, len);
        hit.t = ta + tau;
        hit.i = i;
        hit.j = j;
        hit.s = std::clamp(s0 + tau * su, 0.0, 1.0);
        hit.r = std::clamp(r0 + tau * rv, 0.0, 1.0);
        return true;
    }

    Rgba8 shade(const Hit& hit) const {
        const ReliefTexel& c00 = t_.texel(hit.i, h_ - 1 - hit.j);
        const ReliefTexel& c10 = t_.texel(hit.i + 1, h_ - 1 - hit.j);
        const ReliefTexel& c01 = t_.texel(hit.i, h_ - 2 - hit.j);
        const ReliefTexel& c11 = t_.texel(hit.i + 1, h_ - 2 - hit.j);
        const double s = hit.s, r = hit.r;
        const double w00 = (1 - s) * (1 - r), w10 = s * (1 - r), w01 = (1 - s) * r, w11 = s * r;
        const auto mix = [&](uint8_t ReliefTexel::*ch) {
            const double v = w00 * c00.*ch + w10 * c10.*ch + w01 * c01.*ch + w11 * c11.*ch;
            return uint8_t(std::clamp(std::lround(v), 0L, 255L));
        };
        return {mix(&ReliefTexel::r), mix(&ReliefTexel::g), mix(&ReliefTexel::b), 255};
    }

    const ReliefTexture& t_;
    int w_, h_;
    glm::dvec3 f_;
    glm::dmat3 minv_;
    std::vector<double> heights_;  // v-row major: heights_[j*w + i] is the texel of image row h-1-j
    std::vector<uint8_t> valid_;
    MinMaxPyramid pyr_;
    double dmin_ = kInf, dmax_ = -kInf;  // over the texels of non-hole cells
    double scale_ = 1.0, cell_len_ = 1.0;
};

}  // namespace raycast_detail

using raycast_detail::Caster;

struct ReliefRaycaster::Impl {
    explicit Impl(const ReliefTexture& t) : caster(t) {}
    Caster caster;
};

ReliefRaycaster::ReliefRaycaster(const ReliefTexture& t) : impl_(std::make_unique<Impl>(t)) {}
ReliefRaycaster::~ReliefRaycaster() = default;

ReliefRayHit ReliefRaycaster::cast(const glm::dvec3& origin, const glm::dvec3& dir, bool brute_force) const {
    return impl_->caster.cast(origin, dir, brute_force);
}

bool ReliefRaycaster::has_surface() const { return impl_->caster.has_surface(); }

ImageRGBA8 raycast_relief(const ReliefTexture& t, const Camera& cam, const RaycastOptions& options, ImageF* depth) {
    if (std::string why = cam.validate(); !why.empty()) throw std::invalid_argument("raycast: camera: " + why);
    ImageRGBA8 img(cam.width, cam.height, Rgba8{0, 0, 0, 255});
    if (depth) depth->resize(cam.width, cam.height, std::numeric_limits<float>::infinity());
    const Caster caster(t);
    const auto rows = [&](int r0, int r1) {
        for (int py = r0; py < r1; ++py) {
            Rgba8* out = img.row(py);
            float* dout = depth ? depth->row(py) : nullptr;
            for (int px = 0; px < cam.width; ++px) {
                glm::dvec3 o, dir;
                cam.ray(px, py, o, dir);
                const ReliefRayHit hit = caster.cast(o, dir, options.brute_force);
                out[px] = hit.color;
                if (dout) dout[px] = float(hit.t);
            }
        }
    };
    // Each row is written by exactly one task and depends on nothing else: the output is the same for any number
    // of threads. Rows run in chunks so that progress is reported between them, from the calling thread (outside
    // any arena: task_arena::execute may hand its functor to a worker).
    if (!caster.has_surface()) {
        if (options.progress) options.progress(1.0);
        return img;
    }
    tbb::task_arena* arena = options.threads > 0 ? &task_arena_for(options.threads) : nullptr;
    const int concurrency = arena ? arena_threads(options.threads) : tbb::this_task_arena::max_concurrency();
    const int chunk = options.progress ? std::max(8, 4 * concurrency) : std::max(cam.height, 1);
    for (int r0 = 0; r0 < cam.height; r0 += chunk) {
        const int r1 = std::min(cam.height, r0 + chunk);
        const auto loop = [&] {
            tbb::parallel_for(tbb::blocked_range<int>(r0, r1, 1),
                              [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
        };
        if (arena)
            arena->execute(loop);
        else
            loop();
        if (options.progress) options.progress(double(r1) / double(cam.height));
    }
    return img;
}

}  // namespace rtm
