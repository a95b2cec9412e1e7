// The curved base mesh of relief mapping with quadric silhouettes (Oliveira and Policarpo, "An efficient
// representation for surface details", UFRGS tech. report RP-351, 2005): the relief's quad bent around a cylinder
// whose axis is parallel to b, behind the relief (the surface bulges towards +f). The top of the displacement
// range lies on the cylinder, arc length along a equal to the quad's width; depth goes inwards along the radius.
// The mesh carries per-vertex tangent frames and the quadric coefficients fitted per vertex by least squares
// (the paper's equation 2); curved_micromesh() is the truth: the relief displaced radially, one vertex a texel.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

#include "texmap/renderer.h"
#include "warp/relief_texture.h"

namespace rtm {

struct CylinderPatch {
    glm::dvec3 centre{0.0};  // on the axis, level with the middle of the quad along b
    glm::dvec3 a_hat{1, 0, 0}, b_hat{0, 1, 0}, f{0, 0, 1};
    double radius = 1.0, angle = 1.0;  // the patch spans azimuths [-angle/2, angle/2] about f
    double width = 1.0, height = 1.0;  // arc length along a (= radius * angle) and length along b (world units)
    double depth = 0.0;                // max - min of the displacement: how far the relief reaches inwards

    // The point at texture coordinates (s, t) in [0, 1]^2 and depth d (0 = top of the range, 1 = bottom).
    glm::dvec3 point(double s, double t, double d = 0.0) const;
    glm::dvec3 normal(double s) const;   // outward
    glm::dvec3 tangent(double s) const;  // d point / ds, normalized
};

// The patch for a relief: the quad's width bent through `angle` radians (default 1.2), the top of the displacement
// range on the cylinder through the quad's centre raised to the top of the range.
CylinderPatch cylinder_patch_for(const ReliefTexture& t, double angle = 1.2);

struct QuadricVertex {
    glm::vec3 position;
    glm::vec3 normal, tangent, binormal;
    glm::vec2 st;
    glm::vec2 quadric;  // (a, b) of z = a x^2 + b y^2 in the vertex's tangent frame (z along the outward normal)
};

// The base mesh, `segments` quads around and `rows` along b, with the quadric coefficients fitted at each vertex
// to its neighbours (the vertices of the triangles sharing it). Positions are relative to `origin` (subtracted in
// double, so that a patch far from the world's origin keeps its digits in float).
void cylinder_base_mesh(const CylinderPatch& p, int segments, int rows, std::vector<QuadricVertex>& vertices,
                        std::vector<uint32_t>& indices, const glm::dvec3& origin = glm::dvec3(0.0));

// The relief displaced inwards on the patch: a vertex at each texel centre with its colour, triangles between
// texel centres (cells with an empty texel left out). Positions relative to `origin`, as above (draw with
// Renderer::draw_mesh's origin).
void curved_micromesh(const ReliefTexture& t, const CylinderPatch& p, std::vector<MeshVertex>& vertices,
                      std::vector<uint32_t>& indices, const glm::dvec3& origin = glm::dvec3(0.0));

}  // namespace rtm
