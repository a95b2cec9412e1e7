#include "cmd_render_scene.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include <unistd.h>

#include "formats/image_io.h"
#include "objects/scene.h"
#include "texmap/gl_context.h"
#include "warp/timing.h"

namespace rtm::cli {

namespace {

nlohmann::json report_json(const SceneFrameReport& r) {
    std::map<std::string, int> by_level;  // drawn quads per pyramid level
    for (size_t q = 0; q < r.quad_levels.size(); ++q) {
        bool hidden = false;
        for (const std::string& s : r.quad_skips[q]) hidden |= s == kSkipBackFacing || s == kSkipOutsideFrustum;
        if (!hidden) ++by_level[std::to_string(r.quad_levels[q])];
    }
    return {{"quads", r.quads},
            {"quads_drawn", r.drawn},
            {"quads_prewarped", r.prewarped},
            {"quads_skipped", r.skips},
            {"texels_warped", r.texels_warped},
            {"micromesh_triangles", r.micromesh_triangles},
            {"object_faces_drawn", r.object_faces_drawn},
            {"object_faces_prewarped", r.object_faces_prewarped},
            {"object_faces_skipped", r.object_face_skips},
            {"object_texels_warped", r.object_texels_warped},
            {"quads_by_level", by_level},
            {"prewarp_ms", r.times.prewarp_ms},
            {"upload_ms", r.times.upload_ms},
            {"texture_map_ms", r.times.texture_map_ms},
            {"total_ms", r.times.total_ms}};
}

}  // namespace

void run_render_scene(const SceneRenderArgs& a) {
    const RenderMethod method = [&] {
        try {
            return parse_render_method(a.method);
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string("--method: ") + e.what());
        }
    }();
    if (method == RenderMethod::raycast)
        throw UsageError("--method raycast traces one relief, not a scene: use micromesh as the scene's truth");
    const Filter filter = parse_filter(a.filter, method == RenderMethod::pipelined ? Reconstruction::pipelined
                                                                                   : Reconstruction::two_pass);
    if (a.repeat > 1 && !a.frames_dir.empty())
        throw UsageError("--repeat times one camera's frame; --frames renders each frame of the path once");
    if (!a.frames_dir.empty() && !a.out.empty())
        throw UsageError("--out writes one image; --frames writes every frame of the path into its folder");
    // The scene's camera or path gives eye, look-at, up and field of view; CAMERA flags other than --size need
    // --eye or --orbit to take the place of all of them.
    if (!a.camera.has_eye() && !a.camera.view_flag.empty())
        throw UsageError(a.camera.view_flag + " needs --eye or --orbit with --scene: the scene's camera" +
                         (a.path_frame >= 0 || !a.frames_dir.empty() ? " path" : "") + " gives the view");
    if (!a.frames_dir.empty() && (a.camera.has_eye() || a.path_frame >= 0))
        throw UsageError("--frames renders the scene's camera path: give no CAMERA and no --camera-path");
    if (a.camera.has_eye() && a.path_frame >= 0) throw UsageError("give either a CAMERA or --camera-path, not both");
    if (a.frames_dir.empty() && a.out.empty() && a.json.empty())
        throw UsageError("render --scene needs --out or --json");
    if (a.camera.has_eye()) (void)a.camera.resolve(Bounds{glm::dvec3(-1), glm::dvec3(1)});  // syntax, before reading
    if (!a.json.empty()) check_output_file(a.json, "--json");
    const int level = parse_level(a.level);

    // Which camera is known from the manifest alone: a scene without one is refused before its items are loaded.
    if (!a.camera.has_eye() && a.frames_dir.empty() && a.path_frame < 0 && !parse_scene_manifest(a.scene).camera)
        throw UsageError(a.scene + " has no default camera: give --eye X,Y,Z or --orbit AZ,EL,D or --camera-path K");
    Scene scene = Scene::load(a.scene);
    const SceneManifest& m = scene.manifest();
    const Bounds bounds = scene.bounds();
    // The CAMERA flags resolved on the scene's bounds when given; otherwise only the image size is taken from them
    // (the scene's camera or path gives the rest; a stand-in orbit here was blamed for what it could not reach).
    Camera sized;
    if (a.camera.has_eye())
        sized = a.camera.resolve(bounds);
    else
        parse_size(a.camera.size, "--size", sized.width, sized.height);

