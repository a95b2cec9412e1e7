// Micro-polygon meshes (truth/micromesh.h): counts with holes, vertices on the exact 3-D points, orientation.
#include "truth/micromesh.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <random>

#include "ground_truth_util.h"

namespace rtm {
namespace {

ReliefTexture relief_with_holes(int w, int h, const ReliefGeometry& g, std::vector<std::pair<int, int>> empty) {
    return truth_test::make_relief_fn(
        w, h, g, [](int x, int r) { return 0.001 * (x * 3 + r * 5 % 7); }, truth_test::hash_color,
        [&](int x, int r) {
            for (auto [ex, er] : empty)
                if (ex == x && er == r) return true;
            return false;
        });
}

TEST(Micromesh, CountsWithoutHoles) {
    const MicroMesh m = build_micromesh(relief_with_holes(4, 3, ReliefGeometry{}, {}));
    EXPECT_EQ(m.vertices.size(), 12u);
    EXPECT_EQ(m.indices.size(), 3u * 2u * 3u * 2u);  // 3x2 cells, two triangles each
}

TEST(Micromesh, EmptyTexelsMakeHoles) {
    // An interior empty texel removes its vertex and the four cells around it; a corner one a single cell;
    // an edge one two.
    EXPECT_EQ(build_micromesh(relief_with_holes(4, 3, ReliefGeometry{}, {{1, 1}})).indices.size(), 3u * 2u * (6 - 4));
    EXPECT_EQ(build_micromesh(relief_with_holes(4, 3, ReliefGeometry{}, {{1, 1}})).vertices.size(), 11u);
    EXPECT_EQ(build_micromesh(relief_with_holes(4, 3, ReliefGeometry{}, {{0, 0}})).indices.size(), 3u * 2u * (6 - 1));
    EXPECT_EQ(build_micromesh(relief_with_holes(4, 3, ReliefGeometry{}, {{0, 1}})).indices.size(), 3u * 2u * (6 - 2));
    EXPECT_EQ(build_micromesh(relief_with_holes(4, 3, ReliefGeometry{}, {{0, 0}, {3, 2}})).indices.size(),
              3u * 2u * (6 - 2));
    // Checkerboard of empties: no cell has four non-empty texels.
    std::vector<std::pair<int, int>> checker;
    for (int r = 0; r < 5; ++r)
        for (int x = 0; x < 5; ++x)
            if ((x + r) % 2) checker.push_back({x, r});
    const MicroMesh c = build_micromesh(relief_with_holes(5, 5, ReliefGeometry{}, checker));
    EXPECT_EQ(c.vertices.size(), 13u);
    EXPECT_TRUE(c.indices.empty());
}

TEST(Micromesh, DegenerateSizesHaveNoTriangles) {
    for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 6}, std::pair{6, 1}}) {
        const MicroMesh m = build_micromesh(relief_with_holes(w, h, ReliefGeometry{}, {}));
        EXPECT_EQ(m.vertices.size(), size_t(w * h));
        EXPECT_TRUE(m.indices.empty());
    }
}

TEST(Micromesh, VerticesOnTheExactPointsWithTheirColours) {
    std::mt19937_64 rng(truth_test::seed(72001));
    const ReliefGeometry g = truth_test::random_geometry(rng);
    const int w = 9, h = 7;
    const ReliefTexture t = relief_with_holes(w, h, g, {{2, 3}, {8, 0}});
    const MicroMesh m = build_micromesh(t);
    ASSERT_EQ(m.vertices.size(), size_t(w * h - 2));
    EXPECT_EQ(m.origin, g.origin);
    // Vertices are in texel order (row 0 first), skipping empties.
    size_t k = 0;
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) {
            if (t.empty_at(x, r)) continue;
            const MeshVertex& v = m.vertices[k++];
            const glm::dvec3 p = t.point(x, r) - m.origin;         // positions are relative to the relief's origin
            EXPECT_EQ(v.position, glm::vec3(p)) << x << "," << r;  // the exact point, rounded to float once
            EXPECT_LT(glm::length(glm::dvec3(v.position) - p), 1e-6 * (1 + glm::length(p)));
            const ReliefTexel& tx = t.texel(x, r);
            EXPECT_EQ(v.color, glm::u8vec4(tx.r, tx.g, tx.b, 255)) << x << "," << r;
        }
    for (uint32_t i : m.indices) ASSERT_LT(i, m.vertices.size());
}

TEST(Micromesh, TrianglesFaceFAndShareTheLowToHighDiagonal) {
    std::mt19937_64 rng(truth_test::seed(72002));
    const ReliefGeometry g = truth_test::random_geometry(rng);
    const ReliefTexture t = truth_test::make_relief_fn(
        3, 3, g, [](int, int) { return 0.0; }, truth_test::hash_color, [](int, int) { return false; });
    const MicroMesh m = build_micromesh(t);
    ASSERT_EQ(m.indices.size(), 4u * 6u);
    const glm::dvec3 f = g.f();
    for (size_t i = 0; i < m.indices.size(); i += 3) {
        const glm::dvec3 p0(m.vertices[m.indices[i]].position), p1(m.vertices[m.indices[i + 1]].position),
            p2(m.vertices[m.indices[i + 2]].position);
        EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), f), 0.0) << "triangle " << i / 3;  // counter-clockwise from +f
    }
    // Cell of texels (0..1, rows 1..2) -- (u, v) in [0.5, 1.5]^2: both triangles contain its low (u, v) corner
    // (texel (0, row 2)) and its high corner (texel (1, row 1)). Vertex index = row * 3 + x (no empties).
    const uint32_t lo = 2 * 3 + 0, hi = 1 * 3 + 1;
    bool found = false;
    for (size_t c = 0; c < m.indices.size(); c += 6) {
        const auto has = [&](size_t tri, uint32_t v) {
            return m.indices[tri] == v || m.indices[tri + 1] == v || m.indices[tri + 2] == v;
        };
        if (has(c, lo) && has(c + 3, lo)) {
            found = true;
            EXPECT_TRUE(has(c, hi) && has(c + 3, hi));
        }
    }
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace rtm
