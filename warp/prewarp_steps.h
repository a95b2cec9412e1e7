// The pre-warp shown step by step (the paper's Figures 8-10): the image after the horizontal pass of the two-pass
// reconstruction and the pre-warped texture, for figures and teaching. It runs the reference two-pass kernels
// (warp/reference) and copies out the intermediate they leave in the workspace (PrewarpWorkspace::mid_color), so the
// normal pre-warp path is untouched and pays nothing for it.
#pragma once

#include "warp/prewarp.h"

namespace rtm {

struct PrewarpSteps {
    // After the horizontal pass: every texel moved to its final column, still on its source row (the output's
    // width, the relief's height; alpha 0 where nothing landed).
    ImageRGBA8 horizontal;
    ImageRGBA8 prewarped;  // after the vertical pass: prewarp()'s output for the same options
    PrewarpStats stats;
};

// The two passes of `relief`'s pre-warp for the eye in `k`. options.method and options.isa are ignored (two-pass,
// generic); the other options apply as in prewarp().
PrewarpSteps prewarp_steps(const ReliefTexture& relief, const PrewarpCoefficients& k, PrewarpOptions options);

}  // namespace rtm
