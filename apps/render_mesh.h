// rtm render --mesh FILE: the mesh itself with conventional OpenGL (apps/cmd_render_mesh.cpp).
#pragma once

#include <string>

#include "cli_common.h"

namespace rtm::cli {

// With repeat > 1, one warm-up draw and then `repeat` timed ones (the upload is once, before them).
void run_render_mesh(const std::string& mesh_path, const CameraArgs& camera, const std::string& out,
                     const std::string& json, int repeat = 1);

}  // namespace rtm::cli
