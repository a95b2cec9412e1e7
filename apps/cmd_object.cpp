// rtm render --object / rtm prewarp --object (apps/cmd_object.h).
#include "cmd_object.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "formats/image_io.h"
#include "formats/object_manifest.h"
#include "objects/relief_object.h"
#include "texmap/camera_rig.h"
#include "texmap/gl_context.h"

namespace rtm::cli {

namespace {

nlohmann::json face_keys(const std::vector<int>& faces) {
    nlohmann::json j = nlohmann::json::array();
    for (int f : faces) j.push_back(kFaceKeys[size_t(f)]);
    return j;
}

}  // namespace

std::string face_output_path(const std::string& out, const std::string& face_key) {
    const std::filesystem::path p(out);
    return (p.parent_path() / (p.stem().string() + "_" + face_key + p.extension().string())).string();
}

void run_render_object(const ObjectRenderArgs& a) {
    RenderMethod method;
    try {
        method = parse_render_method(a.method);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--method: ") + e.what());
    }
    if (method != RenderMethod::flat && method != RenderMethod::two_pass && method != RenderMethod::pipelined &&
        method != RenderMethod::micromesh)
        throw UsageError("--method: " + a.method +
                         " is not available for --object; known: flat, two-pass, pipelined, micromesh");
    const Filter filter = parse_filter(a.filter, method == RenderMethod::pipelined ? Reconstruction::pipelined
                                                                                   : Reconstruction::two_pass);
    const int level = parse_level(a.level);
    if (a.repeat < 1) throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    if (!a.camera.has_eye()) throw UsageError("render needs --eye X,Y,Z or --orbit AZ,EL,D");
    (void)a.camera.resolve(Bounds{glm::dvec3(-1), glm::dvec3(1)});
    if (a.out.empty() && a.json.empty()) throw UsageError("render --object needs --out or --json");
    if (!a.out.empty()) check_output_file(a.out, "--out");
    if (!a.json.empty()) check_output_file(a.json, "--json");

    SixFaceObject loaded = load_object(a.object);
    if (a.discontinuity >= 0)
        for (ReliefTexture& t : loaded.faces) mark_discontinuities(t, a.discontinuity);
    ReliefObject object(std::move(loaded));
    const Camera cam = a.camera.resolve(object.bounds());
    PrewarpOptions opt;
    opt.exact = a.exact;
    opt.filter = filter;
    opt.threads = a.threads;
    DrawOptions draw;
    draw.depth_correction = a.depth_correction;
    draw.skips = !a.no_skips;
    draw.level = level;

    auto ctx = GlContext::create_offscreen(cam.width, cam.height);
    Renderer renderer;
    std::vector<double> t_pre, t_up, t_map, t_total;
    std::array<std::vector<double>, kFaceCount> t_face;
    ObjectReport rep;
    std::vector<std::string> skips;
    ImageRGBA8 image;
    const int warm = a.repeat > 1 ? 1 : 0;
    for (int i = 0; i < a.repeat + warm; ++i) {
        StageTimes st;
        image = render_object_frame(object, renderer, cam, method, opt, draw, st, &rep);
        for (const std::string& s : rep.skips)
            if (std::find(skips.begin(), skips.end(), s) == skips.end()) skips.push_back(s);
        if (i < warm) continue;
        t_pre.push_back(st.prewarp_ms);
        t_up.push_back(st.upload_ms);
        t_map.push_back(st.texture_map_ms);
        t_total.push_back(st.total_ms);
        for (const ObjectFaceReport& fr : rep.faces) t_face[size_t(fr.face)].push_back(fr.prewarp_ms);
    }
    if (!a.out.empty()) write_rgba8(a.out, image);
    if (!a.json.empty()) {
        nlohmann::json faces = nlohmann::json::array();
        std::vector<int> drawn;
        for (const ObjectFaceReport& fr : rep.faces) {
            drawn.push_back(fr.face);
            faces.push_back({{"face", kFaceKeys[size_t(fr.face)]},
                             {"level", fr.level},
                             {"adjacent", face_keys(fr.adjacent)},
                             {"prewarp_ms", timing_json(t_face[size_t(fr.face)])},
                             {"skips", fr.skips}});
        }
        nlohmann::json j = {
            {"command", "render"},
            {"object", a.object},
            {"method", a.method},
            {"exact", a.exact},
            {"filter", a.filter},
            {"region", rep.region.index()},
            {"visible_faces", face_keys(rep.region.visible_faces())},
            {"faces_drawn", face_keys(drawn)},
            {"faces", faces},
            {"prewarp_ms", timing_json(t_pre)},
            {"upload_ms", timing_json(t_up)},
            {"texture_map_ms", timing_json(t_map)},
            {"total_ms", timing_json(t_total)},
            {"texels", object.texels()},
            {"level", rep.faces.empty() ? 0 : rep.faces.front().level},
            {"skips", skips},
            {"eye", {cam.eye.x, cam.eye.y, cam.eye.z}},
            {"size", {cam.width, cam.height}},
        };
        write_json(a.json, j);
    }
}

void run_prewarp_object(const ObjectPrewarpArgs& a) {
    const glm::dvec3 eye = parse_vec3(a.eye, "--eye");
    PrewarpOptions opt;
    if (a.method == "two-pass")
        opt.method = Reconstruction::two_pass;
    else if (a.method == "pipelined")
        opt.method = Reconstruction::pipelined;
    else
        throw UsageError("--method: unknown method \"" + a.method + "\" for prewarp; known: two-pass, pipelined");
    int level = parse_level(a.level);
    if (a.repeat < 1) throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    opt.exact = a.exact;
    opt.threads = a.threads;
    opt.filter = parse_filter(a.filter, opt.method);
    opt.isa = parse_isa_arg(a.isa, "--isa");
    check_output_file(a.out, "--out");

    ReliefObject object(load_object(a.object));
    const ObjectRegion region = object.region(eye);
    if (region.inside())
        throw std::runtime_error("--eye " + a.eye + " is inside the object's box " + object.box().to_string() +
                                 ": no face can be pre-warped for it");
    nlohmann::json faces = nlohmann::json::array();
    std::vector<std::pair<std::string, ImageRGBA8>> outputs;
    std::vector<double> totals(size_t(a.repeat), 0.0);  // per repeat, over the visible faces
    int first_level = -1;
    Isa ran = Isa::automatic;  // the target the first visible face's pre-warp ran on
    // auto: per face, the level `render --object --level auto` draws from this eye at its default camera (512x512,
    // 45 degrees, towards the box's centre): the relief quad's parallax-bounded choice on the face's texture
    // (objects/level_choice.h, as plan_object_face makes it).
    Camera auto_cam = aimed_camera(eye, object.bounds().centre(), 512, 512);
    if (!auto_cam.validate().empty()) auto_cam.up = {0, 0, -1};  // looking straight up or down
    auto_cam.fit_clip_planes(object.bounds().centre(), std::max(object.bounds().radius(), 1e-12));
    for (int f : region.visible_faces()) {
        const int lvl = level >= 0 ? level : object.face(f).choose_level(auto_cam, DrawOptions{}.level_error_px);
        ObjectFacePrewarp w;
        object.prewarp_face(f, eye, lvl, opt, false, w);  // warm-up (and the only run when repeat == 1)
        std::vector<double> times;
        for (int i = 0; i < a.repeat; ++i) {
            object.prewarp_face(f, eye, lvl, opt, false, w);
            times.push_back(w.prewarp_ms);
            totals[size_t(i)] += w.prewarp_ms;
        }
        if (first_level < 0) first_level = w.level, ran = w.isa;
        const std::string path = face_output_path(a.out, kFaceKeys[size_t(f)]);
        faces.push_back({{"face", kFaceKeys[size_t(f)]},
                         {"out", path},
                         {"level", w.level},
                         {"width", w.image.width},
                         {"height", w.image.height},
                         {"adjacent", face_keys(w.adjacent)},
                         {"adjacent_pixels", w.adjacent_pixels},
                         {"crack_pixels", w.crack_pixels},
                         {"texels", w.texels},
                         {"isa", isa_name(w.isa)},
                         {"prewarp_ms", timing_json(times)}});
        outputs.emplace_back(path, std::move(w.image));
    }
    if (ran != Isa::automatic) warn_isa_not_run(a.isa, ran, opt);  // the faces' pre-warps run alike
    for (const auto& [path, img] : outputs) write_rgba8(path, img);
    if (!a.json.empty()) {
        std::vector<int> back;
        for (int f = 0; f < kFaceCount; ++f)
            if (!region.visible(f)) back.push_back(f);
        nlohmann::json j = {
            {"command", "prewarp"},
            {"object", a.object},
            {"method", a.method},
            {"exact", a.exact},
            {"filter", a.filter},
            {"isa", ran == Isa::automatic ? "" : isa_name(ran)},
            {"eye", {eye.x, eye.y, eye.z}},
            {"region", region.index()},
            {"faces", faces},
            {"prewarp_ms", timing_json(totals)},
            {"level", first_level},
            {"skips", back.empty() ? nlohmann::json::array() : nlohmann::json::array({kSkipBackFacing})},
            {"back_facing", face_keys(back)},
            {"texels", object.texels()},
        };
        write_json(a.json, j);
    }
}

}  // namespace rtm::cli
