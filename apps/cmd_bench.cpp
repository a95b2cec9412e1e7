// rtm bench: pre-warp throughput against the memory bound, and the paper's Table 1 (measure/bench.h). Progress on
// stderr, a Markdown report on stdout, JSON with --json FILE.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "cli_common.h"
#include "formats/image_io.h"
#include "measure/bench.h"
#include "measure/scene_bench.h"
#include "objects/render_method.h"
#include "warp/task_arenas.h"

namespace rtm::cli {

namespace {

struct BenchArgs {
    std::string json, sizes, reliefs, threads, methods, isa;
    bool full = false, no_exact = false, no_reference = false, no_table1 = false, no_objects = false;
    bool adjacent_whole = false;
    std::string scene = "media/town.scene.json";
    bool scene_given = false, no_scene = false, scene_only = false, scene_sequential = false;
    std::string scene_variants;
    double min_time = 0;
    bool min_time_given = false;
    double discontinuity = 0;
    bool discontinuity_given = false;
    // Typed flags (first_given) of the sections the others may leave out: "" when none was.
    std::string prewarp_flag, scene_flag, objects_flag;
};

std::vector<int> parse_ints(const std::string& text, const std::string& flag, int lo, int hi) {
    std::vector<int> v;
    std::stringstream ss(text);
    for (std::string item; std::getline(ss, item, ',');) {
        int x = 0;
        if (!parse_whole_number(item, x, hi) || x < lo)
            throw UsageError(flag + ": expected integers " + std::to_string(lo) + ".." + std::to_string(hi) +
                             " separated by commas, found \"" + text + "\"");
        v.push_back(int(x));
    }
    if (v.empty()) throw UsageError(flag + ": expected at least one value");
    return v;
}

void run_bench_command(const BenchArgs& a) {
    BenchConfig c = default_bench_config(a.full);
    if (!a.sizes.empty()) c.sizes = parse_ints(a.sizes, "--sizes", 8, 8192);
    if (!a.threads.empty()) {
        // What runs is what is reported: a count past the machine's parallelism runs as that (warp/task_arenas.h).
        std::vector<int> runs;
        for (int t : parse_ints(a.threads, "--threads", 1, 1024)) {
            const int can = arena_threads(t);
            if (can < t)
                std::fprintf(stderr, "rtm: warning: --threads %d: this machine runs at most %d; measured with %d\n", t,
                             can, can);
            if (std::find(runs.begin(), runs.end(), can) == runs.end()) runs.push_back(can);
        }
        c.threads = runs;
    }
    if (!a.reliefs.empty()) c.reliefs = parse_relief_names(a.reliefs, "--reliefs");
    c.isas = parse_isa_list(a.isa.empty() ? std::string("auto") : a.isa, "--isa");
    if (a.isa.empty()) c.isas.clear();
    if (!a.methods.empty()) {
        c.methods.clear();
        std::stringstream ss(a.methods);
        for (std::string item; std::getline(ss, item, ',');) {
            try {
                c.methods.push_back(parse_reconstruction(item));
            } catch (const std::invalid_argument& e) {
                throw UsageError(std::string("--methods: ") + e.what());
            }
        }
    }
    if (a.min_time_given) {
        if (!(a.min_time >= 0.0 && a.min_time <= 3600.0)) {
            std::ostringstream found;
            found << a.min_time;  // shortest form: "-2", "nan"
            throw UsageError("--min-time: expected seconds in 0..3600, found " + found.str());
        }
        c.min_seconds = a.min_time;
    }
    if (a.discontinuity_given) {
        if (!(a.discontinuity > 0.0 && a.discontinuity <= 1.0)) {
            std::ostringstream found;
            found << a.discontinuity;
            throw UsageError("--discontinuity: expected a fraction of the displacement range in (0, 1], found " +
                             found.str());
        }
        c.discontinuity = a.discontinuity;
    }
    if (!a.json.empty()) check_output_file(a.json, "--json");
    c.exact = !a.no_exact;
    c.reference = !a.no_reference;
    c.table1 = !a.no_table1;
    c.objects = !a.no_objects;
    c.object_adjacent_holes_only = !a.adjacent_whole;
    c.progress = [](const std::string& line) { std::fprintf(stderr, "bench: %s\n", line.c_str()); };
    if (a.no_scene && (a.scene_only || a.scene_given))
        throw UsageError("--no-scene contradicts --scene and --scene-only");
    // The scene section runs with the other OpenGL frames (Table 1) when the default scene is at hand, or on request.
    const bool with_scene = !a.no_scene &&
                            (a.scene_given || a.scene_only || (!a.no_table1 && std::filesystem::exists(a.scene)));
    if (a.scene_only && !with_scene) throw IoError(a.scene + ": no such scene (give --scene FILE)");
    // What a section the others leave out would ignore: exit 2, not silence.
    if (a.scene_only && !a.prewarp_flag.empty())
        throw UsageError(a.prewarp_flag + " applies to the pre-warp sections, which --scene-only leaves out");
    if (!with_scene && !a.scene_flag.empty())
        throw UsageError(a.scene_flag + " applies to the scene's path, which does not run (" +
                         (a.no_scene    ? "--no-scene"
                          : a.no_table1 ? "--no-table1 without --scene"
                                        : "no scene at hand") +
                         ")");
    if (!a.objects_flag.empty() && (a.no_table1 || a.no_objects))
        throw UsageError(a.objects_flag + " applies to the six-face objects' frames, which " +
                         (a.no_table1 ? "--no-table1" : "--no-objects") + " leaves out");
    // The generic kernels are measured as the reference rows (one thread), not among the fast rows' targets.
    if (a.no_reference && std::find(c.isas.begin(), c.isas.end(), Isa::generic) != c.isas.end())
        throw UsageError(
            "--isa generic: the generic kernels run as the reference rows, which --no-reference leaves out");
    const BenchResult r = a.scene_only ? BenchResult{} : run_bench(c);
    nlohmann::json j = a.scene_only ? nlohmann::json::object() : bench_json(r);
    std::string md = a.scene_only ? std::string() : bench_markdown(r);
    if (with_scene) {
        md += "\n### A scene along its camera path\n\n";
        std::vector<SceneVariant> variants = scene_frame_variants();
        if (!a.scene_variants.empty()) {
            try {
                variants = select_scene_variants(variants, a.scene_variants);
            } catch (const std::invalid_argument& e) {
                throw UsageError(std::string("--scene-variants: ") + e.what());
            }
        }
        const SceneBench sb = bench_scene(a.scene, 640, 480, variants, c.progress, !a.scene_sequential);
        md += scene_bench_markdown(sb);
        j["command"] = "bench";
        j["scene"] = scene_bench_json(sb);
    } else if (!a.no_scene && !a.no_table1) {
        md += "\n### A scene along its camera path\n\nSkipped: " + a.scene +
              " not found (run from the source folder or give --scene FILE).\n";
    }
    if (!a.json.empty()) write_json(a.json, j);
    std::printf("%s", md.c_str());
}

}  // namespace

void add_bench_command(CLI::App& app) {
    auto a = std::make_shared<BenchArgs>();
    CLI::App* sub = app.add_subcommand("bench", "Pre-warp throughput against the memory bound, and Table 1");
    sub->add_option("--json", a->json, "Write the figures as JSON");
    sub->add_flag("--full", a->full, "All sizes up to 4096^2 (default: 128^2 to 1024^2, about a minute)");
    sub->add_option("--sizes", a->sizes, "Texture sizes, e.g. 256,1024 (overrides the default set)")
        ->check(non_empty_list());
    sub->add_option("--reliefs", a->reliefs, "Procedural reliefs, e.g. bumps,bricks,ridges")->check(non_empty_list());
    sub->add_option("--methods", a->methods, "Reconstructions, e.g. two-pass,pipelined (default both)")
        ->check(non_empty_list());
    sub->add_option("--threads", a->threads, "Thread counts of the fast kernels, e.g. 1,2")->check(non_empty_list());
    sub->add_option("--isa", a->isa,
                    "SIMD targets to measure side by side, e.g. avx512,avx3,avx2,sse4,generic (default: "
                    "auto, i.e. RTM_ISA or the fastest)")
        ->check(non_empty_list());
    sub->add_option("--min-time", a->min_time, "Seconds of repeats per measurement (default 0.25)")
        ->each([a](const std::string&) { a->min_time_given = true; });
    sub->add_option("--discontinuity", a->discontinuity,
                    "Mark the throughput reliefs' surface discontinuities at this fraction of their displacement "
                    "range, as six-face objects' faces are (e.g. 0.05; default: no marks)")
        ->each([a](const std::string&) { a->discontinuity_given = true; });
    sub->add_flag("--no-exact", a->no_exact, "Skip the --exact (double precision) path");
    sub->add_flag("--no-reference", a->no_reference, "Skip the generic reference kernels");
    sub->add_flag("--no-table1", a->no_table1, "Skip the OpenGL frame (Table 1) and the objects beside it");
    sub->add_flag("--no-objects", a->no_objects, "Skip the six-face objects' frames beside Table 1");
    sub->add_flag("--adjacent-whole", a->adjacent_whole,
                  "Objects: warp the adjacent faces whole, not only where the face leaves holes (the same image; "
                  "to measure what that saves)");
    sub->add_option("--scene", a->scene,
                    "Scene whose camera path is timed at 640x480 (default media/town.scene.json, when present)")
        ->each([a](const std::string&) { a->scene_given = true; });
    sub->add_flag("--no-scene", a->no_scene, "Skip the scene's camera path");
    sub->add_flag("--scene-only", a->scene_only, "Only the scene's camera path");
    sub->add_option("--scene-variants", a->scene_variants,
                    "Only these variants of the scene's path, by name, separated by ';' (default all)");
    sub->add_flag("--scene-sequential", a->scene_sequential,
                  "The scene's variants one after another, each over the whole path (default: interleaved frame by "
                  "frame)");
    sub->callback([a, sub] {
        a->prewarp_flag = first_given(*sub, {"--full", "--sizes", "--reliefs", "--methods", "--threads", "--isa",
                                             "--min-time", "--discontinuity", "--no-exact", "--no-reference",
                                             "--no-table1", "--no-objects", "--adjacent-whole"});
        a->scene_flag = first_given(*sub, {"--scene-variants", "--scene-sequential"});
        a->objects_flag = first_given(*sub, {"--adjacent-whole"});
        run_bench_command(*a);
    });
}

}  // namespace rtm::cli
