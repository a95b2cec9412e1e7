#include "objects/relief_quad.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "objects/bounds.h"
#include "objects/micromesh.h"
#include "objects/view_analysis.h"
#include "warp/pyramid.h"

namespace rtm {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
}  // namespace

RenderMethod parse_render_method(const std::string& s) {
    if (s == "flat") return RenderMethod::flat;
    if (s == "two-pass") return RenderMethod::two_pass;
    if (s == "pipelined") return RenderMethod::pipelined;
    if (s == "micromesh") return RenderMethod::micromesh;
    if (s == "raycast") return RenderMethod::raycast;
    throw std::invalid_argument("unknown method \"" + s + "\"; known: flat, two-pass, pipelined, micromesh, raycast");
}

std::string to_string(RenderMethod m) {
    switch (m) {
        case RenderMethod::flat: return "flat";
        case RenderMethod::two_pass: return "two-pass";
        case RenderMethod::pipelined: return "pipelined";
        case RenderMethod::micromesh: return "micromesh";
        case RenderMethod::raycast: return "raycast";
    }
    return "?";
}

ImageRGBA8 flat_texture(const ReliefTexture& t) {
    ImageRGBA8 img(t.width, t.height);
    for (size_t i = 0; i < t.texels.size(); ++i) {
        const ReliefTexel& x = t.texels[i];
        // Empty texels are (0, 0, 0, 0): the renderer divides filtered colour by alpha (no dark fringes).
        img.pixels[i] = x.q == kEmptyIndex ? Rgba8{} : Rgba8{x.r, x.g, x.b, 255};
    }
    return img;
}

ReliefQuad::ReliefQuad(ReliefTexture relief) : relief_(std::move(relief)) {}
ReliefQuad::~ReliefQuad() = default;
ReliefQuad::ReliefQuad(ReliefQuad&&) noexcept = default;

std::array<glm::dvec3, 4> ReliefQuad::corners() const {
    const ReliefGeometry& g = relief_.geometry;
    const glm::dvec3 aw = g.a * double(relief_.width), bh = g.b * double(relief_.height);
    return {g.origin, g.origin + aw, g.origin + aw + bh, g.origin + bh};
}

const MicroMesh& ReliefQuad::micromesh() {
    if (!micromesh_) micromesh_ = std::make_unique<MicroMesh>(build_micromesh(relief_));
    return *micromesh_;
}

bool ReliefQuad::faces(const glm::dvec3& eye) const {
    return compute_coefficients(relief_.geometry, eye).side == ViewSide::front;
}

const ReliefTexture& ReliefQuad::level_texture(int i) {
    if (i <= 0) return relief_;
    while (int(pyramid_.size()) < i) {
        const ReliefTexture& prev = pyramid_.empty() ? relief_ : pyramid_.back();
        if (prev.width == 1 && prev.height == 1) break;
        pyramid_.push_back(downsample(prev, relief_));
    }
    return pyramid_[size_t(std::min<int>(i, int(pyramid_.size()))) - 1];
}

const ReliefTexture& ReliefQuad::level(int i) { return level_texture(i); }

int ReliefQuad::levels() {
    int n = 1, w = relief_.width, h = relief_.height;
    while (w > 1 || h > 1) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
        ++n;
    }
    return n;
}

int ReliefQuad::auto_level(const Camera& cam) {
    const double area = projected_area_pixels(cam, corners());
    if (area < 0) return 0;  // the quad reaches behind the eye: large on screen
    return level_for_density(double(relief_.width) * relief_.height, area, levels() - 1);
}

double ReliefQuad::prewarp(const glm::dvec3& eye, const PrewarpOptions& options, bool with_displ) {
    const auto t0 = Clock::now();
    stats_ = rtm::prewarp(relief_, compute_coefficients(relief_.geometry, eye), options, workspace_, prewarped_,
                          with_displ ? &displ_ : nullptr);
    cached_.valid = false;
    return ms_since(t0);
}

namespace {

// The smallest rectangle holding every pixel where a and b differ (same size); w = 0 when they are equal.
struct Rect {
    int x = 0, row = 0, w = 0, h = 0;
};
Rect dirty_rect(const ImageRGBA8& a, const ImageRGBA8& b) {
    Rect r;
    int x0 = a.width, x1 = -1, r0 = a.height, r1 = -1;
    for (int row = 0; row < a.height; ++row) {
        const Rgba8* pa = a.row(row);
        const Rgba8* pb = b.row(row);
        if (std::equal(pa, pa + a.width, pb)) continue;
        r0 = std::min(r0, row);
        r1 = row;
        int lo = 0, hi = a.width - 1;
        while (pa[lo] == pb[lo]) ++lo;
        while (pa[hi] == pb[hi]) --hi;
        x0 = std::min(x0, lo);
        x1 = std::max(x1, hi);
    }
    if (r1 < 0) return r;
    return {x0, r0, x1 - x0 + 1, r1 - r0 + 1};
}

}  // namespace

