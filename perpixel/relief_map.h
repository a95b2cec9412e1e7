// The textures the per-pixel methods read, made on the CPU from a relief texture: the colour (premultiplied by
// coverage alpha, empty texels (0, 0, 0, 0), as the texture-mapping stage expects) and the relief map of
// Policarpo et al.: one RGBA8 texel per relief texel, the unit normal in RGB (n * 0.5 + 0.5, in the frame
// (a/|a|, b/|b|, f)) and the depth in alpha. Depth is 0 at the top of the displacement range and 1 at the bottom:
// alpha = 254 - q for quantized index q (shared with the pre-warp), so the shader's depth = alpha / 254 is exact
// on every level and bilinear filtering interpolates it between texel centres. Empty texels get depth 1 (the
// colour's alpha makes them holes).
#pragma once

#include "warp/image.h"
#include "warp/relief_texture.h"

namespace rtm {

ImageRGBA8 perpixel_color_texture(const ReliefTexture& t);
// Normals from the exact displacement by central differences (one-sided at borders and beside empty texels).
ImageRGBA8 perpixel_relief_map(const ReliefTexture& t);
// The exact depth map (PerPixelCommon::float_textures): depth = (max - displacement) / (max - min) of the
// quantizer's range from the exact displacement, in float, not quantized; empty texels (and a zero range) 1.
ImageF perpixel_depth_map(const ReliefTexture& t);

}  // namespace rtm
