// The curved base mesh of relief mapping with quadric silhouettes (Oliveira and Policarpo, "An efficient
// representation for surface details", UFRGS tech. report RP-351, 2005): the relief's quad bent over a cylinder
// whose axis is parallel to b, behind the relief (a parabolic cylinder locally: one principal curvature, the
// paper's Figure 7 (c)), or over a sphere (both curvatures: a paraboloid, Figure 7 (a)); the surface bulges towards
// +f. The top of the displacement range lies on the surface, arc length along a (on the sphere, along its equator)
// equal to the quad's width; depth goes inwards along the radius. The mesh carries per-vertex tangent frames, the
// texture tile's size at the vertex and the quadric coefficients fitted per vertex by least squares (the paper's
// equation 2); curved_micromesh() is the truth: the relief displaced radially, one vertex a texel.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "perpixel/perpixel_method.h"
#include "texmap/renderer.h"
#include "warp/relief_texture.h"

namespace rtm {

struct CurvedPatch {
    using Shape = CurvedShape;  // perpixel/perpixel_method.h
    Shape shape = Shape::cylinder;
    glm::dvec3 centre{0.0};  // on the axis (the sphere's centre), level with the middle of the quad along b
    glm::dvec3 a_hat{1, 0, 0}, b_hat{0, 1, 0}, f{0, 0, 1};
    double radius = 1.0, angle = 1.0;  // the patch spans azimuths [-angle/2, angle/2] about f, towards a
    double angle_b = 1.0;              // the sphere: latitudes [-angle_b/2, angle_b/2] towards b (height / radius)
    double width = 1.0, height = 1.0;  // arc length along a (= radius * angle) and length along b (world units)
    double depth = 0.0;                // max - min of the displacement: how far the relief reaches inwards

    // The point at texture coordinates (s, t) in [0, 1]^2 and depth d (0 = top of the range, 1 = bottom).
    glm::dvec3 point(double s, double t, double d = 0.0) const;
    glm::dvec3 normal(double s, double t) const;    // outward
    glm::dvec3 tangent(double s, double t) const;   // d point / ds, normalized
    glm::dvec3 binormal(double s, double t) const;  // d point / dt, normalized
    // The texture tile's size on the top surface at (s, t): |d point / ds| and |d point / dt| (the paper's s_x and
    // s_y, section 3.4): width and height on the cylinder; on the sphere the width shrinks with the latitude.
    glm::dvec2 tile(double s, double t) const;
};

// The patch for a relief: the quad's width bent through `angle` radians (default 1.2), the top of the displacement
// range on the surface through the quad's centre raised to the top of the range. The sphere has the same radius.
CurvedPatch curved_patch_for(const ReliefTexture& t, CurvedPatch::Shape shape = CurvedPatch::Shape::cylinder,
                             double angle = 1.2);
// "cylinder", "sphere"; nullopt for anything else.
std::optional<CurvedPatch::Shape> parse_curved_shape(const std::string& name);
std::string to_string(CurvedPatch::Shape shape);

struct QuadricVertex {
    glm::vec3 position;
    glm::vec3 normal, tangent, binormal;
    glm::vec2 st;
    glm::vec2 quadric;  // (a, b) of z = a x^2 + b y^2 in the vertex's tangent frame (z along the outward normal)
    glm::vec2 tile;     // the texture tile's size at the vertex (CurvedPatch::tile)
};

// The base mesh, `segments` quads along a and `rows` along b, with the quadric coefficients fitted at each vertex
// to its neighbours (the vertices of the triangles sharing it). Positions are relative to `origin` (subtracted in
// double, so that a patch far from the world's origin keeps its digits in float).
void curved_base_mesh(const CurvedPatch& p, int segments, int rows, std::vector<QuadricVertex>& vertices,
                      std::vector<uint32_t>& indices, const glm::dvec3& origin = glm::dvec3(0.0));

// The relief displaced inwards on the patch: a vertex at each texel centre with its colour, triangles between
// texel centres (cells with an empty texel left out). Positions relative to `origin`, as above (draw with
// Renderer::draw_mesh's origin).
void curved_micromesh(const ReliefTexture& t, const CurvedPatch& p, std::vector<MeshVertex>& vertices,
                      std::vector<uint32_t>& indices, const glm::dvec3& origin = glm::dvec3(0.0));

}  // namespace rtm
