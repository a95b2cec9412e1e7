// A relief's micro-polygon mesh (truth/micromesh.h) ordered by square tiles of cells, each tile with its bounding
// box, so that a view draws only the tiles that can be in its frustum. For the eye inside a relief's slab (the
// inside-slab-micromesh action, objects/frame_plan.h): the mesh stays on the GPU (texmap GlMesh) and each frame draws
// the index ranges of the tiles not wholly outside the frustum, most of a facade being beside or behind a viewer
// standing in it.
//
// The triangles are those of build_micromesh, each tile's in the same (row-major) order as there; only the order of
// the tiles differs. Drawing every tile draws the whole mesh; a culled tile has no fragment in the view.
#pragma once

#include <cstdint>
#include <vector>

#include "objects/bounds.h"
#include "texmap/camera.h"
#include "texmap/renderer.h"
#include "truth/micromesh.h"
#include "warp/relief_texture.h"

namespace rtm {

struct MicroMeshTile {
    uint32_t first = 0, count = 0;  // a range of indices (whole triangles)
    Bounds bounds;                  // of its triangles' vertices
};

struct TiledMicroMesh {
    MicroMesh mesh;
    std::vector<MicroMeshTile> tiles;  // tiles with at least one triangle, rows of tiles from the top
};

// `tile_cells`: the tile's side in cells (>= 1, else std::invalid_argument naming the value).
TiledMicroMesh build_tiled_micromesh(const ReliefTexture& t, int tile_cells = 16);

// The index ranges of the tiles (a TiledMicroMesh's) not wholly outside the camera's frustum (conservative,
// objects/view_analysis.h outside_frustum), consecutive tiles merged into one range; `triangles`, when given, receives
// the number drawn. Needs only the tiles: a mesh kept on the GPU keeps no vertices on the CPU.
std::vector<IndexRange> visible_tile_ranges(const std::vector<MicroMeshTile>& tiles, const Camera& cam,
                                            size_t* triangles = nullptr);

}  // namespace rtm
