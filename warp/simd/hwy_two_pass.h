// The two-pass pre-warp kernels written once over Google Highway, compiled for every SIMD target of this
// architecture (x86-64: AVX-512 with VBMI/VNNI and without, AVX2, SSE4; ARM: NEON and SVE) and chosen at run time
// (warp/isa.h). Their job is warp/simd/two_pass_job.h's, their scheduling warp/simd/schedule.cpp's; their output
// is prewarp()'s two-pass lookup-table path's bit for bit. (They replaced hand-written AVX-512 kernels of the same
// design: docs/perf-history.md.)
//
// Horizontal steps: each row is set up with the reference's own arithmetic, a vector of texels at a time (row_samples'
// positions and final row coordinates, NaN where a texel does not take part; the tables' entries looked up by
// displacement index: byte permutes on AVX-512, gathers or loads elsewhere), and drawn in the reference's
// occlusion-compatible order: consecutive spans of one orientation (a sub-run, either way along the row) have disjoint
// pixels and up to a vector of them are drawn together (from 8 lanes on, each pixel of the run looks its span up and
// the run is stored a vector of pixels at a time), everything else sample by sample through raster_point and
// raster_span. Rows that fold over (FastKernelPolicy:: two_pass_reverse) are drawn backwards, each pixel once
// (WarpRowBackward). Vertical steps: the columns advance together, as many in
// the lanes of a vector as the target has; each lane computes what raster_span / raster_point compute for its column,
// operation by operation in float (no contraction: the file is compiled with -ffp-contract=off, and SSE4 has no FMA
// anyway), and the colour with lerp8's integer formula (on AVX-512 by VNNI dot
// products); each column keeps floor and ceil of its last sample's v - 0.5 (ColumnStep), so a step rounds its new
// samples only. Where the pixels go (warp/simd/hwy_columns-inl.h): two masked row stores a step where the lanes share a
// row or the next (AVX-512, AVX2, SVE), otherwise one scatter (AVX-512) or lane by lane; spans of 5 pixels and more row
// by row over the lanes. Still steps (zero displacement) are copied by the shared scheduling, tested by StillSteps a
// vector at a time. Surface discontinuities (paper section 4.1.1; TwoPassJob::breaks, threshold): a row's marks end its
// groups of spans and make the sample after a marked pair a point (WarpRow), marked rows go forwards; with a threshold
// the rows carry each texel's displacement as a second attribute (RowOut::attr2) and ColumnStep<true> joins two samples
// of a column only where their displacements differ by at most the threshold.
//
// The building blocks (row set-up, row warp, column step) are shared with the Highway pipelined kernel
// (warp/simd/hwy_row-inl.h, warp/simd/hwy_columns-inl.h, warp/simd/hwy_pipelined.h). Not here (docs/BENCHMARKS.md,
// "SIMD targets"): the hand-written AVX-512 kernels' span search over sub-runs of any length (here a group ends after
// a vector of spans) and their set-up of each row's spans once per row.
#pragma once

#include <cstddef>
#include <cstdint>

#include "warp/isa.h"
#include "warp/simd/two_pass_job.h"

namespace rtm::simd {

// The horizontal pass of steps [s0, s1) into one band; `scratch` holds 3 * source width floats (4 with a
// discontinuity threshold, TwoPassJob::threshold) that no other call uses at the same time (one per band slot: the
// kernels then allocate nothing, whichever thread runs them). Returns the steps whose rows may hold still pixels (bit
// i: step s0 + i's row has a texel at zero displacement and TwoPassJob::copy_still is on), the only ones the
// vertical pass tests for still steps.
using HorizontalStepsFn = uint32_t (*)(const fast::TwoPassJob&, int, int, uint32_t*, float*, size_t, float* scratch);
using VerticalStepsFn = void (*)(const fast::TwoPassJob&, int, int, const uint32_t*, const float*, size_t, int, int);
// The still-step test of the vertical pass (warp/simd/schedule.cpp, vertical_with_still): bit i set where step
// s0 + i is one of `steps` (bit i likewise) and holds in every column of [gx0, gx0 + width) (width <= 16) a written
// pixel (alpha 255) on the centre of its own output line (v == fast::step_line + 0.5). Band rows are read a whole
// vector past gx0 + width.
using StillStepsFn = uint32_t (*)(const fast::TwoPassJob&, int s0, int s1, uint32_t steps, const uint32_t* band_c,
                                  const float* band_v, size_t stride, int gx0, int width);

struct TwoPassKernels {
    HorizontalStepsFn horizontal = nullptr;
    VerticalStepsFn vertical = nullptr;
    StillStepsFn still = nullptr;
};

// The Highway kernels compiled for `isa` (avx512, avx2, sse4, neon, sve); null pointers for any other target or one
// this build did not compile.
TwoPassKernels hwy_two_pass_kernels(Isa isa);

// The Highway targets this file was compiled for (HWY_TARGETS).
int64_t hwy_compiled_targets();

}  // namespace rtm::simd
