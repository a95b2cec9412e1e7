// Ground truth by micro-polygons (paper section 3.2.1): vertices at the texel centres displaced along f (exact
// displacement), two triangles per cell of four non-empty texels, colour per vertex. Empty texels make holes.
#pragma once

#include <cstdint>
#include <vector>

#include "texmap/renderer.h"
#include "warp/relief_texture.h"

namespace rtm {

struct MicroMesh {
    // Positions relative to `origin` (the relief's origin): world point = origin + position, so that a relief far
    // from the world's origin keeps its float positions' digits (at 1e8 a unit quad drew nothing). Draw with
    // Renderer::draw_mesh(cam, vertices, indices, origin).
    std::vector<MeshVertex> vertices;
    std::vector<uint32_t> indices;
    glm::dvec3 origin{0.0};
};

// `triangle_cells`, when given, receives for each triangle (indices[3i..3i+2]) its cell, row * width + x: the
// triangles of one cell are consecutive, cells in row-major order.
MicroMesh build_micromesh(const ReliefTexture& t, std::vector<uint32_t>* triangle_cells = nullptr);

// Draws the mesh where it lies in the world (its positions offset by its origin).
inline void draw_mesh(Renderer& renderer, const Camera& cam, const MicroMesh& m) {
    renderer.draw_mesh(cam, m.vertices, m.indices, m.origin);
}

}  // namespace rtm
