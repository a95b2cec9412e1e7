#include "cmd_compare_mesh.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli_common.h"
#include "formats/atomic_file.h"
#include "formats/image_io.h"
#include "formats/object_manifest.h"
#include "measure/object_accuracy.h"
#include "mesh/bake_object.h"
#include "texmap/gl_context.h"

namespace rtm::cli {

namespace {

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

// --mesh: the object baked from the mesh (OUT/object/NAME.object.json, or --object) against the mesh itself.
void run_compare_mesh(const CompareMeshArgs& a) {
    if (!a.object.empty() && a.texels_given) throw UsageError("--texels bakes the mesh; it does not apply to --object");
    if (a.texels < 1 || a.texels > 16384)
        throw UsageError("--texels: expected N texels along the longest side, 1..16384, found " +
                         std::to_string(a.texels));
    ObjectAccuracyOptions o;
    parse_size(a.size, "--size", o.width, o.height);
    o.threads = a.threads;
    const TriangleMesh mesh = load_mesh(a.mesh);
    for (const std::string& w : mesh.warnings) std::fprintf(stderr, "rtm: warning: %s\n", w.c_str());
    make_output_folder(a.out);
    std::string manifest = a.object;
    if (manifest.empty()) {
        const std::string name = std::filesystem::path(a.mesh).stem().string();
        BakedObject baked;
        {
            auto ctx = GlContext::create_offscreen(16, 16);
            baked = bake_object(mesh, a.texels);
        }
        for (const std::string& w : baked.warnings)
            std::fprintf(stderr, "rtm: warning: %s: %s\n", a.mesh.c_str(), w.c_str());
        manifest = write_object(a.out + "/object", name, baked, std::filesystem::path(a.mesh).filename().string());
        std::fprintf(stderr, "compare: baked %s\n", manifest.c_str());
    }
    SixFaceObject loaded = load_object(manifest);
    if (a.discontinuity >= 0)
        for (ReliefTexture& t : loaded.faces) mark_discontinuities(t, a.discontinuity);
    ReliefObject object(std::move(loaded));
    if (!a.no_images)
        o.on_image = [&](const std::string& view, const std::string& what, const ImageRGBA8& img) {
            write_rgba8(a.out + "/" + view + "_" + what + ".png", img);
        };
    size_t done = 0;
    o.on_progress = [&](const std::string& what) {
        ++done;
        std::fprintf(stderr, "compare %s: %s (%zu/%zu)\n", object.name().c_str(), what.c_str(), done, o.views.size());
    };
    const std::vector<ObjectAccuracyRow> rows = measure_object_against_mesh(mesh, object, o);
    const ReliefTexture& px = object.face(0).relief();
    const std::string md = object_accuracy_markdown(object.name() + " (six faces, +x " + std::to_string(px.width) +
                                                        "x" + std::to_string(px.height) + " texels, " + a.size +
                                                        " pixels)",
                                                    rows);
    nlohmann::json j = nlohmann::json::array(), summary = nlohmann::json::array();
    for (const ObjectAccuracyRow& r : rows)
        j.push_back({{"view", r.view},
                     {"method", r.method},
                     {"psnr", finite_or_null(r.error.psnr)},
                     {"rmse", finite_or_null(r.error.rmse)},
                     {"iou", r.error.iou},
                     {"only_mesh", r.error.only_ref},
                     {"only_object", r.error.only_test}});
    for (const ObjectAccuracySummary& m : summarize_object_accuracy(rows))
        summary.push_back({{"method", m.method},
                           {"views", m.views},
                           {"mean_iou", m.mean_iou},
                           {"worst_iou", m.worst_iou},
                           {"worst_iou_view", m.worst_iou_view},
                           {"mean_psnr", m.mean_psnr},
                           {"worst_psnr", m.worst_psnr},
                           {"worst_psnr_view", m.worst_psnr_view}});
    write_json(a.out + "/compare.json", {{"mesh", a.mesh}, {"object", manifest}, {"summary", summary}, {"rows", j}});
    write_text_atomically(a.out + "/compare.md", md);
    std::printf("%s", md.c_str());
}

}  // namespace rtm::cli
