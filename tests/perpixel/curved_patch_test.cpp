// The curved base of quadric silhouettes (perpixel/curved_patch.h), cylinder and sphere: the top surface at the
// radius, depth inwards along the normal, an orthonormal frame at every point, the tile's size as the derivatives'
// lengths, and the fitted quadric of each interior vertex near the surface's own (-1 / (2 radius) along each curved
// direction, 0 along the cylinder's axis).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

#include "perpixel/curved_patch.h"
#include "procedural/known_answer.h"

namespace rtm {
namespace {

CurvedPatch patch_of(CurvedShape shape) {
    return curved_patch_for(to_relief(make_known_answer("sphere-cap", 64)), shape, 1.2);
}

TEST(CurvedPatch, PointsFramesAndTilesOfBothShapes) {
    for (CurvedShape shape : {CurvedShape::cylinder, CurvedShape::sphere}) {
        SCOPED_TRACE(to_string(shape));
        const CurvedPatch p = patch_of(shape);
        EXPECT_NEAR(p.radius * p.angle, p.width, 1e-12);
        const double h = 1e-6;
        for (double s : {0.0, 0.3, 0.5, 1.0})
            for (double t : {0.0, 0.25, 0.5, 1.0}) {
                const glm::dvec3 N = p.normal(s, t), T = p.tangent(s, t), B = p.binormal(s, t);
                EXPECT_NEAR(glm::length(N), 1.0, 1e-12);
                EXPECT_NEAR(glm::length(T), 1.0, 1e-12);
                EXPECT_NEAR(glm::length(B), 1.0, 1e-12);
                EXPECT_NEAR(glm::dot(N, T), 0.0, 1e-12);
                EXPECT_NEAR(glm::dot(N, B), 0.0, 1e-12);
                EXPECT_NEAR(glm::dot(T, B), 0.0, 1e-12);
                EXPECT_GT(glm::dot(glm::cross(T, B), N), 0.999);  // right-handed, normal outwards
                // Depth goes inwards along the normal, `depth` world units for d = 1.
                const glm::dvec3 top = p.point(s, t), bottom = p.point(s, t, 1.0);
                EXPECT_NEAR(glm::length(top - bottom - N * p.depth), 0.0, 1e-12);
                // The tangent and binormal are the derivatives' directions, the tile their lengths (central
                // differences: error about h^2 times the curvature, far below 1e-6).
                const glm::dvec3 ds = (p.point(s + h, t) - p.point(s - h, t)) / (2 * h);
                const glm::dvec3 dt = (p.point(s, t + h) - p.point(s, t - h)) / (2 * h);
                EXPECT_NEAR(glm::length(ds), p.tile(s, t).x, 1e-6);
                EXPECT_NEAR(glm::length(dt), p.tile(s, t).y, 1e-6);
                EXPECT_NEAR(glm::dot(glm::normalize(ds), T), 1.0, 1e-9);
                EXPECT_NEAR(glm::dot(glm::normalize(dt), B), 1.0, 1e-9);
                // The top surface at the radius: from the axis (cylinder) or the centre (sphere).
                glm::dvec3 rel = top - p.centre;
                if (shape == CurvedShape::cylinder) rel -= p.b_hat * glm::dot(rel, p.b_hat);
                EXPECT_NEAR(glm::length(rel), p.radius, 1e-12);
            }
        // The middle of the quad is where the relief's centre was, raised to the top of the range: both shapes
        // touch the flat quad there.
        EXPECT_NEAR(glm::length(p.point(0.5, 0.5) - (p.centre + p.f * p.radius)), 0.0, 1e-12);
    }
}

// Equation 2's fit at interior vertices: for a surface of radius R the height below the tangent plane is
// -rho^2 / (2R) to second order, so a (and b on the sphere) is -1 / (2R), b = 0 along the cylinder's axis. The
// next term, rho^4 / (8 R^3), is rho^2 / (4 R^2) of it: with 32 x 32 quads over 1.2 rad that is under 0.1%.
TEST(CurvedPatch, FittedQuadricsAreTheSurfaceCurvatures) {
    for (CurvedShape shape : {CurvedShape::cylinder, CurvedShape::sphere}) {
        SCOPED_TRACE(to_string(shape));
        const CurvedPatch p = patch_of(shape);
        std::vector<QuadricVertex> v;
        std::vector<uint32_t> idx;
        curved_base_mesh(p, 32, 32, v, idx);
        ASSERT_EQ(v.size(), 33u * 33u);
        ASSERT_EQ(idx.size(), 32u * 32u * 6u);
        const double want = -1.0 / (2.0 * p.radius);
        for (int j = 1; j < 32; ++j)
            for (int i = 1; i < 32; ++i) {
                const QuadricVertex& x = v[size_t(j * 33 + i)];
                EXPECT_NEAR(x.quadric.x, want, 1e-3 * std::abs(want)) << i << "," << j;
                EXPECT_NEAR(x.quadric.y, shape == CurvedShape::sphere ? want : 0.0, 1e-3 * std::abs(want))
                    << i << "," << j;
                EXPECT_NEAR(x.tile.x, p.tile(x.st.x, x.st.y).x, 1e-6);
            }
    }
    EXPECT_EQ(parse_curved_shape("sphere"), CurvedShape::sphere);
    EXPECT_EQ(parse_curved_shape("cylinder"), CurvedShape::cylinder);
    EXPECT_FALSE(parse_curved_shape("cone").has_value());
}

}  // namespace
}  // namespace rtm
