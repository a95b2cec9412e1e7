// rtm compare: renders one relief with every method at eight views from frontal to grazing, writes the pictures
// and a table of run time against error (PSNR, RMSE, coverage IoU) relative to the ray-cast truth. With --mesh: bakes
// the mesh into a six-face object (or takes --object) and renders both from a ring of 32 views
// (measure/object_accuracy.h), the object by two-pass and pipelined relief texture mapping against the mesh.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "cli_common.h"
#include "formats/atomic_file.h"
#include "measure/compare.h"
#include "measure/object_accuracy.h"
#include "formats/relief_manifest.h"
#include "formats/image_io.h"
#include "formats/object_manifest.h"
#include "mesh/bake_object.h"
#include "texmap/gl_context.h"

namespace rtm::cli {

namespace {

struct CompareArgs {
    std::string relief, mesh, object, out, size = "512x512";
    int repeat = 5, threads = 0, texels = 256;
    double discontinuity = -1;  // --mesh: re-mark every face's discontinuities (world units); -1: the manifest's
    bool no_images = false, texels_given = false;
};

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

void make_output_folder(const std::string& out) {
    std::error_code ec;
    std::filesystem::create_directories(out, ec);
    if (ec || !std::filesystem::is_directory(out)) throw IoError(out + ": cannot create the output folder");
}

// --mesh: the object baked from the mesh (OUT/object/NAME.object.json, or --object) against the mesh itself.
void run_compare_mesh(const CompareArgs& a) {
    if (!a.object.empty() && a.texels_given) throw UsageError("--texels bakes the mesh; it does not apply to --object");
    if (!(a.discontinuity >= 0 || a.discontinuity == -1) || !std::isfinite(a.discontinuity))
        throw UsageError("--discontinuity: expected a threshold >= 0, found " + std::to_string(a.discontinuity));
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

void run_compare(const CompareArgs& a) {
    if (a.relief.empty() == a.mesh.empty()) throw UsageError("compare needs one of --relief M and --mesh FILE");
    if (a.repeat < 1) throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    if (!a.mesh.empty()) return run_compare_mesh(a);
    if (!a.object.empty() || a.texels_given || a.discontinuity != -1)
        throw UsageError("--object, --texels and --discontinuity apply to --mesh");
    CompareOptions o;
    parse_size(a.size, "--size", o.width, o.height);
    o.repeat = a.repeat;
    o.threads = a.threads;
    ReliefManifest m;
    ReliefQuad quad(load_relief(a.relief, &m));
    make_output_folder(a.out);
    if (!a.no_images)
        o.on_image = [&](const std::string& view, const std::string& method, const ImageRGBA8& img) {
            write_rgba8(a.out + "/" + view + "_" + method + ".png", img);
        };
    const size_t steps = o.views.size();
    size_t done = 0;
    o.on_progress = [&](const std::string& what) {
        ++done;
        std::fprintf(stderr, "compare %s: %s (%zu/%zu)\n", m.name.c_str(), what.c_str(), done, steps);
    };
    const std::vector<CompareRow> rows = run_comparison(quad, o);
    const std::string md = comparison_markdown(m.name + " (" + std::to_string(quad.relief().width) + "x" +
                                                   std::to_string(quad.relief().height) + " texels, " + a.size +
                                                   " pixels)",
                                               rows);
    nlohmann::json j = nlohmann::json::array();
    for (const CompareRow& r : rows)
        j.push_back({{"view", r.view},
                     {"method", r.method},
                     {"total_ms", r.ms},
                     {"prewarp_ms", r.prewarp_ms},
                     {"psnr", finite_or_null(r.error.psnr)},
                     {"rmse", r.error.rmse},
                     {"iou", r.error.iou},
                     {"psnr_vs_micromesh", finite_or_null(r.vs_micromesh.psnr)},
                     {"iou_vs_micromesh", r.vs_micromesh.iou}});
    write_json(a.out + "/compare.json", {{"relief", a.relief}, {"rows", j}});
    write_text_atomically(a.out + "/compare.md", md);
    std::printf("%s", md.c_str());
}

}  // namespace

void add_compare_command(CLI::App& app) {
    auto a = std::make_shared<CompareArgs>();
    CLI::App* sub = app.add_subcommand(
        "compare", "Render one relief with every method (time against error), or a baked mesh against the mesh");
    sub->add_option("--relief", a->relief, "Relief texture manifest");
    sub->add_option("--mesh", a->mesh, "A mesh: bake it (or take --object) and compare the object with the mesh");
    sub->add_option("--object", a->object, "With --mesh: an object manifest baked from it, instead of baking");
    sub->add_option(
        "--discontinuity", a->discontinuity,
        "With --mesh: re-mark every face's discontinuities (world units, 0 = none); default: the manifest's");
    auto* texels = sub->add_option("--texels", a->texels, "With --mesh: bake texels along the box's longest side")
                       ->capture_default_str();
    sub->add_option("--out", a->out, "Output folder")->required();
    sub->add_option("--size", a->size, "Image size WxH")->capture_default_str();
    sub->add_option("--repeat", a->repeat, "Frames timed per method and view")->capture_default_str();
    sub->add_option("--threads", a->threads, "Threads (0 = all)")->capture_default_str();
    sub->add_flag("--no-images", a->no_images, "Only the table");
    sub->callback([a, texels] {
        a->texels_given = texels->count() > 0;
        run_compare(*a);
    });
}

}  // namespace rtm::cli
