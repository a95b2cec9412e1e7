#include "objects/quad_frame.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <numeric>

#include "warp/task_arenas.h"
#include "warp/timing.h"

namespace rtm {

PrewarpSchedule schedule_prewarps(const std::vector<long long>& texels, int threads, bool concurrent) {
    PrewarpSchedule s;
    for (size_t i = 0; i < texels.size(); ++i)
        if (texels[i] > 0) s.order.push_back(i);
    // Largest first; equal sizes in the quads' order (the order changes no pixel, only the balance).
    std::stable_sort(s.order.begin(), s.order.end(), [&](size_t a, size_t b) { return texels[a] > texels[b]; });
    s.threads = std::max(1, threads);
    s.over_quads = concurrent && s.order.size() > 1 && int(s.order.size()) >= s.threads;
    return s;
}

void draw_quad_frame(std::vector<ReliefQuad>& quads, Renderer& renderer, const Camera& cam, RenderMethod method,
                     const PrewarpOptions& options, const DrawOptions& draw, const QuadFrameOptions& fo,
                     std::vector<DrawReport>& reports, std::vector<StageTimes>& quad_times, StageTimes& frame) {
    const auto t_frame = Clock::now();
    const size_t n = quads.size();
    reports.assign(n, {});
    quad_times.assign(n, {});

    // 1. Plans (serial: a plan may build the pyramid level it needs).
    DrawOptions fitted = draw;
    fitted.max_texture_size = renderer.max_texture_size();
    std::vector<FramePlan> plans(n);
    std::vector<long long> texels(n, 0);
    for (size_t i = 0; i < n; ++i) {
        const auto t0 = Clock::now();
        plans[i] = quads[i].plan_draw(cam, method, options, fitted);
        reports[i].level = plans[i].level;
        reports[i].skips = plans[i].skips;
        if (plans[i].action == FrameAction::prewarp) {
            const ReliefTexture& t = quads[i].level(plans[i].level);
            texels[i] = std::max(1ll, (long long)t.width * t.height);
        }
        quad_times[i].total_ms += ms_since(t0);
    }

    // 2. Pre-warps: each touches only its own quad.
    const auto t_warp = Clock::now();
    const int threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
    const PrewarpSchedule s = schedule_prewarps(texels, threads, fo.concurrent);
    auto warp_one = [&](size_t i, int warp_threads) {
        const auto t0 = Clock::now();
        FramePlan p = plans[i];
        p.prewarp.threads = warp_threads;  // the output does not depend on it (warp/prewarp.h)
        quads[i].prewarp_planned(p, draw, quad_times[i], reports[i]);
        quad_times[i].total_ms += ms_since(t0);
    };
    if (s.over_quads) {
        auto loop = [&] {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, s.order.size(), 1),
                              [&](const tbb::blocked_range<size_t>& r) {
                                  for (size_t j = r.begin(); j != r.end(); ++j) warp_one(s.order[j], 1);
                              });
        };
        if (options.threads > 0) {
            task_arena_for(options.threads).execute(loop);
        } else {
            loop();
        }
    } else {
        for (size_t i : s.order) warp_one(i, options.threads);
    }
    frame.prewarp_ms += ms_since(t_warp);

    // 3. Uploads and draws, in the quads' order (the order they share the depth buffer in).
    for (size_t i = 0; i < n; ++i) {
        const auto t0 = Clock::now();
        quads[i].present(renderer, cam, plans[i], draw, quad_times[i], reports[i], fo.finish_each);
        quad_times[i].total_ms += ms_since(t0);
        frame.upload_ms += quad_times[i].upload_ms;
        frame.texture_map_ms += quad_times[i].texture_map_ms;
    }
    const auto t_finish = Clock::now();
    renderer.finish();
    frame.texture_map_ms += ms_since(t_finish);
    frame.total_ms += ms_since(t_frame);
}

}  // namespace rtm
