// Seeing the algorithm over the image (drawn with Dear ImGui's draw lists, after the frame): outlines of the
// texture-mapped quads and of their side polygons (the paper's Figure 16), and insets with the pre-warped textures
// of the quads drawn this frame (Figures 9c and 17), each with its epipole and the four occlusion-compatible
// quadrants (section 3.1: each quadrant is warped from the borders towards the epipole).
#pragma once

#include <glm/vec2.hpp>

#include "texmap/camera.h"
#include "viewer/loaded.h"

struct ImDrawList;

namespace rtm::viewer {

// A world point in framebuffer pixels, x right and y down from the top-left corner. False when the point is at or
// behind the eye's plane.
bool project(const Camera& cam, const glm::dvec3& p, glm::dvec2& px);

// Where (u, v), in the quad's texel units, lies on an inset of `size` showing the quad's texture with its margins:
// x right, y down from the inset's top-left corner.
glm::dvec2 inset_position(const DrawnQuad& q, const glm::dvec2& uv, const glm::dvec2& size);

// Outlines in `list`, `scale` framebuffer pixels per draw-list unit. Quads yellow, side polygons cyan.
void draw_outlines(ImDrawList* list, const Camera& cam, const FrameReport& report, float scale);

// The insets, bottom-right of the display (display_w x display_h in draw-list units), right to left. Returns their
// bounding rectangle (x, y, w, h) in draw-list units, zero when nothing is drawn.
glm::vec4 draw_insets(ImDrawList* list, const FrameReport& report, float display_w, float display_h);

}  // namespace rtm::viewer
