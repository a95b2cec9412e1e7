// The viewer's Dear ImGui panel, top-left: the method and its options, the skips and whether each fired this
// frame, the camera and the camera path, what is shown over the image, and the frame time by stage as the
// paper's Table 1 with a rolling plot, frames per second and texels pre-warped per frame.
#pragma once

#include <glm/vec4.hpp>

#include <string>

#include "viewer/cameras.h"
#include "viewer/frame_stats.h"
#include "viewer/keys.h"
#include "viewer/loaded.h"

namespace rtm::viewer {

struct PanelContext {
    std::string loaded_name, loaded_kind, gl_renderer, status;
    const FrameReport* report = nullptr;
    const FrameStats* stats = nullptr;        // every frame: frames per second, frame time, the plot
    const FrameStats* timed_stats = nullptr;  // the frames whose stages were timed: the table
    int timed_every = 16;                     // 1 frame of this many is timed
    FlyCamera* fly = nullptr;
    bool has_path = false;
    double* path_time = nullptr;
    double path_duration = 0;
    bool* playing = nullptr;
    float ui_scale = 1.f;  // the screen's content scale in ImGui units: the panel's fixed widths follow it
};

// Draws the panel (between ImGui::NewFrame and ImGui::Render) and returns its rectangle (x, y, w, h) in ImGui
// units. Buttons set requests in `r`, as their keys do.
glm::vec4 draw_panel(ViewSettings& s, PanelContext& c, KeyRequests& r);

}  // namespace rtm::viewer
