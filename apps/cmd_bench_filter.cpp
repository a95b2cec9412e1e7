// rtm bench-filter: what the coverage filter costs and gains against point sampling (docs/ACCURACY.md).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli_common.h"
#include "measure/filter_measure.h"
#include "formats/image_io.h"

namespace rtm::cli {

namespace {

struct Args {
    std::string json, reliefs, out;
    int size = 256, samples = 8, repeat = 5, threads = 1;
};

void run(const Args& a) {
    check_isa_environment();
    if (a.size < 8 || a.size > 4096) throw UsageError("--size: expected 8..4096, found " + std::to_string(a.size));
    if (a.samples < 1 || a.samples > 64)
        throw UsageError("--samples: expected 1..64, found " + std::to_string(a.samples));
    if (a.repeat < 1) throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    if (!a.json.empty()) check_output_file(a.json, "--json");
    FilterMeasureOptions o;
    o.size = a.size;
    o.samples = a.samples;
    o.repeat = a.repeat;
    o.threads = a.threads;
    if (!a.reliefs.empty()) o.reliefs = parse_relief_names(a.reliefs, "--reliefs");
    o.progress = [](const std::string& s) { std::fprintf(stderr, "%s\n", s.c_str()); };
    if (!a.out.empty()) {
        make_output_folder(a.out);
        check_output_file((std::filesystem::path(a.out) / "probe.png").string(), "--out");  // takes files, before work
        o.on_image = [&](const std::string& relief, const std::string& view, const std::string& what,
                         const ImageRGBA8& img) {
            write_rgba8((std::filesystem::path(a.out) / (relief + "_" + view + "_" + what + ".png")).string(), img);
        };
    }
    const auto rows = measure_filters(o);
    std::printf("%s", filter_table_markdown(rows).c_str());
    if (!a.json.empty()) {
        nlohmann::json j = nlohmann::json::array();
        for (const FilterMeasurement& m : rows)
            j.push_back({{"relief", m.relief},
                         {"view", m.view},
                         {"filter", m.filter},
                         {"ms", m.ms},
                         {"fast_ms", m.fast_ms},
                         {"color_rmse", m.error.color_rmse},
                         {"coverage_mae", m.error.coverage_mae},
                         {"iou", m.error.iou}});
        write_json(a.json, j);
    }
}

}  // namespace

void add_bench_filter_command(CLI::App& app) {
    auto a = std::make_shared<Args>();
    CLI::App* sub = app.add_subcommand("bench-filter", "Coverage (Fant-style) against point filtering: time and error");
    sub->add_option("--reliefs", a->reliefs, "Procedural reliefs, e.g. bricks,ridges (default: all four)")
        ->check(non_empty_list());
    sub->add_option("--size", a->size, "Relief size in texels")->check(whole_number())->capture_default_str();
    sub->add_option("--samples", a->samples, "Truth rays per pixel side")->check(whole_number())->capture_default_str();
    sub->add_option("--repeat", a->repeat, "Timed pre-warps per measurement")
        ->check(whole_number())
        ->capture_default_str();
    add_threads_option(*sub, a->threads);
    sub->add_option("--json", a->json, "Write the figures as JSON");
    sub->add_option("--out", a->out, "Write the pre-warped textures and their truth into this directory");
    sub->callback([a] { run(*a); });
}

}  // namespace rtm::cli
