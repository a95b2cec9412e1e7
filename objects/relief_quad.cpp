#include "objects/relief_quad.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "objects/bounds.h"
#include "truth/micromesh.h"
#include "warp/timing.h"
#include "objects/view_analysis.h"
#include "warp/pyramid.h"

namespace rtm {

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

void premultiply_alpha(ImageRGBA8& img) {
    for (Rgba8& p : img.pixels) {
        if (p.a == 255) continue;
        auto m = [&](uint8_t c) { return uint8_t((unsigned(c) * p.a + 127) / 255); };
        p = {m(p.r), m(p.g), m(p.b), p.a};
    }
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

long long ReliefQuad::still_texels(int i, bool exact) {
    if (int(still_texels_.size()) <= i) still_texels_.resize(size_t(i) + 1, {-1, -1});
    long long& n = still_texels_[size_t(i)][exact];
    if (n < 0) n = count_still_texels(level_texture(i), exact);
    return n;
}

const MovingTexels& ReliefQuad::moving(int i) {
    if (int(moving_.size()) <= i) moving_.resize(size_t(i) + 1);
    std::optional<MovingTexels>& m = moving_[size_t(i)];
    if (!m) m = moving_texels(level_texture(i));
    return *m;
}

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
    ++prewarp_version_;
    cached_.valid = false;
    return ms_since(t0);
}

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
            o.copy_still_runs = options.copy_still_runs && d.skips;  // --no-skips: warp every texel
            const bool same_setup = cached_.valid && cached_.level == lvl && cached_.method == method &&
                                    cached_.exact == o.exact && cached_.keep_outliers == o.keep_outliers &&
                                    cached_.displ == d.depth_correction && cached_.filter == o.filter;
            // Skip: the eye moved so little that no texel would move by more than the tolerance.
            if (d.skips && same_setup && max_texel_motion(t, cached_.k, k) < d.reuse_tolerance) {
                rep.skips.push_back(kSkipReuse);
            } else {
                const auto t0 = Clock::now();
                stats_ = rtm::prewarp(t, k, o, workspace_, prewarped_, d.depth_correction ? &displ_ : nullptr);
                ++prewarp_version_;
                // Coverage alpha: the texture-mapping stage expects premultiplied colour (it divides the
                // filtered colour by the filtered alpha); point-sampled output has alpha 0 or 255 only.
                if (o.filter == Filter::coverage) premultiply_alpha(prewarped_);
                if (o.keep_outliers) {
                    const PrewarpExtent& e = stats_.extent;
                    wall_content_ = margin_content(prewarped_, e.left, e.right, e.bottom, e.top);
                }
                times.prewarp_ms += ms_since(t0);
                cached_ = {true, lvl, method, o.exact, o.keep_outliers, d.depth_correction, o.filter, k};
                // Skip: texels at zero displacement were copied, not warped (paper section 5, the brick wall).
                // The reference kernels count their copies; the avx512 kernels copy one-pixel spans on pixel
                // centres without counting, and the still texels are a property of the level, counted once. (The
                // Highway kernels draw such spans like any other: no skip.)
                const long long still = o.copy_still_runs ? still_texels(lvl, o.exact) : 0;
                if (still > 0 && (stats_.still_copied > 0 || stats_.isa == Isa::avx512)) {
                    rep.skips.push_back(kSkipZeroRuns);
                    rep.still_texels = still;
                    rep.still_copied = stats_.still_copied;
                }
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
                rs.wall_content = &wall_content_;
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
    // Skip: upload only the pixels that can differ from the texture already on the GPU. Pixels that moving texels
    // cannot reach are written by still texels only and are the same in every pre-warp of this level and setup
    // (moving_footprint, objects/view_analysis.h), so the changed pixels lie in the union of the moving footprints
    // of the uploaded pre-warp and of this one: eight corner warps per frame, nothing read or kept.
    // Comparing the new image with a copy of the last upload, as this skip first did, cannot pay with llvmpipe
    // (OSMesa), where an upload is a memcpy: measured on the 2-core development machine, median ms, n^2 texels,
    //       n   full upload   find the changed rectangle (memcmp)   keep a copy   upload a 1.6% / 25% / 50% rectangle
    //     256     0.009              0.006                             0.007        0.0004 / 0.002 / 0.003
    //    1024     0.135              0.094 (0.33 in a frame, cold)     0.103        0.003  / 0.030 / 0.066
    //    2048     1.098              0.810                             0.914        0.009  / 0.178 / 0.429
    // (comparing pixel by pixel with Rgba8's operator== instead of memcmp: 0.056 ms at 256^2; that and the copy on
    // every frame whose margins changed the texture's size made bench-skips measure 1.0 -> 1.9 ms at 256^2). A
    // rectangle's upload costs in proportion to its area, so any rectangle smaller than the texture pays.
    const PixelRect whole{0, 0, img->width, img->height};
    const PixelRect moving_now =
        kind == 1 ? moving_footprint(t, moving(lvl), cached_.k, stats_.extent) : PixelRect{};
    PixelRect r = whole;
    if (d.skips && uploaded_.kind == kind && uploaded_.width == img->width && uploaded_.height == img->height) {
        if (kind != 1 || uploaded_.version == prewarp_version_) {
            r = {};  // the same image (a flat level, or a reused pre-warp)
        } else {
            const Cached& a = uploaded_.setup;
            const bool same_setup = a.level == cached_.level && a.method == cached_.method &&
                                    a.exact == cached_.exact && a.keep_outliers == cached_.keep_outliers &&
                                    a.filter == cached_.filter && uploaded_.extent == stats_.extent;
            if (same_setup) r = united(uploaded_.moving, moving_now);
        }
    }
    if (r.area() < whole.area()) {
        rep.skips.push_back(kSkipPartialUpload);
        if (!r.empty()) texture_->upload_rect(*img, r.x, r.row, r.w, r.h);
    } else {
        texture_->upload(*img);
    }
    rep.uploaded_texels = r.area();
    if (d.skips)
        uploaded_ = {kind, prewarp_version_, img->width, img->height, cached_, stats_.extent, moving_now};
    else
        uploaded_.kind = -1;
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
