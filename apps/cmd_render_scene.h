// rtm render --scene: one frame of a scene (a CAMERA, a frame of its camera path, or its default camera), or every
// frame of its camera path into a folder (--frames DIR).
#pragma once

#include <string>

#include "cli_common.h"

namespace rtm::cli {

struct SceneRenderArgs {
    std::string scene, out, json, method, frames_dir;
    std::string level = "0";  // --level N or auto (per quad, by its screen area)
    CameraArgs camera;
    int path_frame = -1;           // --camera-path K
    std::string filter = "point";  // --filter point|coverage
    bool exact = false, no_skips = false, no_sidewalls = false;
    int threads = 0;
    int repeat = 1;  // --repeat N >= 1 (checked by run_render): one camera's frame N times after one warm-up
};

void run_render_scene(const SceneRenderArgs& a);

}  // namespace rtm::cli
