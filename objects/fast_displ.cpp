#include "objects/fast_displ.h"

#include <stdexcept>

#include "warp/isa.h"
#include "warp/simd/schedule.h"

namespace rtm {

ReliefTexture index_relief(const ReliefTexture& t) {
    ReliefTexture o = t;
    for (ReliefTexel& x : o.texels.edit())
        if (x.q != kEmptyIndex) x.r = x.g = x.b = x.q;
    return o;
}

bool fast_displ_covers(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpOptions& o) {
    // Reliefs with discontinuity marks (which the AVX-512 two-pass kernels cover for colour) keep the reference's
    // exact displacement: the index image would differ from it by up to a level, and depth-corrected pictures of
    // marked reliefs stay what they were.
    if (!t.breaks.empty() || t.discontinuity_threshold > 0.0) return false;
    return fast_prewarp_covers(resolve_isa(o.isa), t, k, o, prewarp_extent(t, k, o), nullptr);
}

PrewarpStats prewarp_fast_displ(const ReliefTexture& t, const ReliefTexture& index, const PrewarpCoefficients& k,
                                const PrewarpOptions& o, PrewarpWorkspace& ws, ImageRGBA8& out, Image2D<uint8_t>& displ,
                                ImageRGBA8& scratch) {
    if (!fast_displ_covers(t, k, o)) throw std::logic_error("prewarp_fast_displ: the fast kernels do not cover this");
    const PrewarpStats stats = prewarp(t, k, o, ws, out);
    prewarp(index, k, o, ws, scratch);
    displ.resize(scratch.width, scratch.height);
    // Point sampling: alpha is 0 (no sample) or 255.
    for (size_t i = 0; i < scratch.pixels.size(); ++i)
        displ.pixels[i] = scratch.pixels[i].a == 0 ? kEmptyIndex : scratch.pixels[i].r;
    return stats;
}

}  // namespace rtm
