// rtm prewarp: writes the pre-warped texture itself (paper Figure 9c).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli_common.h"
#include "objects/bounds.h"
#include "formats/relief_manifest.h"
#include "objects/relief_quad.h"
#include "formats/image_io.h"
#include "warp/prewarp.h"

namespace rtm::cli {

namespace {

struct PrewarpArgs {
    std::string relief, eye, out, method = "two-pass", level = "0", json, filter = "point", isa = "auto";
    bool exact = false;
    int repeat = 1, threads = 0;
};

void run_prewarp(const PrewarpArgs& a) {
    const glm::dvec3 eye = parse_vec3(a.eye, "--eye");
    PrewarpOptions opt;
    if (a.method == "two-pass")
        opt.method = Reconstruction::two_pass;
    else if (a.method == "pipelined")
        opt.method = Reconstruction::pipelined;
    else
        throw UsageError("--method: unknown method \"" + a.method + "\" for prewarp; known: two-pass, pipelined");
    const int level_arg = parse_level(a.level);
    if (a.repeat < 1) throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    if (a.threads < 0) throw UsageError("--threads: expected N >= 0, found " + std::to_string(a.threads));
    opt.exact = a.exact;
    opt.threads = a.threads;
    opt.filter = parse_filter(a.filter, opt.method);
    opt.isa = parse_isa_arg(a.isa, "--isa");

    ReliefQuad quad(load_relief(a.relief));
    int level = level_arg;
    if (level < 0) {  // auto: the level for a 512x512, 45-degree view from the eye towards the relief's centre
        Camera cam;
        cam.eye = eye;
        cam.look_at = relief_bounds(quad.relief()).centre();
        if (!cam.validate().empty()) cam.look_at = eye - quad.relief().geometry.f();
        level = quad.auto_level(cam);
    }
    level = std::min(level, quad.levels() - 1);
    const ReliefTexture& relief = quad.level(level);
    const PrewarpCoefficients k = compute_coefficients(relief.geometry, eye);
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    PrewarpStats stats = prewarp(relief, k, opt, ws, out);  // warm-up (and the only run when repeat == 1)
    std::vector<double> times;
    for (int i = 0; i < a.repeat; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        stats = prewarp(relief, k, opt, ws, out);
        times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    write_rgba8(a.out, out);
    if (!a.json.empty()) {
        // Texels at zero displacement do not move and are copied without the warp arithmetic (skip
        // "zero-displacement-runs"); the generic kernels count them, the fast kernels copy without counting.
        const bool copies = opt.copy_still_runs && opt.filter == Filter::point;
        const long long still = copies ? count_still_texels(relief, opt.exact) : 0;
        nlohmann::json skips = nlohmann::json::array();
        // (The Highway kernels draw such spans like any other: no skip on avx2, sse4, neon, sve.)
        if (still > 0 && (stats.isa == Isa::generic || stats.isa == Isa::avx512))
            skips.push_back("zero-displacement-runs");
        static const char* sides[] = {"front", "on_plane", "behind"};
        nlohmann::json j = {
            {"command", "prewarp"},
            {"relief", a.relief},
            {"method", a.method},
            {"exact", a.exact},
            {"filter", a.filter},
            {"isa", isa_name(stats.isa)},
            {"prewarp_ms", timing_json(times)},
            {"texels", stats.texels},
            {"dropped_texels", stats.dropped},
            {"width", relief.width},
            {"height", relief.height},
            {"level", level},
            {"skips", skips},
            {"still_texels", still},
            {"still_copied", stats.still_copied},
            {"eye", {eye.x, eye.y, eye.z}},
            {"k", {k.k1, k.k2, k.k3}},
            {"epipole", {k.epipole_u, k.epipole_v}},
            {"side", sides[int(k.side)]},
        };
        write_json(a.json, j);
    }
}

}  // namespace

void add_prewarp_command(CLI::App& app) {
    auto a = std::make_shared<PrewarpArgs>();
    CLI::App* sub = app.add_subcommand("prewarp", "Pre-warp a relief texture for one centre of projection");
    sub->add_option("--relief", a->relief, "Relief texture manifest (NAME.relief.json)")->required();
    sub->add_option("--eye", a->eye, "Centre of projection X,Y,Z")->required();
    sub->add_option("--out", a->out, "Output image (the pre-warped texture)")->required();
    sub->add_option("--method", a->method, "two-pass or pipelined")->capture_default_str();
    sub->add_flag("--exact", a->exact, "Unquantized displacement, double-precision coordinates");
    sub->add_option("--filter", a->filter, "point or coverage (Fant-style, two-pass only)")->capture_default_str();
    sub->add_option("--level", a->level, "Relief texture pyramid level N or auto")->capture_default_str();
    sub->add_option("--repeat", a->repeat, "Run N times after one warm-up, for timing")->capture_default_str();
    sub->add_option("--threads", a->threads, "Threads (0 = all)")->capture_default_str();
    sub->add_option("--isa", a->isa, "SIMD target: auto, avx512, avx2, sse4, neon, sve or generic (the reference "
                                     "kernels); auto follows RTM_ISA, else the fastest")
        ->capture_default_str();
    sub->add_option("--json", a->json, "Write figures as JSON");
    sub->callback([a] { run_prewarp(*a); });
}

}  // namespace rtm::cli
