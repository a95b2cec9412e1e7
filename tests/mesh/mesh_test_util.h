// Helpers for tests/mesh: small meshes written as OBJ files with known geometry and colours.
#pragma once

#include <string>

namespace rtm::mesh_testing {

// A "box with a bump" in x, y in [0, 1], z in [0.25, 0.75], as two quads facing +z:
//   floor: z = 0.25 over [0, 1]^2, material colour 0.2 0.4 0.6 -> (51, 102, 153);
//   bump:  z = 0.75 over [0.25, 0.75]^2, material colour 1 0.8 0 -> (255, 204, 0).
// Writes NAME.obj and NAME.mtl into `dir`; returns the OBJ's path.
std::string write_bump_obj(const std::string& dir, const std::string& name = "bump");

// Where the duck of Debian's assimp-testmodels package is (empty if the package is missing).
std::string duck_path();

}  // namespace rtm::mesh_testing
