// The synthetic six-face objects: every non-empty texel's 3-D point lies on the analytic surface (the face's
// orthographic ray cast), empty texels are where the ray misses, and the faces agree with the box frames.
#include "procedural/synthetic_object.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rtm {
namespace {

TEST(SyntheticObject, SphereTexelsLieOnTheSphere) {
    const int n = 32;
    const SixFaceObject obj = make_synthetic_object(SyntheticShape::sphere, n);
    for (int f = 0; f < kFaceCount; ++f) {
        const ReliefTexture& t = obj.faces[size_t(f)];
        int filled = 0;
        for (int r = 0; r < n; ++r)
            for (int x = 0; x < n; ++x) {
                const ReliefGeometry& g = t.geometry;
                const glm::dvec3 on_face = g.origin + g.a * (x + 0.5) + g.b * ((n - 1 - r) + 0.5);
                // The texel's ray hits the unit sphere iff its distance from the axis through the centre is < 1.
                const glm::dvec3 off = on_face - g.f() * glm::dot(on_face, g.f());
                const bool hits = glm::length(off) < 1.0;
                ASSERT_EQ(!t.empty_at(x, r), hits) << kFaceKeys[size_t(f)] << " texel " << x << "," << r;
                if (!hits) continue;
                ++filled;
                // Exact float displacement: |X| = 1 up to float rounding of the stored displacement (2^-24 relative).
                EXPECT_NEAR(glm::length(t.point(x, r)), 1.0, 1e-6);
                EXPECT_LE(t.displ(x, r), 0.0f);
            }
        // A disc of radius 1 in a 2 x 2 square: pi / 4 of the texels, within the rim's texels.
        EXPECT_NEAR(filled, M_PI / 4 * n * n, 4.0 * n);
        EXPECT_FALSE(t.breaks.empty());
    }
}

TEST(SyntheticObject, CrossBoxDepthsAreTheCrossAndTheInnerCube) {
    const int n = 40;  // texel spacing 0.05: the cross's edges (at 0.15 and 0.7) fall between texel centres
    const SixFaceObject obj = make_synthetic_object(SyntheticShape::cross_box, n);
    for (int f = 0; f < kFaceCount; ++f) {
        const ReliefTexture& t = obj.faces[size_t(f)];
        for (int r = 0; r < n; ++r)
            for (int x = 0; x < n; ++x) {
                const ReliefGeometry& g = t.geometry;
                const glm::dvec3 p = g.origin + g.a * (x + 0.5) + g.b * ((n - 1 - r) + 0.5);
                const int ax = face_axis(f), u = (ax + 1) % 3, v = (ax + 2) % 3;
                const double pu = std::abs(p[u]), pv = std::abs(p[v]);
                const bool on_cross = (pu <= 0.7 && pv <= 0.15) || (pu <= 0.15 && pv <= 0.7);
                const bool on_cube = pu <= 0.8 && pv <= 0.8;
                // Beyond the inner cube the ray meets the crosses of the neighbouring faces' ends, or nothing.
                if (on_cross) {
                    EXPECT_EQ(t.displ(x, r), 0.0f);
                } else if (on_cube) {
                    EXPECT_NEAR(t.displ(x, r), -0.2, 1e-6);
                } else if (!t.empty_at(x, r)) {
                    EXPECT_LE(t.displ(x, r), -0.2f);
                }
            }
    }
}

TEST(SyntheticObject, Deterministic) {
    const auto a = synthetic_faces(SyntheticShape::cross_box, 16), b = synthetic_faces(SyntheticShape::cross_box, 16);
    for (int f = 0; f < kFaceCount; ++f) {
        EXPECT_EQ(a[size_t(f)].color.pixels, b[size_t(f)].color.pixels);
        EXPECT_EQ(a[size_t(f)].displacement.pixels, b[size_t(f)].displacement.pixels);
    }
    EXPECT_THROW(parse_synthetic_shape("cube"), std::invalid_argument);
}

}  // namespace
}  // namespace rtm
