// Measures each skip of ReliefQuad::draw: frame time with the skip against the same frames with skips off
// (--no-skips), and the error each adds against the micro-polygon truth. Used by `rtm bench-skips`; the table
// goes to docs/BENCHMARKS.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

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

}  // namespace rtm
