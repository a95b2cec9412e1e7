// The job of the fast pipelined pre-warp kernel (warp/simd/hwy_pipelined.h; paper section 3.2.2) and its entry
// points as a set (PipelinedKernels), which warp/simd/schedule.cpp schedules.
//
// A part (the rows below the epipole, bottom up, or the rows above it, top down) is processed row by row: each row
// is prepared and warped into a row buffer, and every group of pixels the row warp reports is rasterized at once into
// its columns, as many columns at a time as the target has lanes, each connected to the last sample its column
// received from the previous row. A part can be split into column ranges that run on different threads: each range
// warps every row (the horizontal work is repeated) and rasterizes only its own columns. Or into chunks of
// consecutive rows: the column state carried from row to row is only the previous row's last emission per column,
// so a chunk starts exactly by warping the row before it without drawing; the part's first chunk draws into the
// output, every other one into a scratch image of its own, and the scratch images are composited over the output in
// row order (the painter's order: a later row's pixels replace an earlier row's).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "warp/simd/fast_tables.h"
#include "warp/simd/kernel_policy.h"
#include "warp/image.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm::fast {

struct PipelinedJob {
    const ReliefTexture* relief = nullptr;
    const FastTables* tables = nullptr;
    PrewarpExtent extent;
    int split_u = 0, split_v = 0;  // split_index of the epipole along rows and columns (source)
    int ysplit = 0;                // split of the output rows between the parts (v order)
    ImageRGBA8* out = nullptr;
    // The last sample each column received in each part (part 0: bottom, 1: top), for the seam between the parts:
    // final row coordinate and colour, alpha 0 where the column received nothing. Out width entries each.
    float* seam_v[2] = {nullptr, nullptr};
    uint32_t* seam_c[2] = {nullptr, nullptr};
    bool copy_still = true;                          // PrewarpOptions::copy_still_runs
    KernelChoice reverse = KernelChoice::automatic;  // FastKernelPolicy::pipelined_reverse
    bool blend_stores = false;                       // FastKernelPolicy::avx2_blend_stores, resolved (avx2 only)
    std::atomic<long long>* dropped = nullptr;
    // Surface discontinuities (paper section 4.1.1; the Highway kernel only, fast_prewarp_covers): the relief's
    // per-texel marks (kBreakRight: no span to the texel on the right; null when it has none) and the threshold on
    // the displacement each column carries (0: none). With a threshold the rows carry each texel's displacement
    // (ref_tables->displ) beside the row coordinate, a column joins its last sample to a new one only where the two
    // differ by at most the threshold (the reference's column_connected), and seam_d keeps each part's last.
    const uint8_t* breaks = nullptr;
    float threshold = 0.0f;
    const PrewarpTables* ref_tables = nullptr;
    float* seam_d[2] = {nullptr, nullptr};
    // The Highway kernel's buffers: each task takes the next of them (next_task counts the tasks of the pre-warp).
    std::vector<std::vector<float>>* task_buffers = nullptr;
    std::atomic<int>* next_task = nullptr;
};

// Rows [r0, r1) of part `part` (0: the part's first row in its order), all columns. The chunk with r0 == 0 draws
// into job.out (clearing the part's output rows first); any other draws into `scratch`, an image of the output's
// size that is 0 everywhere, and records the output v-rows it may have written in [ylo, yhi) (pixels written there
// have alpha 255: the kernels write only Lerp8 colours and points with alpha set). Only the chunk with r1 equal to
// the part's row count records the seam.
struct PipelinedChunk {
    int part = 0, r0 = 0, r1 = 0;
    ImageRGBA8* scratch = nullptr;
    int ylo = 0, yhi = 0;
};

}  // namespace rtm::fast

namespace rtm::simd {

// The entry points of one target's pipelined kernel (warp/simd/hwy_pipelined.h):
// part(job, part, x0, x1): part 0 (rows from the bottom up to the split, output v-rows [0, ysplit)) or 1 (rows from
// the top down to the split, output v-rows [ysplit, out height)), output columns [x0, x1): clears that region, then
// fills it.
// chunk(job, chunk): a PipelinedChunk.
// composite(job, chunks, n, y0, y1): output v-rows [y0, y1): the pixels the scratch chunks wrote (alpha not 0)
// replace the output's, chunk after chunk in the order given (the parts' row order), and the scratch rows are cleared
// to 0 again.
// seam(job): the span between the last rows of the two parts, in every column where both have a sample.
struct PipelinedKernels {
    void (*part)(const fast::PipelinedJob&, int, int, int) = nullptr;
    void (*chunk)(const fast::PipelinedJob&, fast::PipelinedChunk&) = nullptr;
    void (*composite)(const fast::PipelinedJob&, const fast::PipelinedChunk*, int, int, int) = nullptr;
    void (*seam)(const fast::PipelinedJob&) = nullptr;
};

}  // namespace rtm::simd
