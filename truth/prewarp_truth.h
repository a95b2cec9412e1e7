// The pre-warped texture as it should be, for measuring the pre-warp's resampling (point against coverage
// filtering, docs/ACCURACY.md): for every output pixel of prewarp() -- same frame, margins included -- the
// average, over S x S points spread evenly over the pixel's square of the relief plane, of what the eye sees
// through that point (exact ray cast of the bilinear surface, truth/raycast.h). Alpha is the fraction of the
// points whose ray hits the surface; colour is the average over those hits (straight, not premultiplied).
#pragma once

#include <functional>

#include <glm/vec3.hpp>

#include "warp/image.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm {

struct PrewarpTruthOptions {
    int samples = 8;                       // S: S x S rays per pixel
    int threads = 0;                       // 0 = all; the output does not depend on it
    std::function<void(double)> progress;  // fraction done, from the calling thread; may be empty
};

ImageRGBA8 prewarp_truth(const ReliefTexture& t, const glm::dvec3& eye, const PrewarpExtent& extent,
                         const PrewarpTruthOptions& options = {});

// Errors of a pre-warped texture against the truth, over the pixels at least `border` pixels inside the quad's
// edges (the ray-cast surface stops at the outermost texel centres, the pre-warp at texel edges, so the outer
// ring is a modelling difference, not a resampling error).
struct PrewarpError {
    double color_rmse = 0;    // RGB, 0..255, over pixels with alpha >= 1/2 in both
    double coverage_mae = 0;  // mean |alpha - alpha_truth| (0..1) over pixels covered (alpha > 0) in either
    double iou = 1;           // alpha >= 1/2 in both / in either
    long long pixels = 0;     // pixels compared for colour
};

PrewarpError prewarp_error(const ImageRGBA8& estimate, const ImageRGBA8& truth, const PrewarpExtent& extent,
                           int border = 1);

}  // namespace rtm
