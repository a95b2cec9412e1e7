#include "objects/frame_plan.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "objects/bounds.h"
#include "objects/level_choice.h"
#include "warp/pyramid.h"

namespace rtm {

std::string to_string(const TextureContent& c) {
    switch (c.source) {
        case TextureContent::Source::none: return "none";
        case TextureContent::Source::prewarp: return "prewarp of level " + std::to_string(c.level);
        case TextureContent::Source::flat: return "flat level " + std::to_string(c.level);
    }
    return "?";
}

std::string to_string(FrameAction a) {
    switch (a) {
        case FrameAction::nothing: return "nothing";
        case FrameAction::micromesh: return "micromesh";
        case FrameAction::flat: return "flat";
        case FrameAction::prewarp: return "prewarp";
        case FrameAction::reuse: return "reuse";
    }
    return "?";
}

std::string FramePlan::to_string() const {
    std::ostringstream os;
    os << "FramePlan{" << rtm::to_string(action) << " level=" << level << (draw ? "" : " not-drawn") << " skips=[";
    for (size_t i = 0; i < skips.size(); ++i) os << (i ? "," : "") << skips[i];
    os << "]";
    if (action == FrameAction::prewarp || action == FrameAction::reuse)
        os << " setup=" << rtm::to_string(setup.method) << (setup.exact ? "+exact" : "")
           << (setup.keep_outliers ? "+walls" : "") << (setup.displ ? "+depth" : "")
           << (setup.filter == Filter::coverage ? "+coverage" : "");
    os << "}";
    return os.str();
}

int pyramid_levels(int width, int height) {
    int n = 1, w = width, h = height;
    while (w > 1 || h > 1) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
        ++n;
    }
    return n;
}

int auto_level(const Camera& cam, const ReliefTexture& relief) {
    const double area = projected_area_pixels(cam, quad_corners(relief));
    if (area < 0) return 0;  // the quad reaches behind the eye: large on screen
    return level_for_density(double(relief.width) * relief.height, area,
                             pyramid_levels(relief.width, relief.height) - 1);
}

PrewarpExtent fit_texture_size(const PrewarpExtent& e, int width, int height, int max_size) {
    // One axis: margins lo and hi beside n texels, at most max_size in all; cut in proportion (what is left of the
    // budget goes to the larger side first, so the sum is exactly the budget).
    const auto fit = [max_size](int n, int& lo, int& hi) {
        const long long budget = std::max(0ll, (long long)max_size - n);
        if ((long long)lo + hi <= budget) return;
        const long long sum = (long long)lo + hi;
        const int new_lo = int(budget * lo / sum);
        hi = int(std::min<long long>(hi, budget - new_lo));
        lo = new_lo;
    };
    PrewarpExtent f = e;
    fit(width, f.left, f.right);
    fit(height, f.bottom, f.top);
    return f;
}