    std::vector<Camera> cams;
    if (!a.frames_dir.empty() || a.path_frame >= 0) {
        if (m.path_keys.empty()) throw IoError(a.scene + ": the scene has no camera_path");
        if (a.path_frame >= m.path_frames)
            throw UsageError("--camera-path: frame " + std::to_string(a.path_frame) + " is outside the path's 0.." +
                             std::to_string(m.path_frames - 1));
        for (int k = a.path_frame >= 0 ? a.path_frame : 0; k < (a.path_frame >= 0 ? a.path_frame + 1 : m.path_frames);
             ++k)
            cams.push_back(key_camera(camera_path_frame(m.path_keys, k, m.path_frames), sized));
    } else if (a.camera.has_eye()) {
        cams.push_back(sized);
    } else if (m.camera) {
        cams.push_back(key_camera(*m.camera, sized));
    } else {
        throw UsageError(a.scene + " has no default camera: give --eye X,Y,Z or --orbit AZ,EL,D or --camera-path K");
    }
    const bool path = !a.frames_dir.empty() || a.path_frame >= 0;
    for (size_t k = 0; k < cams.size(); ++k) {
        if (const std::string why = cams[k].validate(); !why.empty())
            throw IoError(a.scene + ": camera" +
                          (path ? " of path frame " + std::to_string(a.path_frame >= 0 ? size_t(a.path_frame) : k)
                                : std::string()) +
                          ": " + why);
        cams[k].fit_clip_planes(bounds.centre(), bounds.radius());
    }
    if (!a.frames_dir.empty()) {  // the folder made and its first frame's name probed before any frame is drawn
        make_output_folder(a.frames_dir, "--frames");
        check_output_file((std::filesystem::path(a.frames_dir) / "frame_0000.png").string(), "--frames");
    }

    PrewarpOptions opt;
    opt.keep_outliers = !a.no_sidewalls;
    opt.threads = a.threads;
    opt.exact = a.exact;
    opt.filter = filter;
    DrawOptions draw;
    draw.depth_correction = true;  // reliefs and polygons occlude each other where their perceived surfaces do
    draw.skips = !a.no_skips;
    draw.level = level;
    auto ctx = GlContext::create_offscreen(sized.width, sized.height, {.pin_llvmpipe_threads = true});
    Renderer renderer;
    nlohmann::json frames = nlohmann::json::array();
    std::vector<double> t_pre, t_up, t_map, t_total;
    const bool progress = cams.size() > 1 && isatty(2);
    // With --repeat N (one camera: --frames refuses it), one warm-up frame and then N timed ones, each in `frames`, as
    // render --relief times them; --out holds the last.
    const int warm = a.repeat > 1 ? 1 : 0;
    const size_t total = cams.size() * size_t(a.repeat + warm);
    for (size_t k = 0; k < total; ++k) {
        const Camera& cam = cams[k % cams.size()];
        SceneFrameReport rep;
        scene.draw(renderer, cam, method, opt, draw, rep);
        if (int(k) < warm) continue;
        t_pre.push_back(rep.times.prewarp_ms);
        t_up.push_back(rep.times.upload_ms);
        t_map.push_back(rep.times.texture_map_ms);
        t_total.push_back(rep.times.total_ms);
        if (!a.frames_dir.empty()) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04zu.png", k);
            write_rgba8((std::filesystem::path(a.frames_dir) / name).string(),
                        renderer.read_pixels(sized.width, sized.height));
        } else if (!a.out.empty() && k + 1 == total) {
            write_rgba8(a.out, renderer.read_pixels(sized.width, sized.height));
        }
        nlohmann::json f = report_json(rep);
        f["eye"] = {cam.eye.x, cam.eye.y, cam.eye.z};
        frames.push_back(f);
        if (progress) std::fprintf(stderr, "\rrender: frame %zu of %zu", k + 1, cams.size());
    }
    if (progress) std::fprintf(stderr, "\n");
    if (!a.json.empty()) {
        nlohmann::json j = {{"command", "render"},
                            {"scene", a.scene},
                            {"method", a.method},
                            {"size", {sized.width, sized.height}},
                            {"frames", frames}};
        if (cams.size() == 1)  // one camera's counts also at the top level (its last frame's, with --repeat)
            for (const char* k : {"quads", "quads_drawn", "quads_prewarped", "quads_skipped", "texels_warped",
                                  "micromesh_triangles", "object_faces_drawn", "object_faces_prewarped",
                                  "object_faces_skipped", "object_texels_warped", "quads_by_level"})
                j[k] = frames.back()[k];
        // Stage times over the frames (min, median, ...), as rtm render writes them for a relief.
        j["prewarp_ms"] = timing_json(t_pre);
        j["upload_ms"] = timing_json(t_up);
        j["texture_map_ms"] = timing_json(t_map);
        j["total_ms"] = timing_json(t_total);
        write_json(a.json, j);
    }
}

}  // namespace rtm::cli
