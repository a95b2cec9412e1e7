// rtm compare: renders one relief with every method at eight views from frontal to grazing, writes the pictures
// and a table of run time against error (PSNR, RMSE, coverage IoU) relative to the ray-cast truth.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "cli_common.h"
#include "formats/atomic_file.h"
#include "measure/compare.h"
#include "formats/relief_manifest.h"
#include "formats/image_io.h"

namespace rtm::cli {

namespace {

struct CompareArgs {
    std::string relief, out, size = "512x512";
    int repeat = 5, threads = 0;
    bool no_images = false;
};

void run_compare(const CompareArgs& a) {
    if (a.relief.empty()) throw UsageError("compare needs --relief M");
    if (a.repeat < 1) throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    CompareOptions o;
    parse_size(a.size, "--size", o.width, o.height);
    o.repeat = a.repeat;
    o.threads = a.threads;
    ReliefManifest m;
    ReliefQuad quad(load_relief(a.relief, &m));
    std::error_code ec;
    std::filesystem::create_directories(a.out, ec);
    if (ec || !std::filesystem::is_directory(a.out)) throw IoError(a.out + ": cannot create the output folder");
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
                     {"psnr", std::isfinite(r.error.psnr) ? nlohmann::json(r.error.psnr) : nlohmann::json(nullptr)},
                     {"rmse", r.error.rmse},
                     {"iou", r.error.iou},
                     {"psnr_vs_micromesh", std::isfinite(r.vs_micromesh.psnr) ? nlohmann::json(r.vs_micromesh.psnr)
                                                                              : nlohmann::json(nullptr)},
                     {"iou_vs_micromesh", r.vs_micromesh.iou}});
    write_json(a.out + "/compare.json", {{"relief", a.relief}, {"rows", j}});
    write_text_atomically(a.out + "/compare.md", md);
    std::printf("%s", md.c_str());
}

}  // namespace

void add_compare_command(CLI::App& app) {
    auto a = std::make_shared<CompareArgs>();
    CLI::App* sub = app.add_subcommand("compare", "Render one relief with every method; time against error");
    sub->add_option("--relief", a->relief, "Relief texture manifest")->required();
    sub->add_option("--out", a->out, "Output folder")->required();
    sub->add_option("--size", a->size, "Image size WxH")->capture_default_str();
    sub->add_option("--repeat", a->repeat, "Frames timed per method and view")->capture_default_str();
    sub->add_option("--threads", a->threads, "Threads (0 = all)")->capture_default_str();
    sub->add_flag("--no-images", a->no_images, "Only the table");
    sub->callback([a] { run_compare(*a); });
}

}  // namespace rtm::cli
