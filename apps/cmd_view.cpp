// rtm view: the interactive viewer (viewer/viewer_app.h; keys in viewer/keys.h, guide in docs/VIEWER.md). This file
// only parses the command line: what to open, the camera, the settings, and the scripted options for tests
// (--frames N --screenshot IMG, --keys, --camera-path, --json).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "cli_common.h"
#include "formats/image_io.h"
#include "objects/scene.h"
#include "viewer/keys.h"
#include "viewer/open_file.h"
#include "viewer/viewer_app.h"

namespace rtm::cli {

namespace {

struct ViewArgs {
    std::string relief, object, scene, file, screenshot, json, camera_path, keys, method = "two-pass", level, split,
                                                                                  filter = "point";
    PerPixelArgs perpixel;
    CameraArgs camera;
    int frames = 0, threads = 0, timed_every = 16;
    double panel_refresh_ms = 100, content_scale = 0;
    bool panel = false, insets = false, outlines = false, fly = false, no_sidewalls = false, depth_correction = false,
         no_skips = false, no_vsync = false;
    double discontinuity = -1;
};

// One warning line for each flag given that what is shown does not use at the start ("rtm: warning: FLAG WHY"); the
// panel and the keys can change method and toggles later, so these are warnings, not errors.
void warn_view_unused(const ViewArgs& a, const std::string& kind, RenderMethod method, bool own_camera) {
    auto warn = [](bool given, const char* flag, const std::string& why) {
        if (given) std::fprintf(stderr, "rtm: warning: %s %s\n", flag, why.c_str());
    };
    if (kind == "scene") {
        warn(a.depth_correction, "--depth-correction", "is always on in a scene");
        warn(a.discontinuity >= 0, "--discontinuity",
             "applies to reliefs and objects; a scene's reliefs take theirs from their manifests");
        warn(method == RenderMethod::raycast, "--method raycast", "traces one relief, not a scene: nothing is drawn");
        warn(own_camera && !a.camera.has_eye() && !a.camera.view_flag.empty(), a.camera.view_flag.c_str(),
             "without --eye or --orbit: a scene starts at its own camera, which gives the view");
    }
    if (kind == "object") {
        warn(a.no_sidewalls, "--no-sidewalls", "applies to relief quads; a six-face object has no side polygons");
        warn(perpixel_method(method).has_value() || method == RenderMethod::raycast, ("--method " + a.method).c_str(),
             "draws single reliefs; an object is drawn by flat, two-pass, pipelined or micromesh: nothing is drawn");
    }
    if (kind == "mesh")
        for (const auto& [given, flag] : {std::pair{a.no_sidewalls, "--no-sidewalls"},
                                          {a.depth_correction, "--depth-correction"},
                                          {a.discontinuity >= 0, "--discontinuity"},
                                          {!a.level.empty(), "--level"},
                                          {a.no_skips, "--no-skips"},
                                          {a.filter != "point", "--filter"}})
            warn(given, flag, "applies to reliefs; a mesh is drawn as it is");
    for (const auto& [given, flag] : {std::pair{!a.perpixel.curved_base.empty(), "--curved-base"},
                                      {!a.perpixel.quadric_distance.empty(), "--quadric-distance"}})
        warn(given && (kind != "relief" || method != RenderMethod::quadric_silhouettes), flag,
             "applies to a relief with --method quadric-silhouettes");
    warn(!a.perpixel.steep_texture.empty() && (kind != "relief" || method != RenderMethod::protruded_displacement),
         "--steep-texture", "applies to a relief with --method protruded-displacement");
}

void run_view(const ViewArgs& a) {
    check_isa_environment();
    const int given = int(!a.relief.empty()) + int(!a.object.empty()) + int(!a.scene.empty()) + int(!a.file.empty());
    if (given != 1) throw UsageError("view needs one of --relief M, --object O, --scene S or a FILE");
    if (a.frames < 0) throw UsageError("--frames: expected N >= 0, found " + std::to_string(a.frames));
    if (!a.screenshot.empty() && a.frames == 0) throw UsageError("--screenshot needs --frames N");
    if (!a.json.empty() && a.frames == 0) throw UsageError("--json needs --frames N");
    if (a.timed_every < 1) throw UsageError("--timed-every: expected N >= 1, found " + std::to_string(a.timed_every));
    auto number = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", v);
        return std::string(buf);
    };
    if (!(a.panel_refresh_ms >= 0))
        throw UsageError("--panel-refresh-ms: expected a time >= 0, found " + number(a.panel_refresh_ms));
    viewer::ViewerOptions o;
    viewer::ViewSettings& s = o.settings;
    try {
        s.method = parse_render_method(a.method);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--method: ") + e.what());
    }
    // --level: 0 unless given, auto for a scene (as rtm render --scene; set once the file's kind is known).
    if (!a.level.empty()) s.level = parse_level(a.level);
    s.coverage = parse_filter(a.filter, s.method == RenderMethod::pipelined
                                            ? Reconstruction::pipelined
                                            : Reconstruction::two_pass) == Filter::coverage;
    if (!a.split.empty()) {
        try {
            viewer::parse_split(a.split, s);
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string("--split: ") + e.what());
        }
    }
    try {
        o.keys = viewer::parse_key_script(a.keys);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--keys: ") + e.what());
    }
    s.perpixel = a.perpixel.settings();
    s.threads = a.threads;
    s.discontinuity = a.discontinuity;
    s.panel = a.panel;
    s.insets = a.insets;
    s.outlines = a.outlines;
    s.side_polygons = !a.no_sidewalls;
    s.depth_correction = a.depth_correction;
    s.skips = !a.no_skips;
    s.vsync = !a.no_vsync;
    // The camera's syntax before any file is read (the default camera: --orbit 30,20,2.2).
    CameraArgs ca = a.camera;
    if (!ca.has_eye()) ca.orbit = "30,20,2.2";
    (void)ca.resolve(Bounds{glm::dvec3(-1), glm::dvec3(1)});
    if (!a.json.empty()) check_output_file(a.json, "--json");
    if (!a.screenshot.empty()) check_output_file(a.screenshot, "--screenshot");

