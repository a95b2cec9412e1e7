// rtm render --mesh FILE: the mesh itself with conventional OpenGL (apps/cmd_render_mesh.cpp).
#pragma once

#include <string>

#include "cli_common.h"

namespace rtm::cli {

void run_render_mesh(const std::string& mesh_path, const CameraArgs& camera, const std::string& out,
                     const std::string& json);

}  // namespace rtm::cli
