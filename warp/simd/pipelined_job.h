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
#include <memory>
#include <vector>

#include "warp/simd/fast_tables.h"
#include "warp/simd/kernel_policy.h"
#include "warp/image.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm::fast {

// Reverse mode's buffers of one task (warp/simd/hwy_pipelined.cpp, RunRows), the same for every target: they grow to
// the largest output seen and never shrink (steady state allocates nothing). The emissions of a row are logged in the
// order of the row warp, a vector of adjacent columns an entry (x, then N row coordinates, NaN where the lane received
// nothing, N packed colours and, with a discontinuity threshold, N displacements; N the target's lanes).
struct EmitLog {
    std::vector<int32_t> x;
    std::vector<float> v, d;
    std::vector<uint32_t> c;
    size_t n = 0;  // entries
};

struct ReverseBuffers {
    // The final samples of the row warped last (fin_ok: -1 where the column has one), and the rows written per column
    // (ColumnsWritten).
    std::vector<float> fin_v, fin_d;
    std::vector<uint32_t> fin_c;
    std::vector<int32_t> fin_ok, lo, hi, bits_on;
    std::vector<uint64_t> bits;
    int nw = 0;
    EmitLog log[2];

    void reserve(int ow, int oh) {
        // Padded as the task buffers are (a whole vector of up to 64 lanes past the width), rounded up to 64 columns.
        const size_t n = (size_t(ow) + 63) / 64 * 64 + 64;
        auto grow = [&](auto& vec, size_t want) {
            if (vec.size() < want) vec.resize(want);
        };
        grow(fin_v, n), grow(fin_d, n), grow(fin_c, n), grow(fin_ok, n), grow(lo, n), grow(hi, n), grow(bits_on, n);
        nw = (oh + 63) / 64;
        grow(bits, n * size_t(nw));
    }
};

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
    // The Highway kernel's buffers, indexed by the task (a part's column range or row chunk: its index in the
    // pre-warp's tasks): PrewarpWorkspace::task_buffers and reverse_buffers (at least 2 * 64 of each).
    std::vector<std::vector<float>>* task_buffers = nullptr;
    std::vector<std::shared_ptr<ReverseBuffers>>* reverse_buffers = nullptr;
};

// Rows [r0, r1) of part `part` (0: the part's first row in its order), all columns. The chunk with r0 == 0 draws
// into job.out (clearing the part's output rows first); any other draws into `scratch`, an image of the output's
// size that is 0 everywhere, and records the output v-rows it may have written in [ylo, yhi) (pixels written there
// have alpha 255: the kernels write only Lerp8 colours and points with alpha set). Only the chunk with r1 equal to
// the part's row count records the seam.
struct PipelinedChunk {
    int task = 0;  // the chunk's index among the pre-warp's (PipelinedJob::task_buffers)
    int part = 0, r0 = 0, r1 = 0;
    ImageRGBA8* scratch = nullptr;
    int ylo = 0, yhi = 0;
};

}  // namespace rtm::fast

namespace rtm::simd {

// The entry points of one target's pipelined kernel (warp/simd/hwy_pipelined.h):
// - part(job, task, part, x0, x1): task `task` (its index among the pre-warp's: PipelinedJob::task_buffers), part 0
//   (rows from the bottom up to the split, output v-rows [0, ysplit)) or 1 (rows from the top down to the split,
//   output v-rows [ysplit, out height)), output columns [x0, x1): clears that region, then fills it.
// - chunk(job, chunk): a PipelinedChunk.
// - composite(job, chunks, n, y0, y1): output v-rows [y0, y1): the pixels the scratch chunks wrote (alpha not 0)
//   replace the output's, chunk after chunk in the order given (the parts' row order), and the scratch rows are
//   cleared to 0 again.
// - seam(job): the span between the last rows of the two parts, in every column where both have a sample.
struct PipelinedKernels {
    void (*part)(const fast::PipelinedJob&, int, int, int, int) = nullptr;
    void (*chunk)(const fast::PipelinedJob&, fast::PipelinedChunk&) = nullptr;
    void (*composite)(const fast::PipelinedJob&, const fast::PipelinedChunk*, int, int, int) = nullptr;
    void (*seam)(const fast::PipelinedJob&) = nullptr;
};

}  // namespace rtm::simd
