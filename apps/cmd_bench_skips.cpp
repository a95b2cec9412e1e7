// rtm bench-skips: what each skip of a frame saves and what error it adds (docs/BENCHMARKS.md).
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "cli_common.h"
#include "measure/skip_measure.h"

namespace rtm::cli {

namespace {

struct Args {
    std::string json;
    int frames = 20;
};

void run(const Args& a) {
    if (a.frames < 2) throw UsageError("--frames: expected N >= 2, found " + std::to_string(a.frames));
    if (!a.json.empty()) check_output_file(a.json, "--json");
    const auto rows = measure_skips(a.frames, [](const std::string& s) { std::fprintf(stderr, "%s\n", s.c_str()); });
    std::printf("%s", skip_table_markdown(rows).c_str());
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
        write_json(a.json, {{"command", "bench-skips"}, {"rows", j}});
    }
    // The copy of zero-displacement runs adds no error by construction (warp/prewarp.cpp): check it here too.
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
    sub->callback([a] { run(*a); });
}

}  // namespace rtm::cli
