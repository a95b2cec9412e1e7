#include "viewer/loaded_scene.h"

#include <algorithm>
#include <stdexcept>

#include "viewer/drawn_quad.h"
#include "viewer/loaded_relief.h"

namespace rtm::viewer {

LoadedScene::LoadedScene(const std::string& manifest) : path_(manifest), scene_(Scene::load(manifest)) {}

void LoadedScene::draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) {
    if (s.method == RenderMethod::raycast) {  // as rtm render --scene refuses it
        report.note = "raycast traces one relief, not a scene: use micromesh as the scene's truth";
        return;
    }
    RenderSettings rs = render_settings(s);
    rs.draw.depth_correction = true;  // as rtm render --scene: reliefs and polygons occlude each other correctly
    SceneFrameReport rep;
    scene_.draw(renderer, cam, s.method, rs.prewarp, rs.draw, rep, {}, rs.perpixel);
    report.times.prewarp_ms += rep.times.prewarp_ms;
    report.times.upload_ms += rep.times.upload_ms;
    report.times.texture_map_ms += rep.times.texture_map_ms;
    report.times.total_ms += rep.times.total_ms;
    report.texels_warped += rep.texels_warped;
    for (const auto& [k, n] : rep.skips)
        if (n > 0) report.skips.push_back(k);
    if (s.method == RenderMethod::micromesh) return;
    std::vector<ReliefQuad>& quads = scene_.quads();
    for (size_t i = 0; i < quads.size() && i < rep.quad_skips.size(); ++i) {
        const int level = i < rep.quad_levels.size() ? rep.quad_levels[i] : 0;  // the level the frame drew
        DrawnQuad q;
        if (describe_drawn_quad(quads[i], "quad " + std::to_string(i), cam, s, rep.quad_skips[i], level, q))
            report.quads.push_back(std::move(q));
    }
    if (!report.quads.empty()) report.level = report.quads.front().level;
}

std::string LoadedScene::raycast_unavailable() const {
    return "no ray caster for a scene (it traces one height field): its truth is micromesh (4)";
}

ImageRGBA8 LoadedScene::raycast(const Camera&, const ViewSettings&) {
    throw std::logic_error("LoadedScene::raycast: " + raycast_unavailable());
}

std::optional<CameraPath> LoadedScene::own_camera_path() const {
    CameraPath p = scene_camera_path(scene_.manifest());
    if (p.keys.empty()) return std::nullopt;
    return p;
}

CameraPath scene_camera_path(const SceneManifest& m, double fps) {
    CameraPath p;
    p.fps = fps;
    if (m.path_keys.size() < 2 || m.path_frames < 2) return p;
    for (int k = 0; k < m.path_frames; ++k) {
        const SceneCameraKey c = camera_path_frame(m.path_keys, k, m.path_frames);
        PathKey key;
        key.t = k / fps;
        key.eye = c.eye;
        key.look_at = c.look_at;
        key.has_look_at = true;
        key.fov_deg = c.fov_deg;
        p.keys.push_back(key);
    }
    return p;
}

}  // namespace rtm::viewer
