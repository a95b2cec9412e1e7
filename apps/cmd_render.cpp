// rtm render: the final view of a relief-textured quad with any method (flat, two-pass, pipelined, and the
// ground truths micromesh and raycast).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <memory>

#include <unistd.h>

#include "cli_common.h"
#include "cmd_object.h"
#include "cmd_render_scene.h"
#include "objects/bounds.h"
#include "objects/render_relief.h"
#include "render_mesh.h"
#include "formats/relief_manifest.h"
#include "objects/relief_quad.h"
#include "perpixel/curved_patch.h"
#include "texmap/gl_context.h"
#include "formats/image_io.h"

namespace rtm::cli {

namespace {

struct RenderArgs {
    std::string relief, object, scene, mesh, frames_dir, out, json, method = "two-pass", level, filter = "point";
    PerPixelArgs perpixel;
    CameraArgs camera;
    bool exact = false, progress = false, no_sidewalls = false, depth_correction = false, no_skips = false;
    bool method_given = false;
    double discontinuity = -1;
    int repeat = 1, threads = 0, path_frame = -1, output_scale = 1;
};

// One warning line for each flag given that what is drawn does not use ("rtm: warning: FLAG WHY").
void warn_unused(std::initializer_list<std::pair<bool, const char*>> flags, const std::string& why) {
    for (const auto& [given, flag] : flags)
        if (given) std::fprintf(stderr, "rtm: warning: %s %s\n", flag, why.c_str());
}

// What each method reads of the relief options, for a relief, an object or a scene: every flag given that `method`
// leaves unused gets a warning line (a scene's depth correction and discontinuities, and a mesh, are said by the
// caller). The pre-warp's flags need two-pass or pipelined; --level a pyramid level of the relief texture, which
// flat texture mapping draws too; --no-skips the skips of those three; --discontinuity a pre-warp or the
// micro-polygons; --progress the ray caster.
void warn_method_unused(const RenderArgs& a, RenderMethod method, Filter filter, bool scene) {
    const bool warps = prewarps(method);
    const bool textured = warps || method == RenderMethod::flat;
    const std::string m = "--method " + a.method;
    if (!warps) {
        warn_unused({{a.exact, "--exact"},
                     {filter != Filter::point, "--filter coverage"},
                     {a.no_sidewalls, "--no-sidewalls"},
                     {a.output_scale != 1, "--output-scale"},
                     {a.depth_correction && !scene, "--depth-correction"}},
                    "applies to the pre-warp, which " + m + " does not do");
    } else if (!a.object.empty()) {
        warn_unused({{a.no_sidewalls, "--no-sidewalls"}},
                    "applies to relief quads; a six-face object has no side polygons");
    }
    if (!textured) {
        warn_unused({{!a.level.empty(), "--level"}},
                    "picks a level of the relief texture, which " + m + " does not draw");
        warn_unused({{a.no_skips, "--no-skips"}},
                    "turns off relief texture mapping's skips, which " + m + " does not make");
    }
    if (!warps && method != RenderMethod::micromesh && !scene)
        warn_unused({{a.discontinuity >= 0, "--discontinuity"}},
                    "marks surface discontinuities, which " + m + " does not read");
    if (method != RenderMethod::raycast || a.relief.empty())
        warn_unused({{a.progress, "--progress"}}, "shows the ray caster's progress (--relief, --method raycast)");
    if (method != RenderMethod::quadric_silhouettes || a.relief.empty())
        warn_unused({{!a.perpixel.curved_base.empty(), "--curved-base"},
                     {!a.perpixel.quadric_distance.empty(), "--quadric-distance"}},
                    "applies to --relief with --method quadric-silhouettes");
    if (method != RenderMethod::protruded_displacement || a.relief.empty())
        warn_unused({{!a.perpixel.steep_texture.empty(), "--steep-texture"}},
                    "applies to --relief with --method protruded-displacement");
}

void run_render(const RenderArgs& a) {
    check_isa_environment();
    const int inputs = int(!a.relief.empty()) + int(!a.object.empty()) + int(!a.scene.empty()) + int(!a.mesh.empty());
    if (inputs > 1) throw UsageError("render takes one of --relief M, --object O, --scene S and --mesh FILE");
    if (inputs == 0) throw UsageError("render needs --relief M, --object O, --scene S or --mesh FILE");
    if (a.output_scale != 1 && a.relief.empty()) throw UsageError("--output-scale applies to --relief only");
    if ((!a.frames_dir.empty() || a.path_frame >= 0) && a.scene.empty())
        throw UsageError("--frames and --camera-path need --scene");
    // A mesh is drawn conventionally (docs/BAKE.md): `flat` (plain texture mapping) is the only method it has.
    if (!a.mesh.empty() && a.method_given && a.method != "flat")
        throw UsageError("--method " + a.method + ": a mesh is drawn conventionally; --mesh takes only --method flat");
    RenderMethod method;
    try {
        method = parse_render_method(a.method);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--method: ") + e.what());
    }
    const Filter filter = parse_filter(a.filter, method == RenderMethod::pipelined ? Reconstruction::pipelined
                                                                                   : Reconstruction::two_pass);
    if (a.repeat < 1) throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    const PerPixelSettings perpixel = a.perpixel.settings();
    const QuadricSilhouettesSettings& quadric = perpixel.quadric_silhouettes;
    // --level: 0 unless given, auto for a scene (each quad at the level its screen area asks for, no coarser than
    // its parallax allows: objects/level_choice.h; the town's margin over flat holds at auto, docs/SCENES.md).
    const std::string level = !a.level.empty() ? a.level : a.scene.empty() ? "0" : "auto";
    const int level_n = parse_level(level);
    if (!a.mesh.empty()) {
        // What only a relief takes: said once each, not silently ignored.
        warn_unused({{a.exact, "--exact"},
                     {filter != Filter::point, "--filter coverage"},
                     {a.no_sidewalls, "--no-sidewalls"},
                     {a.depth_correction, "--depth-correction"},
                     {a.discontinuity >= 0, "--discontinuity"},
                     {!a.level.empty(), "--level"},
                     {a.no_skips, "--no-skips"},
                     {a.threads != 0, "--threads"},
                     {a.progress, "--progress"}},
                    "applies to reliefs; a mesh is drawn as it is");
        run_render_mesh(a.mesh, a.camera, a.out, a.json, a.repeat);
        return;
    }
    if (!a.object.empty()) {
        warn_method_unused(a, method, filter, false);
        return run_render_object({a.object, a.out, a.json, a.method, level, a.filter, a.camera, a.exact,
                                  a.depth_correction, a.no_skips, a.repeat, a.threads, a.discontinuity});
    }
    if (!a.scene.empty()) {
        SceneRenderArgs s;
        s.scene = a.scene;
        s.out = a.out;
        s.json = a.json;
        s.method = a.method;
        s.frames_dir = a.frames_dir;
        s.level = level;
        s.camera = a.camera;
        s.path_frame = a.path_frame;
        s.filter = a.filter;
        s.exact = a.exact;
        s.no_skips = a.no_skips;
        s.no_sidewalls = a.no_sidewalls;
        s.threads = a.threads;
        s.repeat = a.repeat;
        warn_unused({{a.depth_correction, "--depth-correction"}}, "is always on in a scene");
        warn_unused({{a.discontinuity >= 0, "--discontinuity"}},
                    "applies to --relief and --object; a scene's reliefs take theirs from their manifests");
        warn_method_unused(a, method, filter, true);
        return run_render_scene(s);
    }
    if (!a.camera.has_eye()) throw UsageError("render needs --eye X,Y,Z or --orbit AZ,EL,D");
    // Validate the camera's syntax before any file is read.
    (void)a.camera.resolve(Bounds{glm::dvec3(-1), glm::dvec3(1)});
    // Every output checked before any work: a failure leaves none (docs/FORMATS.md, "Exit status and errors").
    if (a.out.empty() && a.json.empty()) throw UsageError("render needs --out or --json");
    if (!a.out.empty()) check_output_file(a.out, "--out");
    if (!a.json.empty()) check_output_file(a.json, "--json");

    warn_method_unused(a, method, filter, false);
    ReliefTexture relief = load_relief(a.relief);
    if (a.discontinuity >= 0) mark_discontinuities(relief, a.discontinuity);
    // --output-scale resamples the relief for the pre-warp's finer texture; the other methods draw it as it is.
    if (prewarps(method)) relief = apply_output_scale(std::move(relief), a.output_scale, a.relief);
    ReliefQuad quad(std::move(relief));
    if (const std::optional<ImageRGBA8> steep = a.perpixel.steep_image()) quad.perpixel().set_steep_texture(*steep);
    const Camera cam = a.camera.resolve(relief_bounds(quad.relief()));
    PrewarpOptions opt;
    opt.exact = a.exact;
    opt.filter = filter;
    opt.keep_outliers = !a.no_sidewalls;
    opt.threads = a.threads;

    std::vector<double> t_pre, t_up, t_map, t_total;
    std::vector<std::string> skips;
    int used_level = 0;
    long long still_texels = 0, still_copied = 0;  // zero-displacement-runs
    ImageRGBA8 image;
    RenderSettings rs;
    rs.method = method;
    rs.prewarp = opt;
    rs.draw.depth_correction = a.depth_correction;
    rs.draw.skips = !a.no_skips;
    rs.draw.level = level_n;
    rs.perpixel = perpixel;
    if (a.progress || isatty(2))
        rs.progress = [](double f) { std::fprintf(stderr, "\r%s %5.1f%%", "raycast", 100 * f); };
    std::unique_ptr<GlContext> ctx;
    std::unique_ptr<Renderer> renderer;
    if (method != RenderMethod::raycast) {
        ctx = GlContext::create_offscreen(cam.width, cam.height, {.pin_llvmpipe_threads = true});
        renderer = std::make_unique<Renderer>();
    }
    // One warm-up frame when repeating (not for raycast, which is slow and has no state to warm).
    const int warm = a.repeat > 1 && method != RenderMethod::raycast ? 1 : 0;
    for (int i = 0; i < a.repeat + warm; ++i) {
        StageTimes st;
        DrawReport rep;
        image = render_relief_frame(quad, renderer.get(), cam, rs, st, &rep);
        used_level = rep.level;
        if (rep.still_texels > 0) {  // the frame that pre-warped (later frames may reuse it)
            still_texels = rep.still_texels;
            still_copied = rep.still_copied;
        }
        for (const std::string& sk : rep.skips)
            if (std::find(skips.begin(), skips.end(), sk) == skips.end()) skips.push_back(sk);
        if (i < warm) continue;
        t_pre.push_back(st.prewarp_ms);
        t_up.push_back(st.upload_ms);
        t_map.push_back(st.texture_map_ms);
        t_total.push_back(st.total_ms);
    }
    if (method == RenderMethod::raycast && rs.progress) std::fprintf(stderr, "\n");
    if (!a.out.empty()) write_rgba8(a.out, image);
    if (!a.json.empty()) {
        nlohmann::json j = {
            {"command", "render"},
            {"relief", a.relief},
            {"method", a.method},
            {"exact", a.exact},
            {"filter", a.filter},
            {"prewarp_ms", timing_json(t_pre)},
            {"upload_ms", timing_json(t_up)},
            {"texture_map_ms", timing_json(t_map)},
            {"total_ms", timing_json(t_total)},
            {"texels", (long long)quad.relief().width * quad.relief().height},
            {"level", used_level},
            {"output_scale", prewarps(method) ? a.output_scale : 1},
            {"skips", skips},
            // zero-displacement-runs: texels of the level at zero displacement, and how many of them the reference
            // kernels copied (0 when the fast kernels ran: they copy without counting).
            {"still_texels", still_texels},
            {"still_copied", still_copied},
            {"eye", {cam.eye.x, cam.eye.y, cam.eye.z}},
            {"size", {cam.width, cam.height}},
        };
        if (method == RenderMethod::quadric_silhouettes) {
            j["curved_base"] = to_string(quadric.base);
            j["quadric_distance"] = quadric.exact_distance ? "exact" : "approximate";
        }
        if (method == RenderMethod::protruded_displacement)
            j["steep_texture"] = a.perpixel.steep_texture.empty() ? nlohmann::json(nullptr)
                                                                  : nlohmann::json(a.perpixel.steep_texture);
        write_json(a.json, j);
    }
}

}  // namespace

void add_render_command(CLI::App& app) {
    auto a = std::make_shared<RenderArgs>();
    CLI::App* sub = app.add_subcommand("render", "Render a relief texture to an image");
    sub->add_option("--relief", a->relief, "Relief texture manifest (NAME.relief.json)");
    sub->add_option("--object", a->object, "Six-face object manifest (NAME.object.json)");
    sub->add_option("--scene", a->scene, "Scene manifest (NAME.scene.json): relief quads and polygons");
    sub->add_option("--camera-path", a->path_frame, "Scene: render frame K of the scene's camera path")
        ->check(frame_index());
    sub->add_option("--frames", a->frames_dir, "Scene: render every frame of its camera path into DIR");
    sub->add_option("--mesh", a->mesh, "A mesh (any file assimp reads), rendered with conventional OpenGL");
    a->camera.add_to(*sub);
    auto* method =
        sub->add_option(
               "--method", a->method,
               "flat, two-pass, pipelined, micromesh, raycast, or a per-pixel method: parallax, "
               "parallax-offset-limiting, steep-parallax, parallax-occlusion, relief-mapping, interval-mapping, "
               "protruded-displacement, quadric-silhouettes (on a curved patch: --curved-base); --mesh: flat only")
            ->capture_default_str();
    a->perpixel.add_to(*sub);
    sub->add_flag("--exact", a->exact, "Pre-warp with unquantized displacement and double-precision coordinates");
    sub->add_option("--filter", a->filter, "Pre-warp resampling: point or coverage (Fant-style, two-pass only)")
        ->capture_default_str();
    sub->add_option("--level", a->level, "Pyramid level N or auto (default 0, for --scene auto: per quad)");
    sub->add_option("--output-scale", a->output_scale,
                    "Pre-warp into a texture N times the relief's size in each direction (1 to 8; --relief only)")
        ->check(whole_number())
        ->capture_default_str();
    sub->add_option("--out", a->out, "Output image");
    sub->add_option("--json", a->json, "Write stage times as JSON");
    sub->add_option("--repeat", a->repeat, "Render N frames after one warm-up, for timing")
        ->check(whole_number())
        ->capture_default_str();
    add_threads_option(*sub, a->threads);
    sub->add_flag("--progress", a->progress, "Show progress of slow methods");
    sub->add_flag("--no-skips", a->no_skips, "Always pre-warp and upload everything (to measure what skips save)");
    sub->add_flag("--no-sidewalls", a->no_sidewalls, "Drop samples that leave the quad (no side polygons)");
    sub->add_flag("--depth-correction", a->depth_correction, "Per-fragment depth from the perceived displacement");
    sub->add_option("--discontinuity", a->discontinuity,
                    "Depth threshold (world units) marking surface discontinuities; 0 = off; default: the manifest's")
        ->check(non_negative_threshold());
    sub->callback([a, method] {
        a->method_given = method->count() > 0;
        run_render(*a);
    });
}

}  // namespace rtm::cli
