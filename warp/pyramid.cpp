#include "warp/pyramid.h"

#include <algorithm>
#include <cmath>

namespace rtm {

ReliefTexture downsample(const ReliefTexture& t, const ReliefTexture& level0) {
    const int w = (t.width + 1) / 2, h = (t.height + 1) / 2;
    ReliefTexture o;
    o.width = w;
    o.height = h;
    o.quant = t.quant;
    o.geometry = t.geometry;
    // Keep the covered area: w * |a_new| = level0.width * |a0|.
    o.geometry.a = level0.geometry.a * (double(level0.width) / w);
    o.geometry.b = level0.geometry.b * (double(level0.height) / h);
    o.texels.assign(size_t(w) * size_t(h), ReliefTexel{});
    o.displacement.assign(size_t(w) * size_t(h), 0.0f);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) {
            // Blocks align with the BOTTOM-left corner in (u, v): v-rows 2j, 2j+1 of the source. Storage rows
            // count from the top, so map through v-rows to keep the quad's origin fixed.
            const int j = h - 1 - r;
            double sr = 0, sg = 0, sb = 0, sd = 0;
            int n = 0;
            for (int dj = 0; dj < 2; ++dj)
                for (int dx = 0; dx < 2; ++dx) {
                    const int sx = 2 * x + dx, sj = 2 * j + dj;
                    if (sx >= t.width || sj >= t.height) continue;
                    const int srow = t.height - 1 - sj;
                    const ReliefTexel& tx = t.texel(sx, srow);
                    if (tx.q == kEmptyIndex) continue;
                    sr += tx.r;
                    sg += tx.g;
                    sb += tx.b;
                    sd += t.displ(sx, srow);
                    ++n;
                }
            const size_t i = size_t(r) * size_t(w) + size_t(x);
            if (n == 0) continue;
            const double d = sd / n;
            o.displacement[i] = float(d);
            o.texels[i] = {uint8_t(std::lround(sr / n)), uint8_t(std::lround(sg / n)), uint8_t(std::lround(sb / n)),
                           o.quant.encode(d)};
        }
    return o;
}

ReliefPyramid::ReliefPyramid(ReliefTexture level0) {
    levels_.push_back(std::move(level0));
    while (levels_.back().width > 1 || levels_.back().height > 1)
        levels_.push_back(downsample(levels_.back(), levels_.front()));
}

int level_for_density(double texels, double pixels, int max_level) {
    if (!(pixels > 0.0)) return max_level;
    if (!(texels > pixels)) return 0;
    const int l = int(std::floor(std::log2(texels / pixels) / 2.0));
    return std::clamp(l, 0, max_level);
}

}  // namespace rtm
