#include "measure/skip_measure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "objects/bounds.h"
#include "measure/compare.h"
#include "warp/timing.h"
#include "measure/image_diff.h"
#include "procedural/procedural_media.h"
#include "objects/render_relief.h"
#include "texmap/gl_context.h"
#include "warp/prewarp_coefficients.h"

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

std::vector<StillWallMeasurement> measure_still_wall(int size, int rounds,
                                                     const std::function<void(const std::string&)>& progress) {
    ReliefTexture walls[4] = {to_relief(make_brick_wall(size)),
                              to_relief(make_shifted_brick_wall(size, 0.05)),
                              to_relief(make_shifted_brick_wall(size, -0.05)),
                              {}};
    // The moving texels alone: the still ones emptied.
    walls[3] = walls[0];
    bool still_level[256] = {};
    for (int q = 0; q < 255; ++q) still_level[q] = walls[0].quant.decode(uint8_t(q)) == 0.0;
    for (ReliefTexel& tx : walls[3].texels.edit())
        if (still_level[tx.q]) tx.q = kEmptyIndex;
    // The still texels copied to their own pixels (no margins: PrewarpOptions' default).
    ImageRGBA8 copy_out(size, size);
    auto copy_still = [&] {
        const ReliefTexture& t = walls[0];
        for (size_t i = 0; i < t.texels.size(); ++i) {
            const ReliefTexel tx = t.texels[i];
            if (still_level[tx.q]) copy_out.pixels[i] = Rgba8{tx.r, tx.g, tx.b, 255};
        }
    };
    const ReliefQuad quad(walls[0]);
    const Camera cam = compare_camera(quad, orbit_view(30.0, 20.0), 512, 512);
    const double still = double(count_still_texels(walls[0], false)) / (double(size) * size);
    std::vector<Isa> isas = {resolve_isa(Isa::automatic)};
    if (isas[0] != Isa::avx2 && isa_supported(Isa::avx2)) isas.push_back(Isa::avx2);
    std::vector<StillWallMeasurement> out;
    for (Isa isa : isas) {
        for (Reconstruction method : {Reconstruction::two_pass, Reconstruction::pipelined}) {
            for (int threads : {1, 2}) {
                StillWallMeasurement m;
                m.method = method;
                m.threads = threads;
                m.size = size;
                m.still_fraction = still;
                m.rounds = rounds;
                // Variants: the wall, the wall without the copy, lifted, sunk, the moving texels alone; each its
                // own workspace and output; then the still copy alone.
                constexpr int kVariants = 5;
                PrewarpOptions o[kVariants];
                const ReliefTexture* relief[kVariants] = {&walls[0], &walls[0], &walls[1], &walls[2], &walls[3]};
                PrewarpWorkspace ws[kVariants];
                ImageRGBA8 img[kVariants];
                std::vector<double> ms[kVariants + 1], cpu[kVariants + 1];
                PrewarpCoefficients k[kVariants];
                for (int v = 0; v < kVariants; ++v) {
                    o[v].method = method;
                    o[v].threads = threads;
                    o[v].isa = isa;
                    o[v].copy_still_runs = v != 1;
                    k[v] = compute_coefficients(relief[v]->geometry, cam.eye);
                    m.isa = isa_name(prewarp(*relief[v], k[v], o[v], ws[v], img[v]).isa);  // warm-up
                }
                const clockid_t clock = threads == 1 ? CLOCK_THREAD_CPUTIME_ID : CLOCK_PROCESS_CPUTIME_ID;
                auto cpu_ms = [clock] {
                    timespec ts;
                    clock_gettime(clock, &ts);
                    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
                };
                // Interleaved rounds: load from other processes falls on every variant alike.
                for (int r = 0; r < rounds; ++r)
                    for (int v = 0; v <= kVariants; ++v) {
                        const double c0 = cpu_ms();
                        const auto t0 = Clock::now();
                        if (v < kVariants)
                            prewarp(*relief[v], k[v], o[v], ws[v], img[v]);
                        else
                            copy_still();
                        ms[v].push_back(ms_since(t0));
                        cpu[v].push_back(cpu_ms() - c0);
                    }
                m.ms_bricks = median(ms[0]);
                m.ms_bricks_no_copy = median(ms[1]);
                m.ms_lifted = median(ms[2]);
                m.ms_sunk = median(ms[3]);
                m.cpu_bricks = median(cpu[0]);
                m.cpu_bricks_no_copy = median(cpu[1]);
                m.cpu_lifted = median(cpu[2]);
                m.cpu_sunk = median(cpu[3]);
                m.ms_moving = median(ms[4]);
                m.cpu_moving = median(cpu[4]);
                m.ms_still_copy = median(ms[5]);
                m.cpu_still_copy = median(cpu[5]);
                PrewarpOptions ro = o[0];
                ro.isa = Isa::generic;
                ro.threads = 2;
                PrewarpWorkspace rws;
                ImageRGBA8 ref;
                prewarp(walls[0], k[0], ro, rws, ref);
                m.same_as_reference = ref == img[0] && ref == img[1];
                if (progress) {
                    char buf[256];
                    std::snprintf(buf, sizeof buf,
                                  "brick wall %d^2 %s %s, %d thread%s: %.3f ms (CPU %.3f), lifted %.3f (CPU %.3f)",
                                  size, m.isa.c_str(), to_string(method).c_str(), threads, threads == 1 ? "" : "s",
                                  m.ms_bricks, m.cpu_bricks, m.ms_lifted, m.cpu_lifted);
                    progress(buf);
                }
                out.push_back(m);
            }
        }
    }
    return out;
}

