// Ground truth by micro-polygons (paper section 3.2.1): vertices at the texel centres displaced along f (exact
// displacement), two triangles per cell of four non-empty texels, colour per vertex. Empty texels make holes.
#pragma once

#include <cstdint>
#include <vector>

#include "texmap/renderer.h"
#include "warp/relief_texture.h"

namespace rtm {

struct MicroMesh {
    std::vector<MeshVertex> vertices;
    std::vector<uint32_t> indices;
};

// `triangle_cells`, when given, receives for each triangle (indices[3i..3i+2]) its cell, row * width + x: the
// triangles of one cell are consecutive, cells in row-major order.
MicroMesh build_micromesh(const ReliefTexture& t, std::vector<uint32_t>* triangle_cells = nullptr);

}  // namespace rtm
