// The fast pre-warp: prewarp() (warp/prewarp.h) hands the cases below to kernels written for speed, whose
// output is bit-identical to the generic implementation's (tests/warp/fast_kernels_test.cpp compares them pixel by
// pixel over random reliefs, views, sizes and thread counts).
//
// Covered: the lookup-table path (not --exact) with the point filter, without depth output (displ_out), margins
// (keep_outliers) or not, reliefs with surface-discontinuity marks or a threshold (paper section 4.1.1) or without,
// both reconstructions, on every SIMD target (avx512, avx2, sse4, neon, sve: the kernels written once over Google
// Highway, warp/simd/hwy_two_pass.h and warp/simd/hwy_pipelined.h). Everything else stays with the generic
// implementation, which remains the reference.
//
// Still texels (PrewarpOptions::copy_still_runs): the row warps copy runs of spans one pixel wide on pixel centres
// (what zero displacement gives: a vector's worth at a time, CopyStill) instead of interpolating them; with the option
// off they interpolate them too, so that the copy can be measured. The two-pass vertical pass copies blocks of still
// pixels, 16 columns by consecutive rows (schedule.cpp, vertical_with_still); the pipelined kernel copies a vector of
// columns whose column spans are still steps (one pixel on a centre, t = 1: StillStep in
// warp/simd/hwy_columns-inl.h), forwards and in reverse mode. The row set-ups skip the table lookups of a vector of
// still texels whatever the option (FastTables' identity levels, warp/simd/fast_tables.h). The output is the same
// either way. The copies are not counted (PrewarpStats::still_copied stays 0 here; tests/objects/skips_test.cpp
// relies on that).
//
// Scheduling lives here, kernels in warp/simd/hwy_two_pass.cpp and warp/simd/hwy_pipelined.cpp: a kernel takes a
// range of rows or columns and every output pixel is computed by exactly one call, or (the pipelined kernel's row
// chunks) by the chunks whose rows reach it, the last of them in the painter's order winning in the composite, so the
// output does not depend on the number of threads. Steady state allocates nothing: intermediate and scratch images live
// in the PrewarpWorkspace, per-thread line buffers in thread-local storage that only grows, and the task arenas for
// explicit thread counts are created once per count.
#pragma once

#include <vector>

#include "warp/image.h"
#include "warp/isa.h"
#include "warp/prewarp.h"
#include "warp/prewarp_coefficients.h"
#include "warp/relief_texture.h"

namespace rtm {

// True when the kernels of target `isa` (supported by this CPU: resolve_isa, warp/isa.h) compute this pre-warp
// (see the top of this file). `extent` is the output's margins.
bool fast_prewarp_covers(Isa isa, const ReliefTexture& relief, const PrewarpCoefficients& k,
                         const PrewarpOptions& options, const PrewarpExtent& extent, const Image2D<uint8_t>* displ_out);

// The pre-warp of prewarp() for a case `isa` covers; `out` is resized to the relief plus the margins.
PrewarpStats fast_prewarp(Isa isa, const ReliefTexture& relief, const PrewarpCoefficients& k,
                          const PrewarpOptions& options, const PrewarpExtent& extent, PrewarpWorkspace& workspace,
                          ImageRGBA8& out);

// Asks the CPU to bring storage row r of the relief into the cache (nothing where r is not a row of it): each kernel
// calls it for the row it sets up next, a row ahead. The hardware prefetchers did not keep up with the row set-ups'
// reads of the texels: the hand-written AVX-512 two-pass kernels (since retired) took 3.4-3.8 ms for the brick wall
// 1024^2 (one thread) without, 2.6-2.7 with (docs/perf-history.md, "Prefetching the next row").
void prefetch_relief_row(const ReliefTexture& relief, int r);

// The pipelined kernel's row chunks (warp/simd/schedule.cpp): `bounds` (n + 1 increasing rows, 0 first, the part's
// row count last) of n chunks that took ms[0 .. n) are moved half-way towards the bounds that would give every
// chunk the same time, each chunk's time spread evenly over its rows; every chunk keeps at least one row. Times
// that are not all finite and positive, or more than 64 chunks (the kernel's most), leave the bounds as they are.
void balance_row_chunks(std::vector<int>& bounds, const double* ms);

}  // namespace rtm
