// The pre-warp's output scale: pre-warping into a texture `factor` times the source's size in each direction
// (docs/DESIGN.md, "Output scale"). It is the pre-warp of the relief resampled onto a grid `factor` times finer
// that covers the same quad: the same origin, a and b divided by the factor. Every kernel then runs unchanged and
// the texture-mapping stage magnifies the pre-warped texture `factor` times less.
//
// Resampling: fine texel centres are placed in the source's texel coordinates (fine centre u_f = (X + 0.5) /
// factor source texels) and take the bilinear interpolation of colour and exact displacement of the four source
// texels around them (clamped at the borders), re-quantized with the source's quantizer. Bilinear interpolation
// reproduces a displacement linear in u and v exactly, so planes stay planes. A fine texel whose nearest source
// texel is empty is empty; empty neighbours take no part (the weights of the others are renormalized); where the
// four source texels are not all connected (surface discontinuities, section 4.1.1) the fine texel takes its
// nearest source texel instead, so no slope is made across a discontinuity, and the marks are recomputed on the
// fine grid with the source's threshold.
#pragma once

#include "relief_texture.h"

namespace rtm {

// factor 1 returns a copy; factor < 1 or a result over 2^28 texels throws std::invalid_argument naming the value.
ReliefTexture upsample(const ReliefTexture& source, int factor);

}  // namespace rtm
