// A mesh baked for the viewer into a six-face object, as `rtm bake --mesh FILE` bakes it (mesh/bake_object.h). A
// translation unit of its own: mesh/bake_object.h and warp/box_faces.h (which the object code includes) both
// define rtm::kFaceKeys.
#pragma once

#include <functional>
#include <string>

#include "mesh/triangle_mesh.h"
#include "objects/bounds.h"

namespace rtm::viewer {

// The box the mesh will be baked in, at `n` texels along its longest side (known before the bake). Throws IoError
// naming `path` when the mesh cannot be baked (a single point, not finite).
Bounds mesh_bake_bounds(const TriangleMesh& mesh, int n, const std::string& path);

// Bakes the mesh (needs a current GL context) and writes the object into `dir` as rtm bake does; returns the
// manifest's path. `progress(done, 6)` after each face; warnings go to stderr naming `path`.
std::string bake_mesh_into(const TriangleMesh& mesh, int n, const std::string& path, const std::string& dir,
                           const std::function<void(int, int)>& progress);

}  // namespace rtm::viewer
