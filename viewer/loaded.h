// What the viewer has loaded: the one interface the window, the panel and the overlays see. Implementations: a
// relief (loaded_relief.h), a six-face object or a mesh baked into one (loaded_object.h), a scene
// (loaded_scene.h); open_file (open_file.h) picks one by the file's kind. draw() renders
// one frame into the current framebuffer and reports what it did: the stage times (the paper's Table 1), the
// texels pre-warped, the skips that fired, and the quads drawn with their pre-warped textures, epipoles and side
// polygons (for the insets and outlines).
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "objects/bounds.h"
#include "formats/scene_manifest.h"
#include "objects/relief_quad.h"
#include "texmap/camera.h"
#include "texmap/renderer.h"
#include "viewer/camera_path.h"
#include "viewer/view_settings.h"
#include "warp/image.h"

namespace rtm::viewer {

// One relief quad drawn this frame.
struct DrawnQuad {
    std::string name;
    std::array<glm::dvec3, 4> corners;  // (0,0), (w,0), (w,h), (0,h) in texel units, world space
    int level = 0;
    int width = 0, height = 0;  // the quad at that level, in texels
    PrewarpExtent margins;      // the texture covers u in [-left, width + right), v in [-bottom, height + top)
    unsigned texture = 0;       // GL name of the texture mapped on the quad (pre-warped, or flat)
    int texture_width = 0, texture_height = 0;
    bool warped = false;  // the texture is a pre-warp (else the flat texture)
    // The epipole (k1/k3, k2/k3) in the level's texel units; not finite when the eye is in the relief's plane.
    glm::dvec2 epipole{0.0};
    std::vector<std::array<glm::dvec3, 4>> side_polygons;  // world-space corners of each side polygon drawn
};

struct FrameReport {
    StageTimes times;
    long long texels_warped = 0;     // source texels pre-warped this frame (0 when reused or skipped)
    std::vector<std::string> skips;  // names from objects/relief_quad.h
    int level = 0;
    std::vector<DrawnQuad> quads;
    std::string note;  // why nothing (or less) was drawn, for the panel: a method this kind cannot draw, ...
};

class Loaded {
public:
    virtual ~Loaded() = default;
    virtual std::string name() const = 0;
    virtual std::string kind() const = 0;  // "relief", "object", "mesh", "scene"
    virtual Bounds bounds() const = 0;
    // One-time work that needs the window's GL context (baking a mesh), before the first draw; `progress` gets
    // one line per step. Throws IoError naming the file.
    virtual void prepare(const std::function<void(const std::string&)>& progress) { (void)progress; }
    // Draws with the settings' method into the current frame; the caller has called renderer.begin_frame(cam).
    // A method this kind cannot draw draws nothing and says why in report.note.
    virtual void draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) = 0;
    // Why there is no ray-cast truth for this kind (empty: raycast() works).
    virtual std::string raycast_unavailable() const { return {}; }
    // The ray-cast truth (CPU, slow: shown as a still).
    virtual ImageRGBA8 raycast(const Camera& cam, const ViewSettings& s) = 0;
    // The file's own camera and camera path (a scene's "camera" and "camera_path"), if it has them.
    // The texture protruded displacement mapping puts on steep slopes (`--steep-texture IMG`): a relief keeps it
    // (over reloads); the other kinds draw no protruded displacement and ignore it.
    virtual void set_steep_texture(const ImageRGBA8& img) { (void)img; }
    virtual std::optional<SceneCameraKey> own_camera() const { return std::nullopt; }
    virtual std::optional<CameraPath> own_camera_path() const { return std::nullopt; }
};

}  // namespace rtm::viewer
