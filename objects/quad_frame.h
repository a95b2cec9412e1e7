// One frame of many relief quads (a scene's): every quad's plan first (objects/frame_plan.h, pure), then the
// pre-warps those plans ask for, concurrently over quads (oneTBB) when there are at least as many as threads, then
// the uploads and draws in the quads' order with one finish for the whole frame instead of one per quad. Each quad's
// pre-warp touches only that quad and its output does not depend on the threads that ran it, so the frame is
// bit-identical to drawing the quads one by one with ReliefQuad::draw.
#pragma once

#include <cstddef>
#include <vector>

#include "objects/frame_plan.h"
#include "objects/relief_quad.h"
#include "texmap/camera.h"
#include "texmap/renderer.h"

namespace rtm {

struct QuadFrameOptions {
    // Pre-warp concurrently over quads when the schedule says so (schedule_prewarps); false: one quad after another,
    // each pre-warp with all of options.threads (the serial reference).
    bool concurrent = true;
    // A finish after each quad's upload and after its draw, so each quad's stage times are its own (as
    // ReliefQuad::draw measures them); the frame then costs a rasterizer pass per quad. Off: one finish per frame.
    bool finish_each = false;
};

// How a frame's pre-warps run: in `order` (largest first, so the longest task does not start last), either
// concurrently over quads with each quad's warp single-threaded, or one after another with `threads` each.
struct PrewarpSchedule {
    std::vector<size_t> order;  // indices of the quads to pre-warp
    bool over_quads = false;
    int threads = 1;  // the threads the step may use
};

// `texels[i]`: the size of the level quad i pre-warps (0 for quads that do not pre-warp this frame). `threads`: the
// threads available (> 0). Over quads when `concurrent`, more than one quad pre-warps and there are at least as many
// of them as threads.
PrewarpSchedule schedule_prewarps(const std::vector<long long>& texels, int threads, bool concurrent);

// One frame of `quads` into the current frame (begin_frame done by the caller). `reports[i]` and `quad_times[i]`
// receive quad i's report and its stage times (with finish_each, exactly as ReliefQuad::draw measures them; else
// prewarp_ms is the quad's own warp, upload_ms and texture_map_ms what issuing its calls took). `frame` receives
// the frame's stage times: prewarp_ms the wall time of the pre-warp step (not the sum over quads), upload_ms the
// sum of the uploads, texture_map_ms the draws plus the frame's finish, total_ms all of it.
void draw_quad_frame(std::vector<ReliefQuad>& quads, Renderer& renderer, const Camera& cam, RenderMethod method,
                     const PrewarpOptions& options, const DrawOptions& draw, const QuadFrameOptions& frame_options,
                     std::vector<DrawReport>& reports, std::vector<StageTimes>& quad_times, StageTimes& frame);

}  // namespace rtm
