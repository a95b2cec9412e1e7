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

MicroMesh build_micromesh(const ReliefTexture& t);

}  // namespace rtm