    const std::string file = !a.relief.empty()   ? a.relief
                             : !a.object.empty() ? a.object
                             : !a.scene.empty()  ? a.scene
                                                 : a.file;
    if (!a.relief.empty() && a.relief.find(".relief.json") == std::string::npos)
        throw IoError(a.relief + ": --relief expects NAME.relief.json");
    if (!a.object.empty() && a.object.find(".object.json") == std::string::npos)
        throw IoError(a.object + ": --object expects NAME.object.json");
    if (!a.scene.empty() && a.scene.find(".scene.json") == std::string::npos)
        throw IoError(a.scene + ": --scene expects NAME.scene.json");
    std::unique_ptr<viewer::Loaded> loaded = viewer::open_file(file);
    if (const std::optional<ImageRGBA8> steep = a.perpixel.steep_image()) loaded->set_steep_texture(*steep);
    const std::string kind = loaded->kind();
    if (kind == "scene" && a.level.empty()) s.level = -1;
    warn_view_unused(a, kind, s.method, loaded->own_camera().has_value());
    o.camera = ca.resolve(loaded->bounds());
    // A scene without a CAMERA starts at its own camera, as rtm render --scene does.
    const std::optional<SceneCameraKey> own = loaded->own_camera();
    const bool own_start = !a.camera.has_eye() && own.has_value();
    if (own_start) o.camera = key_camera(*own, o.camera);
    // --camera-path given the scene itself plays the scene's own path.
    if (a.camera_path == file) {
        if (!loaded->own_camera_path()) throw IoError(file + ": has no camera_path for --camera-path");
        o.own_camera_path = true;
    } else {
        o.camera_path = a.camera_path;
    }
    if (!ca.orbit.empty() && !ca.look_at.empty()) {
        // --orbit with --look-at: render's view (the eye about the centre), orbiting the point looked at.
        o.orbit = viewer::orbit_about(o.camera.look_at, o.camera.eye, loaded->bounds());
    } else if (!ca.orbit.empty()) {
        const glm::dvec3 v = parse_vec3(ca.orbit, "--orbit");
        o.orbit = {v.x, v.y, v.z};
    }
    o.start_fly = !ca.eye.empty() || a.fly || own_start;
    if (a.fly && ca.eye.empty()) o.camera.eye = o.orbit.eye(loaded->bounds());
    o.frames = a.frames;
    o.timed_every = a.timed_every;
    o.panel_refresh_ms = a.panel_refresh_ms;
    o.content_scale = float(a.content_scale);
    o.screenshot = a.screenshot;

