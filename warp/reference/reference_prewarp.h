// The reference kernels of the pre-warp (the generic target, warp/isa.h): prewarp()'s output for every case, in
// scalar C++ that follows the paper step by step (warp/prewarp.h describes what it computes). Every SIMD kernel
// (warp/simd/) is compared with these pixel by pixel; prewarp() hands them whatever the chosen target's kernels do
// not cover.
#pragma once

#include "warp/image.h"
#include "warp/prewarp.h"

namespace rtm::reference {

// The pre-warp with margins `extent` (prewarp_extent of the options); `out` is resized to the relief plus them.
PrewarpStats prewarp(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options,
                     const PrewarpExtent& extent, PrewarpWorkspace& workspace, ImageRGBA8& out,
                     Image2D<uint8_t>* displ_out);

}  // namespace rtm::reference