std::string still_wall_markdown(const std::vector<StillWallMeasurement>& rows) {
    std::string s =
        "| target | method | threads | bricks ms (CPU) | bricks, copy off | lifted +0.05 | sunk -0.05 | "
        "lifted / bricks (CPU) | sunk / bricks (CPU) | copy off / on (CPU) | moving texels alone | still copy alone "
        "| lifted / (moving + copy) (CPU) | same as reference |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    char buf[800];
    for (const StillWallMeasurement& m : rows) {
        std::snprintf(buf, sizeof buf,
                      "| %s | %s | %d | %.3f (%.3f) | %.3f (%.3f) | %.3f (%.3f) | %.3f (%.3f) | %.2fx (%.2fx) | "
                      "%.2fx (%.2fx) | %.2fx (%.2fx) | %.3f (%.3f) | %.3f (%.3f) | %.2fx (%.2fx) | %s |\n",
                      m.isa.c_str(), to_string(m.method).c_str(), m.threads, m.ms_bricks, m.cpu_bricks,
                      m.ms_bricks_no_copy, m.cpu_bricks_no_copy, m.ms_lifted, m.cpu_lifted, m.ms_sunk, m.cpu_sunk,
                      m.ms_lifted / m.ms_bricks, m.cpu_lifted / m.cpu_bricks, m.ms_sunk / m.ms_bricks,
                      m.cpu_sunk / m.cpu_bricks, m.ms_bricks_no_copy / m.ms_bricks, m.cpu_bricks_no_copy / m.cpu_bricks,
                      m.ms_moving, m.cpu_moving, m.ms_still_copy, m.cpu_still_copy,
                      m.ms_lifted / (m.ms_moving + m.ms_still_copy), m.cpu_lifted / (m.cpu_moving + m.cpu_still_copy),
                      m.same_as_reference ? "yes" : "no");
        s += buf;
    }
    if (!rows.empty()) {
        std::snprintf(buf, sizeof buf,
                      "\n%d^2, %.0f%% of the texels still; medians of %d interleaved rounds, wall clock and CPU time "
                      "(the thread's with 1 thread, the process's with 2).\n",
                      rows[0].size, 100.0 * rows[0].still_fraction, rows[0].rounds);
        s += buf;
    }
    return s;
}

}  // namespace rtm
