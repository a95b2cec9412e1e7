#include "viewer/frame_stats.h"

#include <algorithm>

#include "warp/timing.h"

namespace rtm::viewer {

double FrameSample::other_ms() const {
    return std::max(0.0, frame_ms - stages.prewarp_ms - stages.upload_ms - stages.texture_map_ms);
}

void FrameStats::add(const FrameSample& s) {
    add(s, std::chrono::duration<double>(Clock::now().time_since_epoch()).count());
}

void FrameStats::add(const FrameSample& s, double now_s) {
    samples_.push_back(s);
    while (samples_.size() > window_) samples_.pop_front();
    ends_.push_back(now_s);
    while (!ends_.empty() && ends_.front() < now_s - 1.0) ends_.pop_front();
    const double span = ends_.size() > 1 ? ends_.back() - ends_.front() : 0.0;
    fps_ = span > 0 ? double(ends_.size() - 1) / span : 0.0;
}

FrameSample FrameStats::mean() const {
    FrameSample m;
    if (samples_.empty()) return m;
    for (const FrameSample& s : samples_) {
        m.frame_ms += s.frame_ms;
        m.stages.prewarp_ms += s.stages.prewarp_ms;
        m.stages.upload_ms += s.stages.upload_ms;
        m.stages.texture_map_ms += s.stages.texture_map_ms;
        m.texels_warped += s.texels_warped;
    }
    const double n = double(samples_.size());
    m.frame_ms /= n;
    m.stages.prewarp_ms /= n;
    m.stages.upload_ms /= n;
    m.stages.texture_map_ms /= n;
    m.texels_warped = (long long)(double(m.texels_warped) / n + 0.5);
    return m;
}

std::vector<float> FrameStats::series(int which) const {
    std::vector<float> v;
    v.reserve(samples_.size());
    for (const FrameSample& s : samples_) {
        double x = 0;
        switch (which) {
            case 0: x = s.frame_ms; break;
            case 1: x = s.stages.prewarp_ms; break;
            case 2: x = s.stages.upload_ms; break;
            case 3: x = s.stages.texture_map_ms; break;
            default: x = s.other_ms(); break;
        }
        v.push_back(float(x));
    }
    return v;
}

}  // namespace rtm::viewer
