#include "measure/skip_measure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "objects/bounds.h"
#include "measure/compare.h"
#include "warp/timing.h"
#include "measure/image_diff.h"
#include "procedural/procedural_media.h"
#include "objects/render_relief.h"
#include "texmap/gl_context.h"

namespace rtm {

namespace {

// An n x n wall at zero displacement with one raised block in a corner: only a small part of the pre-warped
// texture changes when the eye moves (the partial-upload case).
ReliefTexture corner_block(int n) {
    ProceduralRelief p = make_bumps(n);
    for (int r = 0; r < n; ++r)
        for (int x = 0; x < n; ++x) {
            const bool block = x >= n * 20 / 256 && x < n * 60 / 256 && r >= n * 20 / 256 && r < n * 60 / 256;
            p.displacement.at(x, r) = block ? 1.0f : 0.0f;
        }
    return to_relief(p);
}

struct Scenario {
    std::string skip, scenario;
    ReliefTexture relief;
    // Camera for frame i of n (the eye may move between frames).
    std::function<Camera(const ReliefQuad&, int, int)> camera;
    int level = 0;
    bool fast = true;       // PrewarpOptions::fast: false measures the reference kernels (the paper's scalar code)
    bool sidewalls = true;  // PrewarpOptions::keep_outliers (side polygons)
    int threads = 0;        // PrewarpOptions::threads (0 = all)
};

Camera orbit(const ReliefQuad& q, double az, double el, double d) {
    return compare_camera(q, {"s", az, el, d}, 512, 512);
}

}  // namespace

std::vector<SkipMeasurement> measure_skips(int frames, const std::function<void(const std::string&)>& progress) {
    std::vector<Scenario> sc;
    sc.push_back({"back-facing", "bumps seen from behind", to_relief(make_bumps(256)),
                  [](const ReliefQuad& q, int, int) { return orbit(q, 160, 10, 2.2); }});
    sc.push_back({"outside-frustum", "bumps behind the camera", to_relief(make_bumps(256)),
                  [](const ReliefQuad& q, int, int) {
                      Camera c = orbit(q, 20, 10, 2.2);
                      c.look_at = c.eye + (c.eye - c.look_at);
                      return c;
                  }});
    sc.push_back({"subpixel-parallax", "bumps 600 radii away", to_relief(make_bumps(256)),
                  [](const ReliefQuad& q, int, int) { return orbit(q, 30, 20, 600); }});
    sc.push_back({"reuse-prewarp", "facade, eye drifting 1e-5 radii per frame", to_relief(make_facade(256)),
                  [](const ReliefQuad& q, int i, int) { return orbit(q, 30 + 1e-4 * i, 15, 2.2); }});
    // Side polygons off: their margins change with the view, and a texture of another size goes up whole.
    for (int n : {256, 1024})
        sc.push_back({"partial-upload",
                      std::to_string(n) + "^2 flat wall with one raised block, eye orbiting 0.5 degree per frame, "
                                          "no side polygons",
                      corner_block(n), [](const ReliefQuad& q, int i, int) { return orbit(q, 20 + 0.5 * i, 15, 2.2); },
                      0, true, false});
    // Zero-displacement runs: the same frames with the copy (skips on) and without (--no-skips), the eye moving
    // enough that every frame is pre-warped again. The copy cannot change a pixel: the picture must be the same.
    const auto brick_orbit = [](const ReliefQuad& q, int i, int) { return orbit(q, 25 + 0.5 * i, 20, 2.2); };
    sc.push_back({"zero-displacement-runs", "bricks 256^2, reference kernels (fast = false), 1 thread",
                  to_relief(make_brick_wall(256)), brick_orbit, 0, false, true, 1});
    sc.push_back({"zero-displacement-runs",
                  "bricks 256^2, fast kernels, 1 thread (they always copy such spans: nothing to switch off)",
                  to_relief(make_brick_wall(256)), brick_orbit, 0, true, true, 1});
    sc.push_back({"inside-slab-micromesh", "eye between the facade's wall and its window frames",
                  to_relief(make_facade(256)), [](const ReliefQuad& q, int, int) {
                      Camera c = orbit(q, 0, 0, 2.2);
                      const ReliefGeometry& g = q.relief().geometry;
                      c.eye = g.origin + g.a * 128.0 + g.b * 60.0 + g.f() * 0.06;
                      c.look_at = c.eye + glm::dvec3(0, 0.3, -1);
                      const Bounds b = relief_bounds(q.relief());
                      c.fit_clip_planes(b.centre(), b.radius());
                      return c;
                  }});
    sc.push_back({"pyramid level auto", "bumps 12 radii away, level auto vs 0", to_relief(make_bumps(256)),
                  [](const ReliefQuad& q, int, int) { return orbit(q, 30, 20, 12); }, -1});

    auto ctx = GlContext::create_offscreen(512, 512, {.pin_llvmpipe_threads = true});
    Renderer renderer;
    std::vector<SkipMeasurement> out;
    for (Scenario& s : sc) {
        SkipMeasurement m;
        m.skip = s.skip;
        m.scenario = s.scenario;
        // One quad with the skips, one without, their frames interleaved: load from other processes on the machine
        // falls on both alike (measuring all frames with, then all without, once showed a skip "costing" 40%).
        ReliefQuad quads[2] = {ReliefQuad(s.relief), ReliefQuad(std::move(s.relief))};  // [with]
        RenderSettings rs[2];
        std::vector<double> ms[2], work[2];
        ImageRGBA8 last[2];
        Camera cam;
        for (int with = 0; with < 2; ++with) {
            rs[with].method = RenderMethod::two_pass;
            rs[with].prewarp.keep_outliers = s.sidewalls;
            rs[with].prewarp.isa = s.fast ? Isa::automatic : Isa::generic;
            rs[with].prewarp.threads = s.threads;
            rs[with].draw.skips = with;
            rs[with].draw.level = with ? s.level : 0;
        }
        for (int i = 0; i < frames; ++i) {
            cam = s.camera(quads[0], i, frames);
            for (int with = 1; with >= 0; --with) {
                StageTimes st;
                DrawReport rep;
                last[with] = render_relief_frame(quads[with], &renderer, cam, rs[with], st, &rep);
                if (with && (std::find(rep.skips.begin(), rep.skips.end(), s.skip) != rep.skips.end() ||
                             (s.level < 0 && rep.level > 0)))
                    m.fired = true;
                if (i > 0) {  // the first frame warms up (and fills the caches)
                    ms[with].push_back(st.total_ms);
                    work[with].push_back(st.prewarp_ms + st.upload_ms);
                }
            }
        }
        RenderSettings mm;
        mm.method = RenderMethod::micromesh;
        StageTimes mt;
        const ImageRGBA8 truth = render_relief_frame(quads[0], &renderer, cam, mm, mt);
        const DiffResult d0 = diff_images(truth, last[0]), d1 = diff_images(truth, last[1]);
        m.work_without = median(work[0]);
        m.work_with = median(work[1]);
        m.ms_without = median(ms[0]);
        m.ms_with = median(ms[1]);
        m.psnr_without = d0.psnr;
        m.psnr_with = d1.psnr;
        m.iou_without = d0.iou;
        m.iou_with = d1.iou;
        m.same_picture = last[0] == last[1];
        if (progress)
            progress(s.skip + ": " + std::to_string(m.ms_without) + " -> " + std::to_string(m.ms_with) + " ms");
        out.push_back(m);
    }
    return out;
}

std::string skip_table_markdown(const std::vector<SkipMeasurement>& rows) {
    std::string s =
        "| skip | scenario | fired | pre-warp + upload ms without | with | frame ms without | with | PSNR vs micromesh "
        "without | with | IoU without | with | same picture |\n"
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    char buf[512];
    for (const SkipMeasurement& m : rows) {
        std::snprintf(buf, sizeof buf,
                      "| %s | %s | %s | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f | %.4f | %.4f | %s |\n", m.skip.c_str(),
                      m.scenario.c_str(), m.fired ? "yes" : "no", m.work_without, m.work_with, m.ms_without, m.ms_with,
                      m.psnr_without, m.psnr_with, m.iou_without, m.iou_with, m.same_picture ? "yes" : "no");
        s += buf;
    }
    return s;
}

}  // namespace rtm
