#include "warp/pyramid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rtm {

ReliefTexture downsample(const ReliefTexture& t, const ReliefTexture& level0) {
    const int w = (t.width + 1) / 2, h = (t.height + 1) / 2;
    ReliefTexture o;
    o.width = w;
    o.height = h;
    o.quant = t.quant;
    o.geometry = level_geometry(level0, w, h);
    std::vector<ReliefTexel>& texels = o.texels.edit();
    std::vector<float>& displ = o.displacement.edit();
    texels.assign(size_t(w) * size_t(h), ReliefTexel{});
    displ.assign(size_t(w) * size_t(h), 0.0f);
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
            displ[i] = float(d);
            texels[i] = {uint8_t(std::lround(sr / n)), uint8_t(std::lround(sg / n)), uint8_t(std::lround(sb / n)),
                         o.quant.encode(d)};
        }
    return o;
}

ReliefGeometry level_geometry(const ReliefTexture& level0, int w, int h) {
    ReliefGeometry g = level0.geometry;
    // Keep the covered area: w * |a_new| = level0.width * |a0|.
    g.a = level0.geometry.a * (double(level0.width) / w);
    g.b = level0.geometry.b * (double(level0.height) / h);
    return g;
}

bool same_texels(const ReliefTexture& a, const ReliefTexture& b) {
    return a.texels.shares_storage_with(b.texels) && a.displacement.shares_storage_with(b.displacement) &&
           a.quant.min == b.quant.min && a.quant.max == b.quant.max;
}

ReliefTexture SharedPyramid::level(const ReliefTexture& level0, int i) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (level0_.texels.empty()) level0_ = level0;
    if (!same_texels(level0, level0_))
        throw std::logic_error("SharedPyramid::level: a relief whose texels are not those of the pyramid's level 0");
    while (int(levels_.size()) < i) {
        const ReliefTexture& prev = levels_.empty() ? level0_ : levels_.back();
        if (prev.width == 1 && prev.height == 1) break;
        levels_.push_back(downsample(prev, level0_));
    }
    if (levels_.empty()) return level0;  // a 1x1 relief is its only level
    ReliefTexture t = levels_[size_t(std::min<int>(i, int(levels_.size()))) - 1];
    t.geometry = level_geometry(level0, t.width, t.height);
    return t;
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
