// rtm bench-skips: what each skip of a frame saves and what error it adds (docs/BENCHMARKS.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "cli_common.h"
#include "formats/image_io.h"
#include "measure/scene_bench.h"
#include "measure/skip_measure.h"

namespace rtm::cli {

namespace {

struct Args {
    std::string json;
    int frames = 20;
    std::string scene = "media/town.scene.json";
    bool scene_given = false, no_scene = false, scene_only = false;
};

void run(const Args& a) {
    if (a.frames < 2) throw UsageError("--frames: expected N >= 2, found " + std::to_string(a.frames));
    if (!a.json.empty()) check_output_file(a.json, "--json");
    if (a.no_scene && (a.scene_only || a.scene_given))
        throw UsageError("--no-scene contradicts --scene and --scene-only");
    const bool with_scene = !a.no_scene && (a.scene_given || std::filesystem::exists(a.scene));
    if (a.scene_only && !with_scene) throw IoError(a.scene + ": no such scene (give --scene FILE)");
    auto progress = [](const std::string& s) { std::fprintf(stderr, "%s\n", s.c_str()); };
    const auto rows = a.scene_only ? std::vector<SkipMeasurement>{} : measure_skips(a.frames, progress);
    if (!a.scene_only) std::printf("%s", skip_table_markdown(rows).c_str());
    // Each skip's worth along a scene's camera path: the path without that skip against all skips.
    nlohmann::json scene_json;
    std::printf("\n### Skips along a scene's camera path\n\n");
    if (with_scene) {
        const SceneBench sb = bench_scene(a.scene, 640, 480, scene_skip_variants(), progress);
        std::printf("%s", scene_bench_markdown(sb).c_str());
        scene_json = scene_bench_json(sb);
    } else {
        std::printf("Skipped: %s not found (run from the source folder or give --scene FILE).\n", a.scene.c_str());
    }
    if (!a.json.empty()) {
        nlohmann::json j = nlohmann::json::array();
        for (const SkipMeasurement& m : rows)
            j.push_back({{"skip", m.skip},
                         {"scenario", m.scenario},
                         {"fired", m.fired},
                         {"ms_without", m.ms_without},
                         {"ms_with", m.ms_with},
                         {"prewarp_upload_ms_without", m.work_without},
                         {"prewarp_upload_ms_with", m.work_with},
                         {"iou_without", m.iou_without},
                         {"iou_with", m.iou_with},
                         {"same_picture", m.same_picture},
                         {"psnr_without", std::isfinite(m.psnr_without) ? nlohmann::json(m.psnr_without) : nullptr},
                         {"psnr_with", std::isfinite(m.psnr_with) ? nlohmann::json(m.psnr_with) : nullptr}});
        write_json(a.json, {{"command", "bench-skips"}, {"rows", j}, {"scene", scene_json}});
    }
    // The copy of zero-displacement runs adds no error by construction (warp/reference/reference_prewarp.cpp):
    // check it here too.
    for (const SkipMeasurement& m : rows)
        if (m.skip == "zero-displacement-runs" && !m.same_picture)
            throw std::runtime_error("bench-skips: zero-displacement-runs changed the picture (" + m.scenario +
                                     "); the copy must give the same pixels as the warp");
}

}  // namespace

void add_bench_skips_command(CLI::App& app) {
    auto a = std::make_shared<Args>();
    CLI::App* sub = app.add_subcommand("bench-skips", "Time saved and error added by each skip of a frame");
    sub->add_option("--frames", a->frames, "Frames per scenario")->capture_default_str();
    sub->add_option("--json", a->json, "Write the figures as JSON");
    sub->add_option("--scene", a->scene,
                    "Scene whose camera path is timed without each skip (default media/town.scene.json, when present)")
        ->each([a](const std::string&) { a->scene_given = true; });
    sub->add_flag("--no-scene", a->no_scene, "Skip the scene's camera path");
    sub->add_flag("--scene-only", a->scene_only, "Only the scene's camera path");
    sub->callback([a] { run(*a); });
}

}  // namespace rtm::cli
