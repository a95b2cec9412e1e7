// Relief texture pyramids (paper section 4.3, Figure 20). Level i averages blocks of 2^i x 2^i texels of level 0
// (colour and exact displacement; empty texels do not take part, and a block with no non-empty texel is empty),
// and its a, b grow with the texel size so the relief covers the same area: a_i = a * (w / w_i), which is
// exactly a doubling per level when the size is a power of two. Levels shrink to 1x1 (w_i = ceil(w / 2^i)).
// Displacement is re-quantized with the level-0 quantizer, so min and qs are shared by all levels.
#pragma once

#include <vector>

#include "relief_texture.h"

namespace rtm {

class ReliefPyramid {
public:
    ReliefPyramid() = default;
    explicit ReliefPyramid(ReliefTexture level0);
    int levels() const { return int(levels_.size()); }
    const ReliefTexture& level(int i) const { return levels_.at(size_t(i)); }

private:
    std::vector<ReliefTexture> levels_;
};

// One level from the level before it (2x2 blocks, with the averaging rule above).
ReliefTexture downsample(const ReliefTexture& t, const ReliefTexture& level0);

// The level whose texel density roughly matches the pixel density: with `texels` texels at level 0 covering
// `pixels` pixels on screen, each level divides the texel count by 4, so level = floor(log2(texels/pixels) / 2),
// clamped to [0, max_level]. A quad covering no pixel gets max_level.
int level_for_density(double texels, double pixels, int max_level);

}  // namespace rtm
