// The pipelined pre-warp kernel (paper section 3.2.2) written once over Google Highway, for the same targets as the
// Highway two-pass kernels (warp/simd/hwy_two_pass.h: avx512, avx2, sse4, neon, sve), chosen at run time
// (warp/isa.h). The entry points of simd::PipelinedKernels for the job of warp/simd/pipelined_job.h (its parts, row
// chunks, column ranges and seam), scheduled by warp/simd/schedule.cpp: the output of prewarp()'s pipelined
// lookup-table path bit for bit.
//
// Each row of a part is set up and warped horizontally as in the two-pass kernels (warp/simd/hwy_row-inl.h:
// PrepareRow, WarpRow) into a row of pixels, and the pixels reach the columns group by group in the row warp's order,
// as the reference's put() does, each drawn from the column's sample of the previous row (raster_span along the
// column, or raster_point), the columns in the lanes of vectors (ColumnDraw, warp/simd/hwy_columns-inl.h, drawing
// only the part's output rows). Groups are handed over in runs: a group that extends the pending run joins it, any
// other (apart from it, or writing over its pixels: a foldover along the row) hands the pending run over first, so a
// row without foldovers is one run and a column that receives several pixels from a row (a foldover) draws every
// one of them, in order. Reverse mode (FastKernelPolicy::pipelined_reverse): where rows
// overdraw much (foldover-heavy reliefs: long column spans that later rows overwrite), the rest of the part runs
// with the painter's algorithm backwards, each row's emissions logged and replayed from the last, every pixel
// written once (RunRows, ColumnDrawRev in warp/simd/hwy_columns-inl.h). Runs of one or two pixels (rows that marks
// or foldovers cut into pieces) go column by column through the reference's raster_span and raster_point.
//
// Surface discontinuities (paper section 4.1.1; PipelinedJob::breaks, threshold): a row's
// marks break its spans in WarpRow; with a threshold the rows carry each texel's displacement (RowOut::attr2), and a
// column joins its sample of the previous row to a new one only where the two displacements differ by at most the
// threshold, forwards (the Emitter) and in reverse mode (the log carries the displacements); the seam likewise.
#pragma once

#include "warp/isa.h"
#include "warp/simd/pipelined_job.h"

namespace rtm::simd {

// The Highway pipelined kernel compiled for `isa` (avx512, avx2, sse4, neon, sve); null pointers for any other target
// or one this build did not compile. The job's tables must be set.
PipelinedKernels hwy_pipelined_kernels(Isa isa);

}  // namespace rtm::simd
