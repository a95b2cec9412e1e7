// The pipelined pre-warp kernel (paper section 3.2.2) written once over Google Highway, for the same targets as the
// Highway two-pass kernels (warp/simd/hwy_two_pass.h: avx2, sse4, neon, sve), chosen at run time (warp/isa.h). Same
// contract as the hand-written AVX-512 kernel (warp/simd/avx512_pipelined.h: the entry points of
// simd::PipelinedKernels, the job, its parts, row chunks, column ranges and seam) and the same scheduling
// (warp/simd/schedule.cpp): the output of prewarp()'s pipelined lookup-table path bit for bit.
//
// Each row of a part is set up and warped horizontally as in the two-pass kernels (warp/simd/hwy_row-inl.h:
// PrepareRow, WarpRow) into a row of pixels, and every column that received one pixel from the row steps at once,
// the columns in the lanes of vectors (ColumnStep, drawing only the part's output rows). A column that received
// more than one pixel from the row (a foldover along the row) draws every one of them in the row warp's order, each
// from the column's last sample of the previous row, as the reference does: the row is warped a second time and
// those columns' pixels are drawn one by one (raster_span / raster_point). No reverse mode
// (FastKernelPolicy::pipelined_reverse is the AVX-512 kernel's).
#pragma once

#include "warp/isa.h"
#include "warp/simd/avx512_pipelined.h"

namespace rtm::simd {

// The Highway pipelined kernel compiled for `isa` (avx2, sse4, neon, sve); null pointers for any other target or one
// this build did not compile. The job's ref_tables must be set.
PipelinedKernels hwy_pipelined_kernels(Isa isa);

}  // namespace rtm::simd
