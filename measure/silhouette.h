// The silhouette error of a rendering against a reference: how far, in pixels, the outline of what the rendering
// covers lies from the reference's outline. Coverage is image_diff's (measure/image_diff.h: not the opaque-black
// background, alpha != 0).
//
// A silhouette pixel is a covered pixel with at least one of its four neighbours not covered; pixels outside the
// image count as not covered (a surface cut by the image border has its outline there).
#pragma once

#include <vector>

#include "warp/image.h"

namespace rtm {

// 1 at the silhouette pixels of `img`, else 0 (row-major, img.width * img.height).
std::vector<unsigned char> silhouette_mask(const ImageRGBA8& img);

// Mean Euclidean distance (pixel centres) from each silhouette pixel of `test` to the nearest silhouette pixel of
// `ref`: 0 when the outlines agree; a shape shifted by k pixels scores about 2k/pi for a disc (the mean of
// k*|cos|), k for a straight edge across the shift. NaN when either image has no silhouette (nothing to measure),
// unless neither has one (0: they agree). Throws std::invalid_argument when the sizes differ.
double silhouette_error(const ImageRGBA8& ref, const ImageRGBA8& test);

// Squared Euclidean distance from every pixel to the nearest set pixel of `mask` (w x h, row-major); +infinity
// everywhere when no pixel is set. Exact (Felzenszwalb and Huttenlocher, "Distance transforms of sampled
// functions", Theory of Computing 2012: two passes of the 1-D lower envelope of parabolas), O(w*h).
std::vector<double> squared_distance_transform(const std::vector<unsigned char>& mask, int w, int h);

// The same by brute force, O((w*h)^2): the reference the fast transform is tested against.
std::vector<double> squared_distance_transform_naive(const std::vector<unsigned char>& mask, int w, int h);

}  // namespace rtm
