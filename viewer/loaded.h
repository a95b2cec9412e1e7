// What the viewer has loaded: the one interface the window, the panel and the overlays see. A relief is one
// implementation (loaded_relief.h); six-face objects and scenes plug in by implementing it too. draw() renders
// one frame into the current framebuffer and reports what it did: the stage times (the paper's Table 1), the
// texels pre-warped, the skips that fired, and the quads drawn with their pre-warped textures, epipoles and side
// polygons (for the insets and outlines).
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "objects/bounds.h"
#include "objects/relief_quad.h"
#include "texmap/camera.h"
#include "texmap/renderer.h"
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
};

class Loaded {
public:
    virtual ~Loaded() = default;
    virtual std::string name() const = 0;
    virtual std::string kind() const = 0;  // "relief", "object", "scene"
    virtual Bounds bounds() const = 0;
    // Draws with the settings' method (flat, two_pass, pipelined, micromesh) into the current frame; the caller
    // has called renderer.begin_frame(cam).
    virtual void draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) = 0;
    // The ray-cast truth (CPU, slow: shown as a still).
    virtual ImageRGBA8 raycast(const Camera& cam, const ViewSettings& s) = 0;
};

// Opens a file by its kind: NAME.relief.json now; .object.json, .scene.json and meshes are named in the error
// until those kinds exist in this build. Throws IoError naming the file.
std::unique_ptr<Loaded> open_file(const std::string& path);

}  // namespace rtm::viewer
