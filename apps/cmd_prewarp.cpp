// rtm prewarp: writes the pre-warped texture itself (paper Figure 9c).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "cli_common.h"
#include "cmd_object.h"
#include "objects/bounds.h"
#include "formats/relief_manifest.h"
#include "objects/relief_quad.h"
#include "objects/render_method.h"
#include "formats/image_io.h"
#include "texmap/camera_rig.h"
#include "warp/prewarp.h"

namespace rtm::cli {

namespace {

struct PrewarpArgs {
    std::string relief, object, eye, out, method = "two-pass", level = "0", json, filter = "point", isa = "auto";
    bool exact = false;
    int repeat = 1, threads = 0, output_scale = 1;
};

void run_prewarp(const PrewarpArgs& a) {
    if (a.relief.empty() == a.object.empty())
        throw UsageError("prewarp needs exactly one of --relief M and --object O");
    if (!a.object.empty() && a.output_scale != 1) throw UsageError("--output-scale applies to --relief only");
    // Both outputs checked before any work: a failure leaves neither (docs/FORMATS.md, "Exit status and errors").
    if (!a.json.empty()) check_output_file(a.json, "--json");
    if (!a.object.empty())
        return run_prewarp_object({a.object, a.eye, a.out, a.method, a.level, a.json, a.filter, a.exact, a.repeat,
                                   a.threads, a.isa});
    check_output_file(a.out, "--out");
    const glm::dvec3 eye = parse_vec3(a.eye, "--eye");
    check_coordinates(eye, "--eye: ");
    PrewarpOptions opt;
    try {
        opt.method = parse_reconstruction(a.method);
    } catch (const std::invalid_argument&) {
        throw UsageError("--method: unknown method \"" + a.method +
                         "\" for prewarp; known: " + reconstruction_names_list());
    }
    const int level_arg = parse_level(a.level);
    if (a.repeat < 1) throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    opt.exact = a.exact;
    opt.threads = a.threads;
    opt.filter = parse_filter(a.filter, opt.method);
    opt.isa = parse_isa_arg(a.isa, "--isa");

    if (a.output_scale < 1 || a.output_scale > 8)
        throw UsageError("--output-scale: expected a factor from 1 to 8, found " + std::to_string(a.output_scale));
    ReliefQuad quad(apply_output_scale(load_relief(a.relief), a.output_scale, a.relief));
    int level = level_arg;
    if (level < 0) {  // auto: the level `render` draws for a 512x512, 45-degree view from the eye to the centre
        Camera cam = aimed_camera(eye, relief_bounds(quad.relief()).centre(), 512, 512);
        if (!cam.validate().empty()) cam = aimed_camera(eye, eye - quad.relief().geometry.f(), 512, 512);
        level = quad.choose_level(cam, DrawOptions{}.level_error_px);
    }
    level = std::min(level, quad.levels() - 1);
    const ReliefTexture& relief = quad.level(level);
    const PrewarpCoefficients k = compute_coefficients(relief.geometry, eye);
    if (k.side == ViewSide::on_plane)
        std::fprintf(stderr,
                     "rtm: warning: --eye %s is in the relief's plane: the relief is seen edge-on, and the "
                     "pre-warped texture is empty\n",
                     a.eye.c_str());
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    PrewarpStats stats = prewarp(relief, k, opt, ws, out);  // warm-up (and the only run when repeat == 1)
    std::vector<double> times;
    for (int i = 0; i < a.repeat; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        stats = prewarp(relief, k, opt, ws, out);
        times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    warn_isa_not_run(a.isa, stats.isa, opt);
    write_rgba8(a.out, out);
    if (!a.json.empty()) {
        // Texels at zero displacement do not move and are copied without the warp arithmetic: the skip
        // "zero-displacement-runs", by the rule ReliefQuad::draw reports it with (objects/frame_plan.h).
        const long long all_still = opt.copy_still_runs ? count_still_texels(relief, opt.exact) : 0;
        const bool fired = zero_runs_fired(stats, all_still);
        const long long still = fired ? all_still : 0;
        nlohmann::json skips = nlohmann::json::array();
        if (fired) skips.push_back(kSkipZeroRuns);
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
            {"output_scale", a.output_scale},
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
    sub->add_option("--relief", a->relief, "Relief texture manifest (NAME.relief.json)");
    sub->add_option("--object", a->object,
                    "Six-face object manifest (NAME.object.json): writes OUT_+x.png ... per visible face");
    sub->add_option("--eye", a->eye, "Centre of projection X,Y,Z")->required();
    sub->add_option("--out", a->out, "Output image (the pre-warped texture)")->required();
    sub->add_option("--method", a->method, "two-pass or pipelined")->capture_default_str();
    sub->add_flag("--exact", a->exact, "Unquantized displacement, double-precision coordinates");
    sub->add_option("--filter", a->filter, "point or coverage (Fant-style, two-pass only)")->capture_default_str();
    sub->add_option("--level", a->level, "Relief texture pyramid level N or auto")->capture_default_str();
    sub->add_option("--output-scale", a->output_scale,
                    "Pre-warp into a texture N times the relief's size in each direction (1 to 8; --relief only)")
        ->check(whole_number())
        ->capture_default_str();
    sub->add_option("--repeat", a->repeat, "Run N times after one warm-up, for timing")
        ->check(whole_number())
        ->capture_default_str();
    add_threads_option(*sub, a->threads);
    sub->add_option("--isa", a->isa,
                    "SIMD target: auto, avx512, avx3, avx2, sse4, neon, sve or generic (the reference "
                    "kernels); auto follows RTM_ISA, else the fastest")
        ->capture_default_str();
    sub->add_option("--json", a->json, "Write figures as JSON");
    sub->callback([a] { run_prewarp(*a); });
}

}  // namespace rtm::cli
