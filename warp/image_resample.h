// Resampling an image to another size with a tent (triangle) filter, separably (rows, then columns): bilinear
// interpolation when enlarging, an area-weighted average over the source texels under each output texel when
// shrinking (the tent's radius is then the scale factor), so that shrinking does not alias. Texel centres map onto
// texel centres (output x covers source u in [x * s, (x + 1) * s), s = source width / output width), edges are
// clamped. The weights are non-negative and sum to one: a constant image stays constant and no value leaves the
// source's range. The same size is the identity. Used by rtm bake --height --size (formats/height_map.h).
#pragma once

#include "warp/image.h"

namespace rtm {

// Throws std::invalid_argument for an empty source or a width or height < 1.
ImageF resample_tent(const ImageF& src, int width, int height);
// Each channel (R, G, B, A) on its own, rounded to the nearest level.
ImageRGBA8 resample_tent(const ImageRGBA8& src, int width, int height);

}  // namespace rtm
