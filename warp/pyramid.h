// Relief texture pyramids (paper section 4.3, Figure 20). Level i averages blocks of 2^i x 2^i texels of level 0
// (colour and exact displacement; empty texels do not take part, and a block with no non-empty texel is empty),
// and its a, b grow with the texel size so the relief covers the same area: a_i = a * (w / w_i), which is
// exactly a doubling per level when the size is a power of two. Levels shrink to 1x1 (w_i = ceil(w / 2^i)).
// Displacement is re-quantized with the level-0 quantizer, so min and qs are shared by all levels.
#pragma once

#include <memory>
#include <mutex>
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

// The geometry of a w x h level of `level0`'s pyramid: level 0's origin, a and b grown to cover the same area.
ReliefGeometry level_geometry(const ReliefTexture& level0, int w, int h);

// Whether a and b hold the same texels and displacements because they are copies of one relief (their arrays shared,
// SharedArray) with the same quantizer: what may share one SharedPyramid.
bool same_texels(const ReliefTexture& a, const ReliefTexture& b);

// Levels 1.. of one relief's pyramid, built on first use and shared by the relief quads that hold copies of that
// relief differing only in geometry (a scene's placements of one file at one scale, objects/scene.cpp): their levels
// hold the same texels, so the quads keep one copy of them (SharedArray) and each its own geometry. Safe to call
// from several threads at once.
class SharedPyramid {
public:
    // Level i >= 1 of level0's pyramid (clamped to the 1x1 level, as ReliefQuad::level), with level0's geometry
    // (level_geometry). Every level0 asked must hold the same texels as the first one asked (same_texels):
    // std::logic_error otherwise.
    ReliefTexture level(const ReliefTexture& level0, int i);

private:
    std::mutex mutex_;
    ReliefTexture level0_;               // the first level0 asked, its arrays shared
    std::vector<ReliefTexture> levels_;  // levels 1.., level0_'s geometry
};

// The level whose texel density roughly matches the pixel density: with `texels` texels at level 0 covering
// `pixels` pixels on screen, each level divides the texel count by 4, so level = floor(log2(texels/pixels) / 2),
// clamped to [0, max_level]. A quad covering no pixel gets max_level.
int level_for_density(double texels, double pixels, int max_level);

}  // namespace rtm
