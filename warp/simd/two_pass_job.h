// The job of the fast two-pass pre-warp kernels (warp/simd/hwy_two_pass.h): what one pre-warp hands to the horizontal
// and vertical steps that warp/simd/schedule.cpp schedules (threads, bands of rows), and the order of the steps.
//
// The two passes are interleaved row by row instead of going through a whole intermediate image. The reference's
// vertical pass warps each column of the intermediate image in occlusion-compatible order: the bottom part from
// the bottom row up to the epipole's row, then the top part from the top row down to it, then the span across the
// epipole. Columns are independent, so all of them can advance together, one intermediate row at a time, if the
// rows are produced in that order: "step" s = 0, 1, ... h - 1 is intermediate row j = s (v order, 0 = bottom) for
// s < split_v, then j = h - 1 - (s - split_v). A band of steps is warped horizontally (rows independent: any order,
// any thread), then handed to the vertical step, which keeps per column the last sample it received and rasterizes
// the span from it to the new one, as many columns at a time as the target has lanes. Bands must reach the vertical
// step in step order; different column ranges may run concurrently.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "warp/simd/fast_tables.h"
#include "warp/simd/kernel_policy.h"
#include "warp/image.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm::fast {

struct TwoPassJob {
    const ReliefTexture* relief = nullptr;
    const FastTables* tables = nullptr;
    const PrewarpTables* ref_tables = nullptr;  // the reference's tables (displ: marked rows' displacements)
    PrewarpExtent extent;
    int split_u = 0, split_v = 0;  // split_index of the epipole along rows and columns (source)
    ImageRGBA8* out = nullptr;     // out width x out height
    // Per output column (out width entries, rounded up to 16; 64-byte aligned): the last sample the column
    // received (final row coordinate, NaN where the column has none, and colour); and the last sample of the bottom
    // part (colour alpha 0 where none), for the span across the epipole.
    float* col_v = nullptr;
    uint32_t* col_c = nullptr;
    float* seam_v = nullptr;
    uint32_t* seam_c = nullptr;
    // Surface discontinuities (paper section 4.1.1; the two-pass kernels, fast_prewarp_covers): the relief's
    // per-texel marks (kBreakRight: no span to the texel on the right; null when it has none), and the threshold
    // on the displacement carried into the columns (0: none). With a threshold the horizontal pass also carries
    // each pixel's interpolated displacement d into band rows `d_offset` floats after the v rows, the column state
    // keeps the last sample's d in col_d (seam_d for the bottom part's last), and two samples of a column are
    // connected only when |d_a - d_b| <= threshold, as the reference's DisplConnected.
    const uint8_t* breaks = nullptr;
    float threshold = 0.0f;
    std::ptrdiff_t d_offset = 0;
    float* col_d = nullptr;
    float* seam_d = nullptr;
    bool copy_still = true;                          // PrewarpOptions::copy_still_runs
    KernelChoice reverse = KernelChoice::automatic;  // FastKernelPolicy::two_pass_reverse
    bool redo_forwards = false;                      // FastKernelPolicy::two_pass_redo_forwards
    bool blend_stores = false;                       // FastKernelPolicy::avx2_blend_stores, resolved (avx2 only)
    std::atomic<long long>* dropped = nullptr;
};

// Source storage row of step s.
inline int step_row(const TwoPassJob& job, int s) {
    const int h = job.relief->height;
    return s < job.split_v ? h - 1 - s : s - job.split_v;
}

// Output v-line of step s (the intermediate row's own line: where the row's still texels land).
inline int step_line(const TwoPassJob& job, int s) {
    const int j = s < job.split_v ? s : job.relief->height - 1 - (s - job.split_v);
    return j + job.extent.bottom;
}

}  // namespace rtm::fast
