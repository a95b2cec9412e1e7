#include "warp/prewarp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "warp/reference/reference_prewarp.h"
#include "warp/simd/schedule.h"

namespace rtm {

std::string to_string(Reconstruction m) { return m == Reconstruction::two_pass ? "two-pass" : "pipelined"; }
std::string to_string(Filter f) { return f == Filter::point ? "point" : "coverage"; }

long long count_still_texels(const ReliefTexture& t, bool exact) {
    // The tables' still levels do not depend on the view: build them for any coefficients.
    const PrewarpTables tab = PrewarpTables::build(PrewarpCoefficients{}, t.quant);
    long long n = 0;
    for (size_t i = 0; i < t.texels.size(); ++i) {
        const uint8_t q = t.texels[i].q;
        n += exact ? q != kEmptyIndex && t.displacement[i] == 0.0f : tab.still[q] != 0;
    }
    return n;
}

void widen_by_warped_box(const PrewarpCoefficients& k, double us0, double us1, double vs0, double vs1, double dmin,
                         double dmax, double& umin, double& umax, double& vmin, double& vmax) {
    auto clampd = [&](double d) { return 1.0 + k.k3 * d > 1e-6 ? d : (1e-6 - 1.0) / k.k3; };
    for (double d : {clampd(dmin), clampd(dmax)})
        for (double us : {us0, us1})
            for (double vs : {vs0, vs1}) {
                double ui, vi;
                if (!k.warp(us, vs, d, ui, vi)) continue;
                umin = std::min(umin, ui);
                umax = std::max(umax, ui);
                vmin = std::min(vmin, vi);
                vmax = std::max(vmax, vi);
            }
}

PrewarpExtent outlier_extent(const ReliefTexture& t, const PrewarpCoefficients& k, int max_margin) {
    PrewarpExtent e;
    if (k.side == ViewSide::on_plane) return e;
    double umin = 0, umax = t.width, vmin = 0, vmax = t.height;
    widen_by_warped_box(k, 0.0, double(t.width), 0.0, double(t.height), t.quant.min, t.quant.max, umin, umax, vmin,
                        vmax);
    auto margin = [&](double over) {
        const double m = std::ceil(std::max(0.0, over));
        return int(std::min(m, double(max_margin)));
    };
    e.left = margin(-umin);
    e.right = margin(umax - t.width);
    e.bottom = margin(-vmin);
    e.top = margin(vmax - t.height);
    return e;
}

PrewarpExtent prewarp_extent(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options) {
    if (!options.keep_outliers) return {};
    const int mm = options.max_margin >= 0 ? options.max_margin : std::max(relief.width, relief.height) * 2;
    PrewarpExtent e = outlier_extent(relief, k, mm);
    const auto cap = [](int& side, int c) {
        if (c >= 0) side = std::min(side, c);
    };
    cap(e.left, options.margin_cap[0]);
    cap(e.right, options.margin_cap[1]);
    cap(e.bottom, options.margin_cap[2]);
    cap(e.top, options.margin_cap[3]);
    return e;
}

PrewarpStats prewarp(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options,
                     PrewarpWorkspace& ws, ImageRGBA8& out, Image2D<uint8_t>* displ_out) {
    const PrewarpExtent e = prewarp_extent(relief, k, options);
    if (options.filter == Filter::coverage && options.method != Reconstruction::two_pass)
        throw std::invalid_argument("the coverage filter works with the two-pass reconstruction only (method " +
                                    to_string(options.method) + ")");
    // The chosen target's kernels where they cover the case (warp/simd/schedule.h), else the reference ones.
    const Isa isa = resolve_isa(options.isa);
    if (fast_prewarp_covers(isa, relief, k, options, e, displ_out))
        return fast_prewarp(isa, relief, k, options, e, ws, out);
    return reference::prewarp(relief, k, options, e, ws, out, displ_out);
}
ImageRGBA8 prewarp(const ReliefTexture& relief, const glm::dvec3& eye, const PrewarpOptions& options) {
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    prewarp(relief, compute_coefficients(relief.geometry, eye), options, ws, out);
    return out;
}

}  // namespace rtm
