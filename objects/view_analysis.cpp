#include "objects/view_analysis.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace rtm {

bool outside_frustum(const Camera& cam, const Bounds& box) {
    return outside_frustum(cam.projection() * cam.view(), box);
}

bool outside_frustum(const glm::dmat4& m, const Bounds& box) {
    if (box.empty()) return true;
    glm::dvec4 clip[8];
    int n = 0;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p{(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y, (i & 4) ? box.hi.z : box.lo.z};
        clip[n++] = m * glm::dvec4(p, 1.0);
    }
    // Clip planes: -w <= x, y, z <= w.
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            bool all_out = true;
            for (int i = 0; i < 8 && all_out; ++i) all_out = sign * clip[i][axis] > clip[i].w;
            if (all_out) return true;
        }
    return false;
}

PrewarpExtent visible_margins(const Camera& cam, const ReliefTexture& t, const PrewarpExtent& full, double guard) {
    // The rectangle of all margins in the plane, clipped in homogeneous clip space (where clipping is linear, so the
    // texel coordinates u, v of a cut point interpolate with the same weight as its clip coordinates).
    struct Vertex {
        glm::dvec4 clip;
        double u, v;
    };
    const glm::dmat4 m = cam.projection() * cam.view();
    const ReliefGeometry& g = t.geometry;
    const double u0 = -full.left, u1 = t.width + full.right, v0 = -full.bottom, v1 = t.height + full.top;
    std::vector<Vertex> poly;
    for (const auto& [u, v] : {std::pair{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}})
        poly.push_back({m * glm::dvec4(g.origin + u * g.a + v * g.b, 1.0), u, v});
    // The cone's planes: w + x >= 0, w - x >= 0, w + y >= 0, w - y >= 0 (w > 0 in front of the eye follows).
    for (int plane = 0; plane < 4 && !poly.empty(); ++plane) {
        const int axis = plane / 2;
        const double sign = plane % 2 ? -1.0 : 1.0;
        const auto dist = [&](const Vertex& p) { return p.clip.w + sign * p.clip[axis]; };
        std::vector<Vertex> out;
        for (size_t i = 0; i < poly.size(); ++i) {
            const Vertex& a = poly[i];
            const Vertex& b = poly[(i + 1) % poly.size()];
            const double da = dist(a), db = dist(b);
            if (da >= 0) out.push_back(a);
            if ((da >= 0) != (db >= 0)) {
                const double s = da / (da - db);
                out.push_back({a.clip + s * (b.clip - a.clip), a.u + s * (b.u - a.u), a.v + s * (b.v - a.v)});
            }
        }
        poly = std::move(out);
    }
    PrewarpExtent e;  // all 0: nothing of the plane in view
    if (poly.empty()) return e;
    double lo_u = poly[0].u, hi_u = lo_u, lo_v = poly[0].v, hi_v = lo_v;
    for (const Vertex& p : poly) {
        lo_u = std::min(lo_u, p.u);
        hi_u = std::max(hi_u, p.u);
        lo_v = std::min(lo_v, p.v);
        hi_v = std::max(hi_v, p.v);
    }
    // Texels wanted past each edge of the quad, at most the full margin.
    const auto need = [guard](double past, int whole) {
        const double n = std::ceil(past + guard);
        return n <= 0.0 ? 0 : n >= double(whole) ? whole : int(n);
    };
    e.left = need(-lo_u, full.left);
    e.right = need(hi_u - t.width, full.right);
    e.bottom = need(-lo_v, full.bottom);
    e.top = need(hi_v - t.height, full.top);
    return e;
}

double projected_area_pixels(const Camera& cam, const std::array<glm::dvec3, 4>& quad) {
    const glm::dmat4 m = cam.projection() * cam.view();
    double xs[4], ys[4];
    for (int i = 0; i < 4; ++i) {
        const glm::dvec4 c = m * glm::dvec4(quad[size_t(i)], 1.0);
        if (!(c.w > 1e-12)) return -1.0;
        xs[i] = (c.x / c.w * 0.5 + 0.5) * cam.width;
        ys[i] = (c.y / c.w * 0.5 + 0.5) * cam.height;
    }
    double a = 0;
    for (int i = 0; i < 4; ++i) {
        const int j = (i + 1) % 4;
        a += xs[i] * ys[j] - xs[j] * ys[i];
    }
    return std::abs(a) * 0.5;
}

double max_parallax_texels(const ReliefTexture& t, const PrewarpCoefficients& k) {
    if (k.side == ViewSide::on_plane) return std::numeric_limits<double>::infinity();
    double du = 0, dv = 0;
    for (double d : {t.quant.min, t.quant.max}) {
        const double den = 1.0 + k.k3 * d;
        if (!(den > 0.0)) return std::numeric_limits<double>::infinity();
        const double s = 1.0 / den - 1.0;
        for (double us : {0.0, double(t.width)}) du = std::max(du, std::abs((us - k.epipole_u) * s));
        for (double vs : {0.0, double(t.height)}) dv = std::max(dv, std::abs((vs - k.epipole_v) * s));
    }
    return std::hypot(du, dv);
}

