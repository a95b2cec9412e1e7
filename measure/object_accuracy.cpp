#include "measure/object_accuracy.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "mesh/mesh_renderer.h"
#include "objects/bounds.h"
#include "texmap/camera_rig.h"
#include "texmap/gl_context.h"

namespace rtm {

std::vector<CompareView> object_ring_views() {
    std::vector<CompareView> out;
    for (double el : {-30.0, 0.0, 35.0, 60.0})
        for (int k = 0; k < 8; ++k) out.push_back(orbit_view(45.0 * k, el, 2.5));
    return out;
}

std::vector<ObjectAccuracyMethod> default_object_accuracy_methods() {
    return {{"two-pass", RenderMethod::two_pass}, {"pipelined", RenderMethod::pipelined}};
}

std::vector<ObjectAccuracyRow> measure_object_against_mesh(const TriangleMesh& mesh, ReliefObject& object,
                                                           const ObjectAccuracyOptions& o) {
    auto ctx = GlContext::create_offscreen(o.width, o.height, {.pin_llvmpipe_threads = true});
    MeshRenderer mesh_renderer(mesh);
    Renderer renderer;
    const Bounds bounds{mesh.lo, mesh.hi};
    std::vector<ObjectAccuracyRow> rows;
    for (const CompareView& v : o.views) {
        const Camera cam = orbit_camera(bounds.centre(), bounds.radius(), {v.azimuth, v.elevation, v.distance}, o.width,
                                        o.height);
        const ImageRGBA8 truth = mesh_renderer.render(cam);
        if (o.on_image) o.on_image(v.name, "mesh", truth);
        for (const ObjectAccuracyMethod& m : o.methods) {
            PrewarpOptions p;
            p.threads = o.threads;
            p.method = m.method == RenderMethod::pipelined ? Reconstruction::pipelined : Reconstruction::two_pass;
            StageTimes st;
            const ImageRGBA8 img = render_object_frame(object, renderer, cam, m.method, p, DrawOptions{}, st);
            ImageRGBA8 heat;
            rows.push_back({v.name, m.name, diff_images(truth, img, o.on_image ? &heat : nullptr)});
            if (o.on_image) {
                o.on_image(v.name, m.name, img);
                o.on_image(v.name, m.name + "_error", heat);
            }
        }
        if (o.on_progress) o.on_progress("view " + v.name + " done");
    }
    return rows;
}

std::vector<ObjectAccuracySummary> summarize_object_accuracy(const std::vector<ObjectAccuracyRow>& rows) {
    std::vector<ObjectAccuracySummary> out;
    std::map<std::string, size_t> index;
    for (const ObjectAccuracyRow& r : rows) {
        auto [it, added] = index.emplace(r.method, out.size());
        if (added) {
            out.emplace_back();
            out.back().method = r.method;
        }
        ObjectAccuracySummary& s = out[it->second];
        const double psnr = std::isfinite(r.error.psnr) ? r.error.psnr : (r.error.rmse == 0.0 ? 99.0 : 0.0);
        if (s.views == 0 || r.error.iou < s.worst_iou) {
            s.worst_iou = r.error.iou;
            s.worst_iou_view = r.view;
        }
        if (s.views == 0 || psnr < s.worst_psnr) {
            s.worst_psnr = psnr;
            s.worst_psnr_view = r.view;
        }
        s.mean_iou += r.error.iou;
        s.mean_psnr += psnr;
        ++s.views;
    }
    for (ObjectAccuracySummary& s : out) {
        s.mean_iou /= s.views;
        s.mean_psnr /= s.views;
    }
    return out;
}

std::string object_accuracy_markdown(const std::string& title, const std::vector<ObjectAccuracyRow>& rows) {
    std::string s = "### " + title +
                    "\n\nThe object against its mesh (rendered conventionally): coverage IoU, PSNR and RMSE over the "
                    "pixels covered in both.\n\n"
                    "| method | views | mean IoU | worst IoU (view) | mean PSNR dB | worst PSNR dB (view) |\n"
                    "|---|---:|---:|---|---:|---|\n";
    char buf[320];
    for (const ObjectAccuracySummary& m : summarize_object_accuracy(rows)) {
        std::snprintf(buf, sizeof buf, "| %s | %d | %.4f | %.4f (%s) | %.2f | %.2f (%s) |\n", m.method.c_str(), m.views,
                      m.mean_iou, m.worst_iou, m.worst_iou_view.c_str(), m.mean_psnr, m.worst_psnr,
                      m.worst_psnr_view.c_str());
        s += buf;
    }
    s += "\n| view | method | IoU | PSNR dB | RMSE | only mesh px | only object px "
         "|\n|---|---|---:|---:|---:|---:|---:|\n";
    for (const ObjectAccuracyRow& r : rows) {
        std::snprintf(buf, sizeof buf, "| %s | %s | %.4f | %.2f | %.2f | %lld | %lld |\n", r.view.c_str(),
                      r.method.c_str(), r.error.iou, r.error.psnr, r.error.rmse, r.error.only_ref, r.error.only_test);
        s += buf;
    }
    return s;
}

}  // namespace rtm
