// rtm bake --mesh FILE --planes P.json: an orthographic colour and depth view of the mesh onto each given
// rectangle, written as one relief texture per rectangle (for scenes: walls, floors, facades).
//
// P.json:
//   { "planes": [ { "name": "floor", "origin": [x, y, z], "a": [x, y, z], "b": [x, y, z], "size": [w, h],
//                   "range": [lo, hi], "cull_back_faces": false }, ... ] }
// Each rectangle is a relief frame (the relief conventions: texel (i, r) centre at u = i + 0.5,
// v = h - 1 - r + 0.5; X = origin + a*u + b*v + f*d, f = normalize(cross(a, b))), w x h texels. The view looks
// along -f and records the first surface inside the slab of displacements [lo, hi] (optional; default the extent
// of the mesh's bounding box along f, so everything). "cull_back_faces" (optional, default false): record only
// the faces seen from their front side (a mesh wound counter-clockwise seen from outside): a view from outside a
// room then sees through its ceiling and walls from behind. "name": letters, digits, '_' and '-', unique; it names the
// output DIR/MESH_NAME.relief.json. Unknown fields are ignored; malformed ones are refused with one line naming
// the file, the plane and the field.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mesh/triangle_mesh.h"
#include "warp/relief_texture.h"

namespace rtm {

struct BakePlane {
    std::string name;
    ReliefGeometry geometry;
    int width = 0, height = 0;
    std::optional<double> range_lo, range_hi;
    bool cull_back_faces = false;  // record only faces seen from their front (MeshRenderer::render)
};

// Throws IoError naming the file, the plane (by index or name) and the field.
std::vector<BakePlane> parse_bake_planes(const std::string& path);

// Bakes every plane (needs a current GlContext) and writes DIR/STEM_NAME.relief.json with its two images each,
// only once every view is rendered; on a write failure the files written are removed. Returns the manifests.
std::vector<std::string> bake_planes(const TriangleMesh& mesh, const std::vector<BakePlane>& planes,
                                     const std::string& dir, const std::string& stem);

}  // namespace rtm
