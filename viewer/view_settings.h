// What the viewer's user chooses: the method and its options (the panel, the keys and the scripted options all
// change this one struct), and what is shown over the image.
#pragma once

#include <string>

#include "objects/relief_quad.h"
#include "perpixel/perpixel_method.h"

namespace rtm::viewer {

// The split view: the right half of the window shows another method, or the error of the current method against
// the truth (the micro-polygon mesh) as a heat map.
enum class SplitMode { off, method, truth };

struct ViewSettings {
    RenderMethod method = RenderMethod::two_pass;
    int level = 0;              // pyramid level; -1 = auto
    bool skips = true;          // the skips of DrawOptions
    bool side_polygons = true;  // keep the samples that leave the quad and draw the side polygons
    bool depth_correction = false;
    bool coverage = false;      // the coverage filter (two-pass only; ignored otherwise)
    double discontinuity = -1;  // threshold for marking discontinuities; -1 = the manifest's own
    int threads = 0;            // pre-warp threads, 0 = all
    PerPixelSettings perpixel;  // the per-pixel methods' settings (the papers' defaults until the panel changes them)

    bool panel = false;     // the Dear ImGui panel
    bool insets = false;    // the pre-warped textures of the quads drawn, with their epipoles
    bool outlines = false;  // outlines of the texture-mapped quads and side polygons
    SplitMode split = SplitMode::off;
    RenderMethod split_method = RenderMethod::micromesh;
    bool vsync = true;
    bool fly = false;  // fly camera instead of orbit
    bool operator==(const ViewSettings&) const = default;
};

// Parses a --split value: a method name (flat, two-pass, pipelined, micromesh) or "truth". Throws
// std::invalid_argument naming the value.
void parse_split(const std::string& text, ViewSettings& s);

}  // namespace rtm::viewer