void ReliefQuad::draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                      StageTimes& times, const DrawOptions& d, DrawReport* report) {
    const auto t_start = Clock::now();
    DrawReport rep;
    auto done = [&] {
        times.total_ms += ms_since(t_start);
        if (report) *report = rep;
    };
    const bool warp_method = method == RenderMethod::two_pass || method == RenderMethod::pipelined;
    if (!warp_method && method != RenderMethod::flat)
        throw std::invalid_argument("ReliefQuad::draw: method " + to_string(method) + " is not a texture method");
    if (!texture_) texture_ = std::make_unique<GlTexture>();

    // Skip: nothing of the relief can be on screen.
    if (d.skips && outside_frustum(cam, relief_bounds(relief_))) {
        rep.skips.push_back(kSkipOutsideFrustum);
        return done();
    }
    // Skip: the eye is inside the relief's slab; texels above its plane cannot be pre-warped, so draw the
    // micro-polygons instead (paper sections 3 and 6: extreme close-ups).
    if (d.skips && warp_method && eye_inside_slab(relief_, cam.eye)) {
        rep.skips.push_back(kSkipInsideSlab);
        const auto t0 = Clock::now();
        renderer.draw_mesh(cam, micromesh().vertices, micromesh().indices);
        renderer.finish();
        times.texture_map_ms += ms_since(t0);
        return done();
    }
    const bool facing = faces(cam.eye);
    if (!facing && d.skips) {  // the quad faces away: not pre-warped, not drawn (paper section 6)
        rep.skips.push_back(kSkipBackFacing);
        return done();
    }

    const int lvl = d.level < 0 ? auto_level(cam) : std::clamp(d.level, 0, levels() - 1);
    rep.level = lvl;
    const ReliefTexture& t = level_texture(lvl);
    ReliefSurface rs;
    rs.origin = t.geometry.origin;
    rs.a = t.geometry.a;
    rs.b = t.geometry.b;
    rs.width = t.width;
    rs.height = t.height;

    const ImageRGBA8* img = nullptr;
    bool warped = false;
    int kind = 0;
    if (warp_method) {
        const PrewarpCoefficients k = compute_coefficients(t.geometry, cam.eye);
        bool plain = false;
        // Skip: the largest parallax is below a fraction of a pixel: a plain texture looks the same.
        if (d.skips) {
            const double area = projected_area_pixels(cam, corners());
            if (area >= 0) {
                const double pixels_per_texel = std::sqrt(area / (double(t.width) * t.height));
                plain = max_parallax_texels(t, k) * pixels_per_texel < d.subpixel_parallax;
            }
        }
        if (plain) {
            rep.skips.push_back(kSkipSubpixelParallax);
        } else {
            PrewarpOptions o = options;
            o.method = method == RenderMethod::two_pass ? Reconstruction::two_pass : Reconstruction::pipelined;
            const bool same_setup = cached_.valid && cached_.level == lvl && cached_.method == method &&
                                    cached_.exact == o.exact && cached_.keep_outliers == o.keep_outliers &&
                                    cached_.displ == d.depth_correction;
            // Skip: the eye moved so little that no texel would move by more than the tolerance.
            if (d.skips && same_setup && max_texel_motion(t, cached_.k, k) < d.reuse_tolerance) {
                rep.skips.push_back(kSkipReuse);
            } else {
                const auto t0 = Clock::now();
                stats_ = rtm::prewarp(t, k, o, workspace_, prewarped_, d.depth_correction ? &displ_ : nullptr);
                times.prewarp_ms += ms_since(t0);
                cached_ = {true, lvl, method, o.exact, o.keep_outliers, d.depth_correction, k};
            }
            img = &prewarped_;
            warped = true;
            kind = 1;
            const PrewarpExtent& e = stats_.extent;
            rs.margin_left = e.left;
            rs.margin_right = e.right;
            rs.margin_bottom = e.bottom;
            rs.margin_top = e.top;
            if (o.keep_outliers) {
                rs.wall_low = std::min(0.0, t.quant.min);
                rs.wall_high = std::max(0.0, t.quant.max);
            }
        }
    }
    if (!img) {
        if (flat_level_ != lvl) {
            flat_ = flat_texture(t);
            flat_level_ = lvl;
        }
        img = &flat_;
        kind = 2 + lvl;
    }
    if (!facing) return done();  // skips disabled: the work was done to be measured, nothing is drawn

    auto t0 = Clock::now();
    // Skip: upload only the rectangle that changed since the last upload.
    if (d.skips && uploaded_kind_ == kind && uploaded_.width == img->width && uploaded_.height == img->height) {
        const Rect r = dirty_rect(*img, uploaded_);
        if (r.w * r.h < img->width * img->height) rep.skips.push_back(kSkipPartialUpload);
        if (r.w > 0) {
            texture_->upload_rect(*img, r.x, r.row, r.w, r.h);
            for (int row = r.row; row < r.row + r.h; ++row)
                std::copy(img->row(row) + r.x, img->row(row) + r.x + r.w, uploaded_.row(row) + r.x);
        }
        rep.uploaded_texels = (long long)r.w * r.h;
    } else {
        texture_->upload(*img);
        rep.uploaded_texels = (long long)img->width * img->height;
        if (d.skips) {
            uploaded_ = *img;
            uploaded_kind_ = kind;
        } else {
            uploaded_kind_ = -1;
        }
    }
    if (warped && d.depth_correction) {
        if (!displ_texture_) displ_texture_ = std::make_unique<GlTexture>();
        displ_texture_->upload_gray(displ_);
        rs.displ = displ_texture_.get();
        rs.k3 = compute_coefficients(t.geometry, cam.eye).k3;
        rs.dmin = t.quant.min;
        rs.dmax = t.quant.max;
        rs.qs = t.quant.qs;
    }
    renderer.finish();
    times.upload_ms += ms_since(t0);
    t0 = Clock::now();
    renderer.draw_relief(cam, rs, *texture_);
    renderer.finish();
    times.texture_map_ms += ms_since(t0);
    done();
}

}  // namespace rtm
