#include "objects/skip_measure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "objects/bounds.h"
#include "objects/compare.h"
#include "objects/image_diff.h"
#include "objects/procedural_media.h"
#include "objects/render_relief.h"
#include "texmap/gl_context.h"

namespace rtm {

namespace {

using Clock = std::chrono::steady_clock;

// A 256x256 wall at zero displacement with one raised block in a corner: only a small part of the pre-warped
// texture changes when the eye moves (the partial-upload case).
ReliefTexture corner_block() {
    ProceduralRelief p = make_bumps(256);
    for (int r = 0; r < 256; ++r)
        for (int x = 0; x < 256; ++x) {
            const bool block = x >= 20 && x < 60 && r >= 20 && r < 60;
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
};

Camera orbit(const ReliefQuad& q, double az, double el, double d) { return compare_camera(q, {"s", az, el, d}, 512, 512); }

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
    sc.push_back({"reuse-prewarp", "facade, eye drifting 1e-5 radii per frame",
                  to_relief(make_facade(256)),
                  [](const ReliefQuad& q, int i, int) { return orbit(q, 30 + 1e-4 * i, 15, 2.2); }});
    sc.push_back({"partial-upload", "one raised block in a flat wall, eye orbiting 0.5 degree per frame",
                  corner_block(), [](const ReliefQuad& q, int i, int) { return orbit(q, 20 + 0.5 * i, 15, 2.2); }});
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

    auto ctx = GlContext::create_offscreen(512, 512);
    Renderer renderer;
    std::vector<SkipMeasurement> out;
    for (Scenario& s : sc) {
        SkipMeasurement m;
        m.skip = s.skip;
        m.scenario = s.scenario;
        ReliefQuad quad(std::move(s.relief));
        for (int with = 1; with >= 0; --with) {
            RenderSettings rs;
            rs.method = RenderMethod::two_pass;
            rs.prewarp.keep_outliers = true;
            rs.draw.skips = with;
            rs.draw.level = with ? s.level : 0;
            std::vector<double> ms, work;
            ImageRGBA8 last;
            Camera cam;
            for (int i = 0; i < frames; ++i) {
                cam = s.camera(quad, i, frames);
                StageTimes st;
                DrawReport rep;
                last = render_relief_frame(quad, &renderer, cam, rs, st, &rep);
                if (with && (std::find(rep.skips.begin(), rep.skips.end(), s.skip) != rep.skips.end() ||
                             (s.level < 0 && rep.level > 0)))
                    m.fired = true;
                if (i > 0) {  // the first frame warms up (and fills the caches)
                    ms.push_back(st.total_ms);
                    work.push_back(st.prewarp_ms + st.upload_ms);
                }
            }
            std::sort(ms.begin(), ms.end());
            std::sort(work.begin(), work.end());
            (with ? m.work_with : m.work_without) = work.empty() ? 0.0 : work[work.size() / 2];
            RenderSettings mm;
            mm.method = RenderMethod::micromesh;
            StageTimes mt;
            const ImageRGBA8 truth = render_relief_frame(quad, &renderer, cam, mm, mt);
            const DiffResult d = diff_images(truth, last);
            (with ? m.ms_with : m.ms_without) = ms.empty() ? 0.0 : ms[ms.size() / 2];
            (with ? m.psnr_with : m.psnr_without) = d.psnr;
            (with ? m.iou_with : m.iou_without) = d.iou;
        }
        if (progress) progress(s.skip + ": " + std::to_string(m.ms_without) + " -> " + std::to_string(m.ms_with) + " ms");
        out.push_back(m);
    }
    return out;
}

std::string skip_table_markdown(const std::vector<SkipMeasurement>& rows) {
    std::string s =
        "| skip | scenario | fired | pre-warp + upload ms without | with | frame ms without | with | PSNR vs micromesh "
        "without | with | IoU without | with |\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    char buf[512];
    for (const SkipMeasurement& m : rows) {
        std::snprintf(buf, sizeof buf, "| %s | %s | %s | %.3f | %.3f | %.2f | %.2f | %.2f | %.2f | %.4f | %.4f |\n",
                      m.skip.c_str(), m.scenario.c_str(), m.fired ? "yes" : "no", m.work_without, m.work_with,
                      m.ms_without, m.ms_with, m.psnr_without, m.psnr_with, m.iou_without, m.iou_with);
        s += buf;
    }
    return s;
}

}  // namespace rtm
