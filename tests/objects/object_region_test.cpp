// The 26 regions around an object's box (and the inside): which faces are visible, and which adjacent faces are
// pre-warped onto each (paper section 4.1, Figure 14 in 3-D), for every region and on every region boundary.
#include "objects/object_region.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace rtm {
namespace {

const Box kBox{{-1.0, 0.5, 2.0}, {3.0, 1.5, 2.25}};

// Eye coordinate on one axis for side s in {-1, 0, +1}: below, level with (the centre) or above the box.
double coord(int axis, int s) {
    if (s == 0) return 0.5 * (kBox.lo[axis] + kBox.hi[axis]);
    return s > 0 ? kBox.hi[axis] + 0.75 : kBox.lo[axis] - 0.75;
}

void check_faces(const ObjectRegion& r, const std::array<int, 3>& side) {
    SCOPED_TRACE(r.to_string());
    EXPECT_EQ(r.side, side);
    const std::vector<int> vis = r.visible_faces();
    size_t nonzero = 0;
    for (int a = 0; a < 3; ++a) nonzero += side[size_t(a)] != 0;
    ASSERT_EQ(vis.size(), nonzero);
    for (int f : vis) EXPECT_EQ(side[size_t(face_axis(f))], int(face_sign(f)));
    EXPECT_EQ(r.inside(), nonzero == 0);
    for (int f = 0; f < kFaceCount; ++f) {
        const std::vector<int> adj = faces_warped_onto(r, f);
        if (!r.visible(f)) {
            EXPECT_TRUE(adj.empty());
            continue;
        }
        // 4 adjacent faces for a one-face view, 3 for each face of a two-face view, 2 for each of a three-face view.
        EXPECT_EQ(adj.size(), size_t(5 - nonzero)) << kFaceKeys[size_t(f)];
        for (int g : adj) {
            EXPECT_NE(face_axis(g), face_axis(f));
            EXPECT_FALSE(r.visible(opposite_face(g)));
        }
        // Every other visible face is among them (the paper's even regions: left onto right and right onto left).
        for (int g : vis) {
            if (g != f) {
                EXPECT_NE(std::find(adj.begin(), adj.end(), g), adj.end());
            }
        }
    }
}

TEST(ObjectRegion, EveryOneOfThe27Cells) {
    std::set<int> indices;
    int one = 0, two = 0, three = 0;
    for (int sx = -1; sx <= 1; ++sx)
        for (int sy = -1; sy <= 1; ++sy)
            for (int sz = -1; sz <= 1; ++sz) {
                const glm::dvec3 eye(coord(0, sx), coord(1, sy), coord(2, sz));
                const ObjectRegion r = classify_region(kBox, eye);
                check_faces(r, {sx, sy, sz});
                indices.insert(r.index());
                const size_t n = r.visible_faces().size();
                one += n == 1;
                two += n == 2;
                three += n == 3;
            }
    EXPECT_EQ(indices.size(), 27u);
    EXPECT_EQ(*indices.begin(), 0);
    EXPECT_EQ(*indices.rbegin(), 26);
    EXPECT_EQ(classify_region(kBox, {coord(0, 0), coord(1, 0), coord(2, 0)}).index(), 13);
    // 6 face regions, 12 edge regions, 8 corner regions.
    EXPECT_EQ(one, 6);
    EXPECT_EQ(two, 12);
    EXPECT_EQ(three, 8);
}

TEST(ObjectRegion, BoundariesBelongToTheSlab) {
    // On a face's plane the face is edge-on: not visible. A hair outside, it is.
    for (int sx = -1; sx <= 1; ++sx)
        for (int sy = -1; sy <= 1; ++sy)
            for (int sz = -1; sz <= 1; ++sz)
                for (int axis = 0; axis < 3; ++axis)
                    for (int end = 0; end < 2; ++end) {
                        glm::dvec3 eye(coord(0, sx), coord(1, sy), coord(2, sz));
                        const double plane = end ? kBox.hi[axis] : kBox.lo[axis];
                        eye[axis] = plane;
                        std::array<int, 3> side{sx, sy, sz};
                        side[size_t(axis)] = 0;
                        check_faces(classify_region(kBox, eye), side);
                        eye[axis] = std::nextafter(plane, end ? INFINITY : -INFINITY);
                        side[size_t(axis)] = end ? 1 : -1;
                        check_faces(classify_region(kBox, eye), side);
                        eye[axis] = std::nextafter(plane, end ? -INFINITY : INFINITY);
                        side[size_t(axis)] = 0;
                        check_faces(classify_region(kBox, eye), side);
                    }
}

TEST(ObjectRegion, PaperExamplesIn2D) {
    // Region (1) of Figure 14, in front of one face: the two faces beside it are pre-warped onto it.
    const ObjectRegion front = classify_region(kBox, {coord(0, 0), coord(1, 0), coord(2, 1)});
    EXPECT_EQ(front.visible_faces(), std::vector<int>({4}));
    EXPECT_EQ(faces_warped_onto(front, 4), std::vector<int>({0, 1, 2, 3}));
    // An even region, two faces seen (+x and +z, level in y): each is pre-warped onto the other, and not the faces
    // opposite them.
    const ObjectRegion even = classify_region(kBox, {coord(0, 1), coord(1, 0), coord(2, 1)});
    EXPECT_EQ(even.visible_faces(), std::vector<int>({0, 4}));
    EXPECT_EQ(faces_warped_onto(even, 4), std::vector<int>({0, 2, 3}));
    EXPECT_EQ(faces_warped_onto(even, 0), std::vector<int>({2, 3, 4}));
}

}  // namespace
}  // namespace rtm
