// One frame of a relief quad with any method: the texture methods (flat, two-pass, pipelined) and the ground
// truths (micromesh through the same OpenGL path, raycast on the CPU). Shared by `rtm render` and `rtm compare`.
#pragma once

#include <functional>

#include "objects/relief_quad.h"
#include "texmap/renderer.h"

namespace rtm {

struct RenderSettings {
    RenderMethod method = RenderMethod::two_pass;
    PrewarpOptions prewarp;                // keep_outliers = side polygons
    DrawOptions draw;                      // depth correction, pyramid level, skips
    PerPixelSettings perpixel;             // the per-pixel methods' parameters
    std::function<void(double)> progress;  // for slow methods (raycast); may be empty
};

// Draws one frame (`report`, if not null, receives the level used and the skips that fired) (begin_frame included;
// `renderer` may be null for raycast) and returns the image read back. `times` accumulates the stage times; reading the
// image back is not counted in them.
ImageRGBA8 render_relief_frame(ReliefQuad& quad, Renderer* renderer, const Camera& cam, const RenderSettings& s,
                               StageTimes& times, DrawReport* report = nullptr);

}  // namespace rtm
