#include "objects/micromesh_tiles.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "objects/view_analysis.h"

namespace rtm {

TiledMicroMesh build_tiled_micromesh(const ReliefTexture& t, int tile_cells) {
    if (tile_cells < 1)
        throw std::invalid_argument("build_tiled_micromesh: tile size " + std::to_string(tile_cells) +
                                    " cells is not positive");
    TiledMicroMesh out;
    std::vector<uint32_t> cells;
    MicroMesh m = build_micromesh(t, &cells);
    const size_t w = size_t(std::max(t.width, 1));
    const size_t tiles_across = (w + size_t(tile_cells) - 1) / size_t(tile_cells);
    const auto tile_of = [&](uint32_t cell) {
        const size_t row = cell / w, x = cell % w;
        return (row / size_t(tile_cells)) * tiles_across + x / size_t(tile_cells);
    };
    // A stable order by tile keeps each tile's triangles in build_micromesh's order.
    std::vector<uint32_t> order(cells.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return tile_of(cells[a]) < tile_of(cells[b]); });
    out.mesh.vertices = std::move(m.vertices);
    out.mesh.origin = m.origin;
    out.mesh.indices.reserve(m.indices.size());
    for (size_t i = 0; i < order.size(); ++i) {
        const size_t tri = order[i];
        const size_t tile = tile_of(cells[tri]);
        if (i == 0 || tile != tile_of(cells[order[i - 1]])) {
            out.tiles.emplace_back();
            out.tiles.back().first = uint32_t(out.mesh.indices.size());
        }
        MicroMeshTile& mt = out.tiles.back();
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = m.indices[3 * tri + size_t(k)];
            out.mesh.indices.push_back(v);
            mt.bounds.extend(out.mesh.origin + glm::dvec3(out.mesh.vertices[v].position));  // world bounds
        }
        mt.count += 3;
    }
    return out;
}

std::vector<IndexRange> visible_tile_ranges(const std::vector<MicroMeshTile>& tiles, const Camera& cam,
                                            size_t* triangles) {
    std::vector<IndexRange> ranges;
    const glm::dmat4 clip_from_world = cam.projection() * cam.view();
    size_t n = 0;
    for (const MicroMeshTile& tile : tiles) {
        if (outside_frustum(clip_from_world, tile.bounds)) continue;
        n += tile.count / 3;
        if (!ranges.empty() && ranges.back().first + ranges.back().count == tile.first)
            ranges.back().count += tile.count;
        else
            ranges.push_back({tile.first, tile.count});
    }
    if (triangles) *triangles = n;
    return ranges;
}

}  // namespace rtm
