// Measures each skip of ReliefQuad::draw: frame time with the skip against the same frames with skips off
// (--no-skips), and the error each adds against the micro-polygon truth. Used by `rtm bench-skips`; the table
// goes to docs/BENCHMARKS.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "warp/prewarp.h"

namespace rtm {

struct SkipMeasurement {
    std::string skip, scenario;
    double ms_with = 0, ms_without = 0;      // median frame time (pre-warp + upload + texture mapping)
    double work_with = 0, work_without = 0;  // median pre-warp + upload time: the work the skips target
    double psnr_with = 0, psnr_without = 0;  // against micromesh, last frame
    double iou_with = 0, iou_without = 0;
    bool fired = false;         // the skip fired in the measured frames
    bool same_picture = false;  // the last frame with skips is the one without, pixel for pixel
};

// Runs every scenario (a few seconds). `progress` gets one line per scenario; may be empty.
std::vector<SkipMeasurement> measure_skips(int frames, const std::function<void(const std::string&)>& progress);

std::string skip_table_markdown(const std::vector<SkipMeasurement>& rows);

// The paper's brick wall (section 5, Figure 21) on the fast kernels: the pre-warp of the brick wall (bricks at zero
// displacement, mortar recessed) against the same wall lifted off zero (every displacement + 0.05, so no texel is
// still) and sunk by 0.05 (the same motion towards the epipole as the bricks' mortar, nothing still), one view
// (orbit azimuth 30, elevation 20, the view of `rtm bench`), PrewarpOptions' defaults but the method and threads.
struct StillWallMeasurement {
    Reconstruction method = Reconstruction::two_pass;
    int threads = 1;
    std::string isa;  // the target whose kernels ran
    int size = 0;
    double still_fraction = 0;  // the brick wall's texels at zero displacement
    // Median ms of interleaved rounds: the wall, the wall with copy_still_runs off, lifted, sunk; wall clock and
    // CPU time (the thread's with 1 thread, the process's with more: on a loaded machine the wall clock also counts
    // the time other processes had the core).
    double ms_bricks = 0, ms_bricks_no_copy = 0, ms_lifted = 0, ms_sunk = 0;
    double cpu_bricks = 0, cpu_bricks_no_copy = 0, cpu_lifted = 0, cpu_sunk = 0;
    // What the split into a warp of the moving texels and a copy of the still ones could reach: the wall with its
    // still texels emptied (the kernels' warp of the moving texels alone) and a plain copy of the still texels to
    // their own output pixels (what copying them "at memory speed" costs), same medians.
    double ms_moving = 0, ms_still_copy = 0, cpu_moving = 0, cpu_still_copy = 0;
    int rounds = 0;
    // The brick wall's picture is the reference kernels' (generic target) bit for bit, with the copy and without.
    bool same_as_reference = false;
};

// Runs the rounds for two-pass and pipelined at 1 and 2 threads, on the automatic target and, where this CPU has
// it, avx2 (when the automatic target is another); a few seconds at 1024^2.
std::vector<StillWallMeasurement> measure_still_wall(int size, int rounds,
                                                     const std::function<void(const std::string&)>& progress);

std::string still_wall_markdown(const std::vector<StillWallMeasurement>& rows);

}  // namespace rtm
