// Micro-polygon meshes by tiles (objects/micromesh_tiles.h) and their draw for the eye inside a relief's slab:
// the same triangles as build_micromesh, bounds that hold them, culling that never drops a triangle in view, and
// the same picture as the whole mesh (DrawOptions::micromesh_tiles off), byte for byte.
#include "objects/micromesh_tiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <string>

#include "common/seed.h"
#include "formats/relief_manifest.h"
#include "measure/compare.h"
#include "objects/render_relief.h"
#include "objects/view_analysis.h"
#include "procedural/procedural_media.h"
#include "texmap/gl_context.h"
#include "warp/test_util.h"

namespace rtm {
namespace {

using Triangle = std::array<uint32_t, 3>;

std::vector<Triangle> triangles(const std::vector<uint32_t>& indices, uint32_t first, uint32_t count) {
    std::vector<Triangle> t;
    for (uint32_t i = first; i + 2 < first + count; i += 3) t.push_back({indices[i], indices[i + 1], indices[i + 2]});
    return t;
}

ReliefTexture facade() { return load_relief(std::string(RTM_SOURCE_DIR) + "/media/facade.relief.json"); }

// Bumps with a few empty texels (holes in the mesh) and an odd size (partial tiles at the right and bottom).
ReliefTexture bumps_with_holes() {
    ReliefTexture t = to_relief(make_bumps(45));
    for (auto [x, r] : {std::pair{3, 4}, {20, 17}, {44, 44}, {0, 30}})
        t.texels.edit()[size_t(r) * 45 + size_t(x)].q = kEmptyIndex;
    return t;
}

TEST(MicromeshTiles, SameTrianglesAsTheMeshEachTilesInItsOrder) {
    for (const ReliefTexture& t : {bumps_with_holes(), facade()}) {
        const MicroMesh whole = build_micromesh(t);
        for (int tile : {1, 7, 16, 1000}) {
            SCOPED_TRACE("tile " + std::to_string(tile) + ", " + std::to_string(t.width) + "x" +
                         std::to_string(t.height));
            const TiledMicroMesh m = build_tiled_micromesh(t, tile);
            ASSERT_EQ(m.mesh.vertices.size(), whole.vertices.size());
            for (size_t i = 0; i < whole.vertices.size(); ++i)
                ASSERT_EQ(m.mesh.vertices[i].position, whole.vertices[i].position);
            // The tiles cover the indices end to end, in order.
            uint32_t next = 0;
            for (const MicroMeshTile& mt : m.tiles) {
                ASSERT_EQ(mt.first, next);
                ASSERT_GT(mt.count, 0u);
                ASSERT_EQ(mt.count % 3, 0u);
                next += mt.count;
                for (uint32_t i = mt.first; i < mt.first + mt.count; ++i) {
                    const glm::dvec3 p = m.mesh.origin + glm::dvec3(m.mesh.vertices[m.mesh.indices[i]].position);
                    ASSERT_TRUE(p.x >= mt.bounds.lo.x && p.x <= mt.bounds.hi.x && p.y >= mt.bounds.lo.y &&
                                p.y <= mt.bounds.hi.y && p.z >= mt.bounds.lo.z && p.z <= mt.bounds.hi.z);
                }
            }
            ASSERT_EQ(next, m.mesh.indices.size());
            // The same triangles (a permutation of whole ones, each keeping its winding).
            std::vector<Triangle> a = triangles(whole.indices, 0, uint32_t(whole.indices.size()));
            std::vector<Triangle> b = triangles(m.mesh.indices, 0, uint32_t(m.mesh.indices.size()));
            std::sort(a.begin(), a.end());
            std::sort(b.begin(), b.end());
            ASSERT_EQ(a, b);
            if (tile == 1000) {  // one tile: build_micromesh's order
                ASSERT_EQ(m.mesh.indices, whole.indices);
            }
        }
    }
}

TEST(MicromeshTiles, RefusesATileSizeBelowOne) {
    const ReliefTexture t = to_relief(make_bumps(8));
    for (int bad : {0, -3}) {
        try {
            build_tiled_micromesh(t, bad);
            FAIL() << "tile size " << bad << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(std::to_string(bad)), std::string::npos) << e.what();
        }
    }
}

// Random eyes near and inside the facade's slab, looking anywhere: every triangle with a vertex inside the view
// volume is in a drawn range, the ranges are ordered and disjoint, and the count drawn is theirs.
TEST(MicromeshTiles, CullingKeepsEveryTriangleInView) {
    const uint64_t seed = test::test_seed(20261203);
    std::printf("RTM_SEED=%llu\n", (unsigned long long)seed);
    std::mt19937_64 rng(seed);
    const ReliefTexture t = facade();
    const TiledMicroMesh m = build_tiled_micromesh(t);
    const Bounds b = relief_bounds(t);
    std::uniform_real_distribution<double> u(0.0, 1.0), s(-1.0, 1.0);
    int culled_views = 0;
    for (int view = 0; view < 60; ++view) {
        Camera cam;
        cam.width = 160;
        cam.height = 120;
        cam.eye = b.lo + (b.hi - b.lo) * glm::dvec3(u(rng), u(rng), u(rng)) + t.geometry.f() * (0.1 * s(rng));
        cam.look_at = cam.eye + glm::dvec3(s(rng), s(rng), s(rng));
        cam.fov_deg = 30 + 60 * u(rng);
        cam.fit_clip_planes(b.centre(), b.radius());
        size_t drawn = 0;
        const std::vector<IndexRange> ranges = visible_tile_ranges(m.tiles, cam, &drawn);
        std::vector<char> in_range(m.mesh.indices.size() / 3, 0);
        size_t counted = 0;
        for (size_t i = 0; i < ranges.size(); ++i) {
            if (i) {
                ASSERT_GT(ranges[i].first, ranges[i - 1].first + ranges[i - 1].count - 1);
            }
            for (uint32_t k = ranges[i].first; k < ranges[i].first + ranges[i].count; k += 3) in_range[k / 3] = 1;
            counted += ranges[i].count / 3;
        }
        ASSERT_EQ(counted, drawn);
        culled_views += drawn < in_range.size();
        const glm::dmat4 clip = cam.projection() * cam.view();
        for (size_t tri = 0; tri < in_range.size(); ++tri) {
            if (in_range[tri]) continue;
            for (int k = 0; k < 3; ++k) {
                const glm::dvec4 c = clip *
                                     glm::dvec4(m.mesh.origin +
                                                    glm::dvec3(m.mesh.vertices[m.mesh.indices[3 * tri + k]].position),
                                                1.0);
                const bool inside = std::abs(c.x) < c.w && std::abs(c.y) < c.w && std::abs(c.z) < c.w;
                ASSERT_FALSE(inside) << "view " << view << ": triangle " << tri
                                     << " has a vertex in view but was culled";
            }
        }
    }
    EXPECT_GE(culled_views, 30);  // most random views see a part of the facade only
}

// The facade drawn with the eye between its wall and its window frames, from random eyes in the slab: the tiles
// kept on the GPU give the picture of the whole mesh uploaded each frame, byte for byte (the same triangles; a culled
// tile has no fragment in view; within a tile the order is the mesh's).
TEST(MicromeshTiles, InsideTheSlabTheSamePictureAsTheWholeMesh) {
    const uint64_t seed = test::test_seed(1203);
    std::printf("RTM_SEED=%llu\n", (unsigned long long)seed);
    std::mt19937_64 rng(seed);
    auto ctx = GlContext::create_offscreen(160, 120);
    Renderer r;
    ReliefQuad q(facade());
    const ReliefGeometry& g = q.relief().geometry;
    std::uniform_real_distribution<double> u(0.0, 1.0), s(-1.0, 1.0);
    int fewer = 0;
    long long drawn_pixels = 0;
    for (int view = 0; view < 24; ++view) {
        Camera cam;
        cam.width = 160;
        cam.height = 120;
        cam.eye = g.origin + g.a * (q.relief().width * u(rng)) + g.b * (q.relief().height * u(rng)) +
                  g.f() * (0.01 + 0.1 * u(rng));
        cam.look_at = cam.eye + glm::dvec3(s(rng), s(rng), -0.2 - u(rng));
        cam.fit_clip_planes(relief_bounds(q.relief()).centre(), relief_bounds(q.relief()).radius());
        if (!eye_inside_slab(q.relief(), cam.eye)) continue;
        ImageRGBA8 img[2];
        DrawReport rep[2];
        for (int tiles = 0; tiles < 2; ++tiles) {
            RenderSettings st;
            st.method = RenderMethod::two_pass;
            st.prewarp.keep_outliers = true;
            st.draw.micromesh_tiles = tiles == 1;
            StageTimes times;
            img[tiles] = render_relief_frame(q, &r, cam, st, times, &rep[tiles]);
            ASSERT_NE(std::find(rep[tiles].skips.begin(), rep[tiles].skips.end(), std::string(kSkipInsideSlab)),
                      rep[tiles].skips.end());
        }
        ASSERT_EQ(img[0].pixels, img[1].pixels) << "view " << view;
        for (const Rgba8& p : img[1].pixels) drawn_pixels += p.r || p.g || p.b;
        EXPECT_EQ(rep[0].micromesh_triangles, rep[0].micromesh_triangles_total);
        EXPECT_EQ(rep[1].micromesh_triangles_total, rep[0].micromesh_triangles_total);
        EXPECT_LE(rep[1].micromesh_triangles, rep[1].micromesh_triangles_total);
        fewer += rep[1].micromesh_triangles < rep[1].micromesh_triangles_total;
    }
    EXPECT_GE(fewer, 12);
    EXPECT_GT(drawn_pixels, 24 * 160 * 120 / 10);  // the views do see the facade
}

}  // namespace
}  // namespace rtm
