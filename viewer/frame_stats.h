// Frame times of the viewer, split as the paper's Table 1 (pre-warp, upload, texture mapping, other = the rest of
// the frame: overlays, panel, swap), over a rolling window of frames, and frames per second over the last second.
#pragma once

#include <deque>
#include <vector>

#include "objects/relief_quad.h"

namespace rtm::viewer {

struct FrameSample {
    double frame_ms = 0;  // wall time of the whole frame
    StageTimes stages;
    long long texels_warped = 0;
    double other_ms() const;  // frame_ms less the three stages, never negative
};

class FrameStats {
public:
    explicit FrameStats(size_t window = 240) : window_(window) {}
    void add(const FrameSample& s);  // `s` ended at `now_s` seconds (monotonic)
    void add(const FrameSample& s, double now_s);
    const std::deque<FrameSample>& samples() const { return samples_; }
    double fps() const { return fps_; }
    FrameSample mean() const;                    // over the window
    std::vector<float> series(int which) const;  // 0 frame, 1 pre-warp, 2 upload, 3 texture mapping, 4 other (ms)

private:
    size_t window_;
    std::deque<FrameSample> samples_;
    std::deque<double> ends_;  // end times of the frames of the last second
    double fps_ = 0;
};

}  // namespace rtm::viewer
