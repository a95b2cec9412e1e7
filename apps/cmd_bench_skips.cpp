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
    bool scene_given = false, no_scene = false, scene_only = false, scene_sequential = false;
    int wall_size = 1024, wall_rounds = 15;
    bool wall_only = false;
    std::string frames_flag, wall_flag, sequential_flag;  // typed (first_given), "" when not
};

void run(const Args& a) {
    check_isa_environment();
    if (a.frames < 2) throw UsageError("--frames: expected N >= 2, found " + std::to_string(a.frames));
    if (!a.json.empty()) check_output_file(a.json, "--json");
    if (a.no_scene && (a.scene_only || a.scene_given))
        throw UsageError("--no-scene contradicts --scene and --scene-only");
    const bool with_scene = !a.no_scene && (a.scene_given || std::filesystem::exists(a.scene));
    if (a.wall_only && (a.scene_only || a.scene_given))
        throw UsageError("--wall-only contradicts --scene and --scene-only");
    if (a.wall_size < 16 || a.wall_size > 8192)
        throw UsageError("--wall-size: expected 16 to 8192 texels, found " + std::to_string(a.wall_size));
    if (a.wall_rounds < 1) throw UsageError("--wall-rounds: expected N >= 1, found " + std::to_string(a.wall_rounds));
    if (a.scene_only && !with_scene) throw IoError(a.scene + ": no such scene (give --scene FILE)");
    // What a section the others leave out would ignore: exit 2, not silence.
    if (!a.frames_flag.empty() && (a.wall_only || a.scene_only))
        throw UsageError("--frames sets the skips' scenarios, which " +
                         std::string(a.wall_only ? "--wall-only" : "--scene-only") + " leaves out");
    if (!a.wall_flag.empty() && a.scene_only)
        throw UsageError(a.wall_flag + " applies to the brick wall, which --scene-only leaves out");
    if (!a.sequential_flag.empty() && (a.wall_only || !with_scene))
        throw UsageError("--scene-sequential applies to the scene's path, which " +
                         std::string(a.wall_only ? "--wall-only leaves out"
                                                 : "does not run (--no-scene, or no scene)"));
    auto progress = [](const std::string& s) { std::fprintf(stderr, "%s\n", s.c_str()); };
    const bool skips = !a.scene_only && !a.wall_only;
    const auto rows = skips ? measure_skips(a.frames, progress) : std::vector<SkipMeasurement>{};
    if (skips) std::printf("%s", skip_table_markdown(rows).c_str());
    // The brick wall on the fast kernels: the pre-warp alone, still texels against none.
    const auto wall = a.scene_only ? std::vector<StillWallMeasurement>{}
                                   : measure_still_wall(a.wall_size, a.wall_rounds, progress);
    nlohmann::json wall_json = nlohmann::json::array();
    if (!a.scene_only) {
        std::printf("\n### The brick wall on the fast kernels\n\n%s", still_wall_markdown(wall).c_str());
        for (const StillWallMeasurement& m : wall)
            wall_json.push_back({{"method", to_string(m.method)},
                                 {"threads", m.threads},
                                 {"isa", m.isa},
                                 {"size", m.size},
                                 {"still_fraction", m.still_fraction},
                                 {"rounds", m.rounds},
                                 {"ms_bricks", m.ms_bricks},
                                 {"ms_bricks_no_copy", m.ms_bricks_no_copy},
                                 {"ms_lifted", m.ms_lifted},
                                 {"ms_sunk", m.ms_sunk},
                                 {"cpu_ms_bricks", m.cpu_bricks},
                                 {"cpu_ms_bricks_no_copy", m.cpu_bricks_no_copy},
                                 {"cpu_ms_lifted", m.cpu_lifted},
                                 {"cpu_ms_sunk", m.cpu_sunk},
                                 {"ms_moving_alone", m.ms_moving},
                                 {"cpu_ms_moving_alone", m.cpu_moving},
                                 {"ms_still_copy_alone", m.ms_still_copy},
                                 {"cpu_ms_still_copy_alone", m.cpu_still_copy},
                                 {"same_as_reference", m.same_as_reference}});
    }
    // Each skip's worth along a scene's camera path: the path without that skip against all skips.
    nlohmann::json scene_json;
    std::string scene_failures;  // variants whose pictures left their skip's tolerance
    std::printf("\n### Skips along a scene's camera path\n\n");
    if (a.wall_only) {
        std::printf("Skipped (--wall-only).\n");
    } else if (with_scene) {
        const SceneBench sb = bench_scene(a.scene, 640, 480, scene_skip_variants(), progress, !a.scene_sequential);
        std::printf("%s", scene_bench_markdown(sb).c_str());
        scene_json = scene_bench_json(sb);
        scene_failures = scene_picture_failures(sb);
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
        write_json(a.json, {{"command", "bench-skips"}, {"rows", j}, {"wall", wall_json}, {"scene", scene_json}});
    }
    // Each skip's picture along the scene's path within the skip's stated tolerance (SceneVariant::max_fraction_off),
    // after the report and the JSON are written.
    if (!scene_failures.empty())
        throw std::runtime_error("bench-skips: " + scene_failures.substr(0, scene_failures.find('\n')));
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
    sub->add_option("--frames", a->frames, "Frames per scenario")->check(whole_number())->capture_default_str();
    sub->add_option("--json", a->json, "Write the figures as JSON");
    sub->add_option("--scene", a->scene,
                    "Scene whose camera path is timed without each skip (default media/town.scene.json, when present)")
        ->each([a](const std::string&) { a->scene_given = true; });
    sub->add_flag("--no-scene", a->no_scene, "Skip the scene's camera path");
    sub->add_flag("--scene-only", a->scene_only, "Only the scene's camera path");
    sub->add_flag("--scene-sequential", a->scene_sequential,
                  "The scene's variants one after another, each over the whole path (default: interleaved frame by "
                  "frame)");
    sub->add_option("--wall-size", a->wall_size, "Side of the brick wall timed on the fast kernels")
        ->check(whole_number())
        ->capture_default_str();
    sub->add_option("--wall-rounds", a->wall_rounds, "Interleaved rounds of the brick wall's pre-warps")
        ->check(whole_number())
        ->capture_default_str();
    sub->add_flag("--wall-only", a->wall_only, "Only the brick wall on the fast kernels (no GL, no scene)");
    sub->callback([a, sub] {
        a->frames_flag = first_given(*sub, {"--frames"});
        a->wall_flag = first_given(*sub, {"--wall-size", "--wall-rounds"});
        a->sequential_flag = first_given(*sub, {"--scene-sequential"});
        run(*a);
    });
}

}  // namespace rtm::cli
