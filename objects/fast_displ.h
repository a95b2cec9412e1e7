// Depth correction's displacement image (paper section 4.2) by the fast pre-warp kernels. The fast kernels
// (warp/simd/) warp colour only, so a pre-warp asked for the displacement seen at each output pixel ran on the
// reference kernels, about ten times slower: on the town's path at 640x480 the frame's CPU time was 46 ms with depth
// correction against 18.5 without (rtm bench --scene-only, docs/BENCHMARKS.md). Here the colour is pre-warped by the
// fast kernels as before, and the displacement by a second fast pre-warp of the same relief whose colour is its
// quantized displacement index (index_relief): the same samples, spans and coverage, the index interpolated along
// the spans as colour is (8 bits, rounded) where the reference interpolates the displacement and then quantizes it.
// So the colour is the reference's bit for bit, empty pixels are the same, and an index differs from the
// reference's by at most one level (qs of the relief's range) where a span interpolates between different indices
// (tests/objects/fast_displ_test.cpp).
#pragma once

#include "warp/image.h"
#include "warp/prewarp.h"
#include "warp/prewarp_coefficients.h"
#include "warp/relief_texture.h"

namespace rtm {

// `t` with each non-empty texel's colour replaced by its displacement index (r = g = b = q).
ReliefTexture index_relief(const ReliefTexture& t);

// True when the fast kernels pre-warp `t` for `k` with `o` (warp/simd/schedule.h), so prewarp_fast_displ applies.
// Never for a relief with discontinuity marks: its displacement stays the reference's, exact.
bool fast_displ_covers(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpOptions& o);

// The pre-warp of `t` into `out` and the displacement index seen at each output pixel into `displ` (kEmptyIndex
// where no sample landed), by two fast pre-warps; `index` is index_relief(t), `scratch` the second one's image.
// Returns the colour pre-warp's statistics. Requires fast_displ_covers.
PrewarpStats prewarp_fast_displ(const ReliefTexture& t, const ReliefTexture& index, const PrewarpCoefficients& k,
                                const PrewarpOptions& o, PrewarpWorkspace& ws, ImageRGBA8& out, Image2D<uint8_t>& displ,
                                ImageRGBA8& scratch);

}  // namespace rtm