    const viewer::ViewerResult r = viewer::run_viewer(std::move(loaded), o);
    if (!a.json.empty()) {
        auto ll = [](const std::vector<long long>& v) {
            std::vector<double> d(v.begin(), v.end());
            return timing_json(d);
        };
        nlohmann::json j = {
            {"command", "view"},
            {"file", file},
            {"method", a.method},
            {"frames", r.frames},
            {"fps", r.fps},
            {"frame_ms", timing_json(r.frame_ms)},
            {"prewarp_ms", timing_json(r.prewarp_ms)},
            {"upload_ms", timing_json(r.upload_ms)},
            {"texture_map_ms", timing_json(r.texture_map_ms)},
            {"other_ms", timing_json(r.other_ms)},
            {"overlay_ms", timing_json(r.overlay_ms)},
            {"swap_ms", timing_json(r.swap_ms)},
            {"texels_warped", ll(r.texels_warped)},
            {"panel_renders", r.panel_renders},
            {"panel_blits", r.panel_blits},
            {"panel", {r.panel.x, r.panel.y, r.panel.z, r.panel.w}},
            {"insets", {r.insets.x, r.insets.y, r.insets.z, r.insets.w}},
            {"size", {r.width, r.height}},
            {"renderer", r.renderer},
        };
        write_json(a.json, j);
    }
}

}  // namespace

void add_view_command(CLI::App& app) {
    auto a = std::make_shared<ViewArgs>();
    CLI::App* sub = app.add_subcommand("view", "Interactive viewer (GLFW window, Dear ImGui panel)");
    sub->add_option("file", a->file,
                    "A file opened by its kind: NAME.relief.json, NAME.object.json, NAME.scene.json or a mesh");
    sub->add_option("--relief", a->relief, "Relief texture manifest");
    sub->add_option("--object", a->object, "Six-face object manifest");
    sub->add_option("--scene", a->scene, "Scene manifest");
    a->camera.size = "1280x720";
    a->camera.add_to(*sub);
    sub->add_option("--method", a->method, "flat, two-pass, pipelined, micromesh, raycast or a per-pixel method")
        ->capture_default_str();
    sub->add_option("--level", a->level, "Relief texture pyramid level N or auto (default 0; auto for a scene)");
    a->perpixel.add_to(*sub);
    sub->add_option("--filter", a->filter, "Pre-warp resampling: point or coverage (two-pass only)")
        ->capture_default_str();
    add_threads_option(*sub, a->threads, "Pre-warp threads");
    sub->add_option("--discontinuity", a->discontinuity, "Mark discontinuities with this threshold")
        ->check(non_negative_threshold());
    sub->add_flag("--no-sidewalls", a->no_sidewalls, "Do not draw the side polygons");
    sub->add_flag("--depth-correction", a->depth_correction, "Per-fragment depth from the displacement");
    sub->add_flag("--no-skips", a->no_skips, "Always pre-warp and upload everything");
    sub->add_flag("--panel", a->panel, "Show the panel");
    sub->add_flag("--insets", a->insets, "Show the pre-warped textures with their epipoles");
    sub->add_flag("--outlines", a->outlines, "Outline the texture-mapped quads and side polygons");
    sub->add_flag("--fly", a->fly, "Start with the fly camera");
    sub->add_option("--split", a->split, "Split view: the right half with METHOD, or 'truth' (error heat map)");
    sub->add_flag("--no-vsync", a->no_vsync, "Start with vsync off (scripted runs always run without it)");
    sub->add_option("--frames", a->frames, "Render N frames in a hidden window and exit (0 = until closed)")
        ->check(whole_number())
        ->capture_default_str();
    sub->add_option("--timed-every", a->timed_every,
                    "Time the stages (each waiting for the GPU) in 1 frame of N; 1 = every frame")
        ->check(whole_number())
        ->capture_default_str();
    sub->add_option("--panel-refresh-ms", a->panel_refresh_ms,
                    "Render the panel at least every T ms, else copy its last pixels; 0 = every frame")
        ->capture_default_str();
    sub->add_option("--content-scale", a->content_scale,
                    "Scripted: the window's content scale changes to S before the first frame (as on another monitor)")
        ->check(CLI::Validator(  // checked as typed: 0, the default, means "not given" and is refused when typed
            [](std::string& text) -> std::string {
                char* end = nullptr;
                const double v = std::strtod(text.c_str(), &end);
                if (text.empty() || *end != '\0' || !(v >= 0.25 && v <= 8))
                    return "expected a scale in [0.25, 8], found \"" + text + "\"";
                return "";
            },
            "S"));
    sub->add_option("--screenshot", a->screenshot, "Write the last frame to IMG (with --frames)");
    sub->add_option("--camera-path", a->camera_path,
                    "Play a camera path (JSON keyframes, docs/VIEWER.md; the scene's own path given the scene)");
    sub->add_option("--keys", a->keys, "Key presses applied before the first frame, e.g. \"2,G,I\"");
    sub->add_option("--json", a->json, "Write frame times and the panel's rectangle as JSON (with --frames)");
    sub->callback([a] { run_view(*a); });
}

}  // namespace rtm::cli