double max_texel_motion(const ReliefTexture& t, const PrewarpCoefficients& k0, const PrewarpCoefficients& k1) {
    return max_motion_texels(t.width, t.height, t.quant.min, t.quant.max, k0, k1);
}

double max_motion_texels(int w, int h, double dmin, double dmax, const PrewarpCoefficients& k0,
                         const PrewarpCoefficients& k1) {
    if (k0.side == ViewSide::on_plane || k1.side == ViewSide::on_plane) return std::numeric_limits<double>::infinity();
    double worst = 0;
    const int levels = 33;
    for (int i = 0; i < levels; ++i) {
        const double d = dmin + (dmax - dmin) * i / (levels - 1);
        for (double us : {0.0, double(w)})
            for (double vs : {0.0, double(h)}) {
                double u0, v0, u1, v1;
                const bool ok0 = k0.warp(us, vs, d, u0, v0), ok1 = k1.warp(us, vs, d, u1, v1);
                if (ok0 != ok1) return std::numeric_limits<double>::infinity();
                if (!ok0) continue;
                worst = std::max(worst, std::hypot(u1 - u0, v1 - v0));
            }
    }
    return worst;
}

bool eye_inside_slab(const ReliefTexture& t, const glm::dvec3& eye) {
    const double dist = glm::dot(eye - t.geometry.origin, t.geometry.f());
    const double lo = std::min(0.0, t.quant.min), hi = std::max(0.0, t.quant.max);
    if (!(hi > lo)) return false;
    return dist >= lo && dist <= hi;
}

MovingTexels moving_texels(const ReliefTexture& t) {
    MovingTexels m;
    m.x0 = t.width;
    m.row0 = t.height;
    m.dmin = std::numeric_limits<double>::infinity();
    m.dmax = -m.dmin;
    for (int r = 0; r < t.height; ++r)
        for (int x = 0; x < t.width; ++x) {
            const uint8_t q = t.texel(x, r).q;
            if (q == kEmptyIndex) continue;
            const double dq = t.quant.decode(q), de = t.displ(x, r);
            if (dq == 0.0 && de == 0.0) continue;
            m.any = true;
            m.x0 = std::min(m.x0, x);
            m.x1 = std::max(m.x1, x);
            m.row0 = std::min(m.row0, r);
            m.row1 = std::max(m.row1, r);
            m.dmin = std::min({m.dmin, dq, de});
            m.dmax = std::max({m.dmax, dq, de});
        }
    if (!m.any) m = {};
    return m;
}

PixelRect united(const PixelRect& a, const PixelRect& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    const int x0 = std::min(a.x, b.x), r0 = std::min(a.row, b.row);
    const int x1 = std::max(a.x + a.w, b.x + b.w), r1 = std::max(a.row + a.h, b.row + b.h);
    return {x0, r0, x1 - x0, r1 - r0};
}

PixelRect moving_footprint(const ReliefTexture& t, const MovingTexels& m, const PrewarpCoefficients& k,
                           const PrewarpExtent& e) {
    const int ow = t.width + e.left + e.right, oh = t.height + e.bottom + e.top;
    const PixelRect all{0, 0, ow, oh};
    if (!m.any) return {};
    if (k.side == ViewSide::on_plane) return all;
    // Source box of the moving texels grown by one texel (the neighbours their spans reach), in (u, v).
    const double us0 = m.x0, us1 = m.x1 + 1.0;
    const double vs0 = t.height - 1.0 - m.row1, vs1 = double(t.height - m.row0);
    double umin = us0 - 1, umax = us1 + 1, vmin = vs0 - 1, vmax = vs1 + 1;
    // Where they go (texels beyond the eye's plane are dropped, and their neighbours then start new runs in place).
    widen_by_warped_box(k, us0, us1, vs0, vs1, m.dmin, m.dmax, umin, umax, vmin, vmax);
    if (!std::isfinite(umin) || !std::isfinite(umax) || !std::isfinite(vmin) || !std::isfinite(vmax)) return all;
    // To output pixels, one more pixel each side: x covers u in [x - left, x + 1 - left); output line y (from the
    // bottom) covers v in [y - bottom, y + 1 - bottom), image row oh - 1 - y.
    auto clampi = [](double v, int lo, int hi) { return int(std::clamp(v, double(lo), double(hi))); };
    const int x0 = clampi(std::floor(umin) + e.left - 1, 0, ow - 1);
    const int x1 = clampi(std::ceil(umax) + e.left + 1, 0, ow - 1);
    const int y0 = clampi(std::floor(vmin) + e.bottom - 1, 0, oh - 1);
    const int y1 = clampi(std::ceil(vmax) + e.bottom + 1, 0, oh - 1);
    return {x0, oh - 1 - y1, x1 - x0 + 1, y1 - y0 + 1};
}

}  // namespace rtm
