#include "objects/level_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "objects/frame_plan.h"
#include "objects/view_analysis.h"
#include "warp/prewarp_coefficients.h"
#include "warp/pyramid.h"

namespace rtm {

std::vector<double> level_displacement_spreads(const ReliefTexture& t) {
    const int levels = pyramid_levels(t.width, t.height);
    std::vector<double> spreads(size_t(levels), 0.0);
    // Per texel of the current level, the min and max of its level-0 texels' displacements, indexed by (x, v-row)
    // with v-row 0 at the bottom (warp/pyramid.cpp's block alignment); min > max marks an empty block.
    int w = t.width, h = t.height;
    std::vector<float> lo(size_t(w) * size_t(h)), hi(lo.size());
    for (int j = 0; j < h; ++j)
        for (int x = 0; x < w; ++x) {
            const int row = h - 1 - j;
            const size_t i = size_t(j) * size_t(w) + size_t(x);
            const bool empty = t.texel(x, row).q == kEmptyIndex;
            lo[i] = empty ? std::numeric_limits<float>::infinity() : t.displ(x, row);
            hi[i] = empty ? -std::numeric_limits<float>::infinity() : t.displ(x, row);
        }
    for (int l = 1; l < levels; ++l) {
        const int nw = (w + 1) / 2, nh = (h + 1) / 2;
        std::vector<float> nlo(size_t(nw) * size_t(nh)), nhi(nlo.size());
        double worst = spreads[size_t(l) - 1];
        for (int j = 0; j < nh; ++j)
            for (int x = 0; x < nw; ++x) {
                float a = std::numeric_limits<float>::infinity(), b = -a;
                for (int dj = 0; dj < 2; ++dj)
                    for (int dx = 0; dx < 2; ++dx) {
                        const int sx = 2 * x + dx, sj = 2 * j + dj;
                        if (sx >= w || sj >= h) continue;
                        const size_t s = size_t(sj) * size_t(w) + size_t(sx);
                        a = std::min(a, lo[s]);
                        b = std::max(b, hi[s]);
                    }
                const size_t i = size_t(j) * size_t(nw) + size_t(x);
                nlo[i] = a;
                nhi[i] = b;
                if (a <= b) worst = std::max(worst, double(b) - double(a));
            }
        spreads[size_t(l)] = worst;
        lo.swap(nlo);
        hi.swap(nhi);
        w = nw;
        h = nh;
    }
    return spreads;
}

double parallax_pixels_per_unit(const Camera& cam, const ReliefTexture& t) {
    const double reach = std::max(std::abs(t.quant.min), std::abs(t.quant.max));
    if (!(reach > 0.0)) return 0.0;
    const double area = projected_area_pixels(cam, quad_corners(t));
    if (area < 0) return std::numeric_limits<double>::infinity();
    const double pixels_per_texel = std::sqrt(area / (double(t.width) * t.height));
    const double parallax = max_parallax_texels(t, compute_coefficients(t.geometry, cam.eye));
    return parallax * pixels_per_texel / reach;
}

int choose_level(const Camera& cam, const ReliefTexture& t, const std::vector<double>& spreads, double max_error_px) {
    const int density = auto_level(cam, t);
    if (density == 0) return 0;
    const double per_unit = parallax_pixels_per_unit(cam, t);
    for (int l = std::min(density, int(spreads.size()) - 1); l > 0; --l)
        if (spreads[size_t(l)] == 0.0 || spreads[size_t(l)] * per_unit <= max_error_px) return l;
    return 0;
}

}  // namespace rtm
