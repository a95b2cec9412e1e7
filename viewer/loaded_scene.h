// A scene loaded in the viewer (NAME.scene.json, docs/SCENES.md): relief quads and plain polygons in one world,
// drawn by Scene::draw as `rtm render --scene` draws it (depth correction always on, each quad with its own skips).
// The scene's own camera and camera path are offered to the viewer (own_camera, own_camera_path).
#pragma once

#include <string>

#include "objects/scene.h"
#include "viewer/loaded.h"

namespace rtm::viewer {

class LoadedScene : public Loaded {
public:
    explicit LoadedScene(const std::string& manifest);  // throws IoError naming the file
    std::string name() const override { return path_; }
    std::string kind() const override { return "scene"; }
    Bounds bounds() const override { return scene_.bounds(); }
    void draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) override;
    std::string raycast_unavailable() const override;
    ImageRGBA8 raycast(const Camera& cam, const ViewSettings& s) override;
    std::optional<SceneCameraKey> own_camera() const override { return scene_.manifest().camera; }
    // The path's frames at 30 per second: frame k at t = k / 30, its eye, look-at and field of view.
    std::optional<CameraPath> own_camera_path() const override;

private:
    std::string path_;
    Scene scene_;
};

// The frames of a scene's camera path (formats/scene_manifest.h) as a viewer camera path: one key per frame at
// t = k / fps. Empty keys when the scene has no path.
CameraPath scene_camera_path(const SceneManifest& m, double fps = 30.0);

}  // namespace rtm::viewer
