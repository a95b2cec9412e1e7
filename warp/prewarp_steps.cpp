#include "warp/prewarp_steps.h"

#include "warp/reference/reference_prewarp.h"

namespace rtm {

PrewarpSteps prewarp_steps(const ReliefTexture& relief, const PrewarpCoefficients& k, PrewarpOptions options) {
    options.method = Reconstruction::two_pass;
    options.isa = Isa::generic;
    PrewarpWorkspace ws;
    PrewarpSteps s;
    s.stats = reference::prewarp(relief, k, options, prewarp_extent(relief, k, options), ws, s.prewarped, nullptr);
    // The reference two-pass kernels leave the horizontal pass's output in mid_color (none when nothing was warped:
    // the eye in the relief's plane, or an empty relief).
    s.horizontal = ws.mid_color;
    if (s.horizontal.width != s.prewarped.width || s.horizontal.height != relief.height)
        s.horizontal = ImageRGBA8(s.prewarped.width, relief.height);
    return s;
}

}  // namespace rtm
