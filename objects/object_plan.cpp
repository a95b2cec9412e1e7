#include "objects/object_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "objects/bounds.h"
#include "objects/level_choice.h"
#include "objects/view_analysis.h"

namespace rtm {

double box_parallax_texels(const ReliefTexture& t, const PrewarpCoefficients& k, double depth) {
    double m = 0.0;
    for (double d : {-depth, 0.0}) {
        const double den = 1.0 + k.k3 * d;
        if (!(den > 0.0)) return std::numeric_limits<double>::infinity();
        const double s = 1.0 / den - 1.0;
        for (double u : {0.0, double(t.width)}) m = std::max(m, std::abs((u - k.epipole_u) * s));
        for (double v : {0.0, double(t.height)}) m = std::max(m, std::abs((v - k.epipole_v) * s));
    }
    return m;
}

ObjectFacePlan plan_object_face(const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                                const DrawOptions& d, const ObjectRegion& region, int face, const ReliefTexture& relief,
                                const LevelSource& level, double depth, const LastFacePrewarp& last,
                                const std::vector<double>* spreads) {
    const bool warp_method = prewarps(method);
    if (!warp_method && method != RenderMethod::flat)
        throw std::invalid_argument("plan_object_face: method " + to_string(method) + " is not a texture method");
    ObjectFacePlan p;
    const std::array<glm::dvec3, 4> corners = quad_corners(relief);
    if (d.skips) {
        Bounds quad_bounds;
        for (const glm::dvec3& c : corners) quad_bounds.extend(c);
        if (outside_frustum(cam, quad_bounds)) {
            p.skips.push_back(kSkipOutsideFrustum);
            return p;
        }
    }
    if (d.level < 0) {  // the relief quad's rule on the face's texture (plan_frame's)
        std::vector<double> own;
        if (!spreads) own = level_displacement_spreads(relief);
        p.level = choose_level(cam, relief, spreads ? *spreads : own, d.level_error_px);
    } else {
        p.level = std::clamp(d.level, 0, pyramid_levels(relief.width, relief.height) - 1);
    }
    const ReliefTexture& t = level(p.level);
    p.k = compute_coefficients(t.geometry, cam.eye);
    p.action = FrameAction::flat;
    if (!warp_method) return p;
    if (d.skips) {
        const double area = projected_area_pixels(cam, corners);
        if (area >= 0) {
            const double pixels_per_texel = std::sqrt(area / (double(t.width) * t.height));
            if (box_parallax_texels(t, p.k, depth) * pixels_per_texel < d.subpixel_parallax) {
                p.skips.push_back(kSkipSubpixelParallax);
                return p;
            }
        }
    }
    p.prewarp = options;
    p.prewarp.method = method == RenderMethod::two_pass ? Reconstruction::two_pass : Reconstruction::pipelined;
    p.prewarp.copy_still_runs = options.copy_still_runs && d.skips;
    p.prewarp.keep_outliers = false;  // an object draws no side polygons
    p.setup.setup = {p.level, method, p.prewarp.exact, false, d.depth_correction, p.prewarp.filter};
    p.setup.adjacent = faces_warped_onto(region, face);
    if (d.skips && last.valid && last.setup == p.setup &&
        max_motion_texels(t.width, t.height, -depth, 0.0, last.k, p.k) < d.reuse_tolerance) {
        p.skips.push_back(kSkipReuse);
        p.action = FrameAction::reuse;
        return p;
    }
    p.action = FrameAction::prewarp;
    return p;
}

}  // namespace rtm
