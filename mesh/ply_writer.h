// Writes a TriangleMesh (mesh/triangle_mesh.h) as a binary little-endian PLY file with per-vertex RGB colours,
// which load_mesh (assimp) reads back: positions, vertex colours and the triangles, nothing else (no texture
// coordinates, no materials). For generated media (procedural/room.h).
#pragma once

#include <string>

#include "mesh/triangle_mesh.h"

namespace rtm {

// Atomically (temporary file + rename); throws IoError naming the path on failure.
void write_ply(const std::string& path, const TriangleMesh& mesh);

}  // namespace rtm