FramePlan plan_frame(const Camera& cam, RenderMethod method, const PrewarpOptions& options, const DrawOptions& d,
                     const ReliefTexture& relief, const LevelSource& level, const LastPrewarp& last,
                     const std::vector<double>* spreads) {
    const bool warp_method = prewarps(method);
    if (!warp_method && method != RenderMethod::flat)
        throw std::invalid_argument("plan_frame: method " + to_string(method) + " is not a texture method");
    FramePlan p;
    // Nothing of the relief can be on screen.
    if (d.skips && d.cull && outside_frustum(cam, relief_bounds(relief))) {
        p.skips.push_back(kSkipOutsideFrustum);
        return p;
    }
    // The eye is inside the relief's slab; texels above its plane cannot be pre-warped, so draw the micro-polygons
    // instead (paper sections 3 and 6: extreme close-ups).
    if (d.skips && warp_method && eye_inside_slab(relief, cam.eye)) {
        p.skips.push_back(kSkipInsideSlab);
        p.action = FrameAction::micromesh;
        return p;
    }
    p.draw = compute_coefficients(relief.geometry, cam.eye).side == ViewSide::front;
    if (!p.draw && d.skips && d.cull) {  // the quad faces away: not pre-warped, not drawn (paper section 6)
        p.skips.push_back(kSkipBackFacing);
        return p;
    }

    const int levels = pyramid_levels(relief.width, relief.height);
    if (d.level >= 0) {
        p.level = std::clamp(d.level, 0, levels - 1);
    } else if (spreads) {
        p.level = choose_level(cam, relief, *spreads, d.level_error_px);
    } else {
        p.level = choose_level(cam, relief, level_displacement_spreads(relief), d.level_error_px);
    }
    const ReliefTexture& t = level(p.level);
    p.k = compute_coefficients(t.geometry, cam.eye);
    p.action = FrameAction::flat;
    if (!warp_method) return p;

    // The largest parallax is below a fraction of a pixel: a plain texture looks the same.
    if (d.skips) {
        const double area = projected_area_pixels(cam, quad_corners(relief));
        if (area >= 0) {
            const double pixels_per_texel = std::sqrt(area / (double(t.width) * t.height));
            if (max_parallax_texels(t, p.k) * pixels_per_texel < d.subpixel_parallax) {
                p.skips.push_back(kSkipSubpixelParallax);
                return p;
            }
        }
    }
    p.prewarp = options;
    p.prewarp.method = method == RenderMethod::two_pass ? Reconstruction::two_pass : Reconstruction::pipelined;
    p.prewarp.copy_still_runs = options.copy_still_runs && d.skips;  // --no-skips: warp every texel
    p.setup = {p.level, method, p.prewarp.exact, p.prewarp.keep_outliers, d.depth_correction, p.prewarp.filter};
    // Margins (side polygons' texels) whose plane points project outside the viewport are never seen: pre-warp
    // only the margins the view can show, with a guard of 2 texels (bilinear filtering reads one texel beyond).
    PrewarpExtent extent = prewarp_extent(t, p.k, p.prewarp);
    bool margins_cut = false;
    if (d.skips && d.cull && p.prewarp.keep_outliers) {
        const PrewarpExtent seen = visible_margins(cam, t, extent, 2.0);
        if (seen != extent) {
            p.prewarp.margin_cap = {seen.left, seen.right, seen.bottom, seen.top};
            extent = seen;
            margins_cut = true;
        }
    }
    if (p.prewarp.keep_outliers && d.max_texture_size > 0) {
        const PrewarpExtent fit = fit_texture_size(extent, t.width, t.height, d.max_texture_size);
        if (fit != extent) {
            p.prewarp.margin_cap = {fit.left, fit.right, fit.bottom, fit.top};
            extent = fit;
        }
    }
    // The eye moved so little that no texel would move by more than the tolerance (and the last pre-warp holds the
    // margins this view can see).
    const auto covers = [](const PrewarpExtent& have, const PrewarpExtent& want) {
        return want.left <= have.left && want.right <= have.right && want.bottom <= have.bottom && want.top <= have.top;
    };
    if (d.skips && last.valid && last.setup == p.setup && covers(last.extent, extent) &&
        max_texel_motion(t, last.k, p.k) < d.reuse_tolerance) {
        p.skips.push_back(kSkipReuse);
        p.action = FrameAction::reuse;
        return p;
    }
    if (margins_cut) p.skips.push_back(kSkipOffscreenMargins);
    p.action = FrameAction::prewarp;
    return p;
}

UploadPlan plan_upload(const UploadedTexture& now, const UploadedTexture& last, bool skips) {
    UploadPlan u;
    const PixelRect whole{0, 0, now.width, now.height};
    u.rect = whole;
    if (skips && last.content == now.content && last.width == now.width && last.height == now.height) {
        if (now.content.source != TextureContent::Source::prewarp || last.version == now.version) {
            u.rect = {};  // the same image (a flat level, or a reused pre-warp)
        } else {
            // Depth correction does not change the pre-warped colours: a pre-warp with it and one without agree
            // outside their moving footprints.
            PrewarpSetup a = last.setup, b = now.setup;
            a.displ = b.displ = false;
            if (a == b && last.extent == now.extent) u.rect = united(last.moving, now.moving);
        }
    }
    u.partial = u.rect.area() < whole.area();
    u.next = skips ? now : UploadedTexture{};
    return u;
}
bool zero_runs_fired(const PrewarpStats& stats, long long still) {
    return still > 0 && (stats.still_copied > 0 || stats.isa != Isa::generic);
}

}  // namespace rtm
