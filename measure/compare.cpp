#include "measure/compare.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "objects/bounds.h"
#include "objects/render_relief.h"
#include "texmap/camera_rig.h"
#include "texmap/gl_context.h"

namespace rtm {

CompareView orbit_view(double azimuth, double elevation, double distance) {
    char name[64];
    std::snprintf(name, sizeof name, "az%02d_el%02d", int(azimuth), int(elevation));
    return {name, azimuth, elevation, distance};
}

std::vector<CompareView> default_compare_views() {
    const double views[][2] = {{0, 0}, {15, 10}, {30, 15}, {45, 20}, {60, 10}, {70, 30}, {80, 5}, {85, 15}};
    std::vector<CompareView> out;
    for (const auto& v : views) out.push_back(orbit_view(v[0], v[1]));
    return out;
}

std::vector<CompareMethod> default_compare_methods() {
    std::vector<CompareMethod> m;
    m.push_back({"flat", RenderMethod::flat, {}});
    PrewarpOptions walls;
    walls.keep_outliers = true;
    m.push_back({"two-pass-no-sidewalls", RenderMethod::two_pass, {}});
    m.push_back({"two-pass", RenderMethod::two_pass, walls});
    PrewarpOptions exact = walls;
    exact.exact = true;
    m.push_back({"two-pass-exact", RenderMethod::two_pass, exact});
    PrewarpOptions pipe = walls;
    pipe.method = Reconstruction::pipelined;
    m.push_back({"pipelined", RenderMethod::pipelined, pipe});
    m.push_back({"micromesh", RenderMethod::micromesh, {}});
    return m;
}

Camera compare_camera(const ReliefQuad& quad, const CompareView& v, int width, int height) {
    const Bounds b = relief_bounds(quad.relief());
    return orbit_camera(b.centre(), b.radius(), {v.azimuth, v.elevation, v.distance}, width, height);
}

std::vector<CompareRow> run_comparison(ReliefQuad& quad, const CompareOptions& o) {
    auto ctx = GlContext::create_offscreen(o.width, o.height, {.pin_llvmpipe_threads = true});
    Renderer renderer;
    std::vector<CompareRow> rows;
    for (const CompareView& v : o.views) {
        const Camera cam = compare_camera(quad, v, o.width, o.height);
        RenderSettings truth_settings;
        truth_settings.method = RenderMethod::raycast;
        truth_settings.prewarp.threads = o.threads;
        StageTimes tt;
        const ImageRGBA8 truth = render_relief_frame(quad, &renderer, cam, truth_settings, tt);
        if (o.on_image) o.on_image(v.name, "raycast", truth);
        RenderSettings mm_settings;
        mm_settings.method = RenderMethod::micromesh;
        StageTimes mt;
        const ImageRGBA8 mesh = render_relief_frame(quad, &renderer, cam, mm_settings, mt);
        rows.push_back({v.name, "raycast", tt.total_ms, 0.0, diff_images(truth, truth), diff_images(mesh, truth)});
        for (const CompareMethod& m : o.methods) {
            RenderSettings s;
            s.method = m.method;
            s.prewarp = m.prewarp;
            s.prewarp.threads = o.threads;
            s.draw.skips = false;  // every frame does all the work: the times compare methods, not caches
            ImageRGBA8 img;
            std::vector<double> total, pre;
            for (int i = 0; i < std::max(1, o.repeat) + 1; ++i) {  // the first frame warms up
                StageTimes st;
                img = render_relief_frame(quad, &renderer, cam, s, st);
                if (i == 0) continue;
                total.push_back(st.total_ms);
                pre.push_back(st.prewarp_ms);
            }
            std::sort(total.begin(), total.end());
            std::sort(pre.begin(), pre.end());
            if (o.on_image) o.on_image(v.name, m.name, img);
            rows.push_back({v.name, m.name, total[total.size() / 2], pre[pre.size() / 2], diff_images(truth, img),
                            diff_images(mesh, img)});
        }
        if (o.on_progress) o.on_progress("view " + v.name + " done");
    }
    return rows;
}

std::string comparison_markdown(const std::string& title, const std::vector<CompareRow>& rows) {
    std::string s = "### " + title +
                    "\n\nError against the ray-cast truth (PSNR, RMSE over pixels covered in both, coverage IoU) and "
                    "against the micro-polygon mesh (PSNR, IoU).\n\n"
                    "| view | method | frame ms | pre-warp ms | PSNR dB | RMSE | IoU | PSNR vs mesh | IoU vs mesh |\n"
                    "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    char buf[256];
    for (const CompareRow& r : rows) {
        if (r.method == "raycast") {
            std::snprintf(buf, sizeof buf, "| %s | raycast (truth) | %.1f | | | | | %.2f | %.4f |\n", r.view.c_str(),
                          r.ms, r.vs_micromesh.psnr, r.vs_micromesh.iou);
        } else {
            std::snprintf(buf, sizeof buf, "| %s | %s | %.2f | %.2f | %.2f | %.2f | %.4f | %.2f | %.4f |\n",
                          r.view.c_str(), r.method.c_str(), r.ms, r.prewarp_ms, r.error.psnr, r.error.rmse, r.error.iou,
                          r.vs_micromesh.psnr, r.vs_micromesh.iou);
        }
        s += buf;
    }
    // Summary per method.
    struct Acc {
        double psnr = 0, iou = 0, psnr_mesh = 0, iou_mesh = 0;
        std::vector<double> ms;
        int n = 0;
    };
    std::map<std::string, Acc> acc;
    std::vector<std::string> order;
    for (const CompareRow& r : rows) {
        if (!acc.count(r.method)) order.push_back(r.method);
        Acc& a = acc[r.method];
        a.psnr += std::isfinite(r.error.psnr) ? r.error.psnr : 99.0;
        a.iou += r.error.iou;
        a.psnr_mesh += std::isfinite(r.vs_micromesh.psnr) ? r.vs_micromesh.psnr : 99.0;
        a.iou_mesh += r.vs_micromesh.iou;
        a.ms.push_back(r.ms);
        ++a.n;
    }
    s += "\n| method | median frame ms | mean PSNR dB | mean IoU | mean PSNR vs mesh | mean IoU vs mesh |\n"
         "|---|---:|---:|---:|---:|---:|\n";
    for (const std::string& m : order) {
        Acc& a = acc[m];
        std::sort(a.ms.begin(), a.ms.end());
        if (m == "raycast")
            std::snprintf(buf, sizeof buf, "| raycast (truth) | %.1f | | | %.2f | %.4f |\n", a.ms[a.ms.size() / 2],
                          a.psnr_mesh / a.n, a.iou_mesh / a.n);
        else
            std::snprintf(buf, sizeof buf, "| %s | %.2f | %.2f | %.4f | %.2f | %.4f |\n", m.c_str(),
                          a.ms[a.ms.size() / 2], a.psnr / a.n, a.iou / a.n, a.psnr_mesh / a.n, a.iou_mesh / a.n);
        s += buf;
    }
    return s;
}

}  // namespace rtm
