// The bake: six orthographic colour and depth views of a mesh, one from outside each face of its bounding box
// looking in, each a relief texture whose quad is that face (the six-face object of docs/BAKE.md).
//
// Face frames (origin, a, b; cross(a, b) = f is the OUTWARD normal, so displacements are <= 0):
//   +z: (x0,y0,z1), a +x, b +y     -z: (x1,y0,z0), a -x, b +y
//   +x: (x1,y0,z1), a -z, b +y     -x: (x0,y0,z0), a +z, b +y
//   +y: (x0,y1,z1), a +x, b -z     -y: (x0,y0,z0), a +x, b +z
// |a| = box extent along a's axis / width, |b| likewise. Texel (i, r), r from the top row, records the surface
// seen along -f through u = i + 0.5, v = h - 1 - r + 0.5 (the relief convention): its colour (alpha 255) and its
// displacement, the signed distance from the face plane, in [-(extent along f), 0]. Texels where no surface was
// seen have alpha 0 and displacement 0.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "mesh/triangle_mesh.h"
#include "warp/box_faces.h"  // kFaceKeys
#include "warp/image.h"
#include "warp/relief_texture.h"

namespace rtm {

// The box a bake uses: the mesh bounds, each axis thickened to at least one texel, and the texel counts.
struct BakeBox {
    glm::dvec3 lo{0.0}, hi{0.0};
    std::array<int, 3> texels{1, 1, 1};  // along x, y, z
    glm::dvec3 extent() const { return hi - lo; }
};

// N = texels along the longest side; the others proportional, rounded, at least 1. An axis thinner than one texel
// (a flat mesh) is thickened symmetrically to one texel, and a warning naming the axis is added. Throws
// std::invalid_argument when the bounds are a single point or not finite, or N is outside 1..16384.
BakeBox bake_box(const glm::dvec3& lo, const glm::dvec3& hi, int n, std::vector<std::string>* warnings);

// The relief frame of face `key` (one of kFaceKeys) of the box: origin, a, b as in the table above.
ReliefGeometry face_geometry(const BakeBox& box, const std::string& key, int* width = nullptr, int* height = nullptr);

struct BakedFace {
    std::string key;
    ReliefGeometry geometry;
    ImageRGBA8 color;                       // alpha 255 seen, 0 empty
    ImageF displacement;                    // world units along f, <= 0; 0 where empty
    double range_lo = 0.0, range_hi = 0.0;  // over the seen texels; [0, 0] when none
    // Surface discontinuities (paper section 4.1.1): neighbouring texels whose displacements differ by more than
    // this (world units) are not connected, so no skin is stretched across a silhouette and the adjacent faces,
    // which see what lies behind it, fill the hole. kBakeDiscontinuityTexels texel spacings; 0 = none.
    double discontinuity = 0.0;
};

// The bake's discontinuity threshold in texel spacings (the larger of the face's two): a surface is cut where it
// turns steeper than atan(12) = 85 degrees from the face, where an adjacent face sees it better. Chosen by the ring
// of views of measure/object_accuracy.h on three models, 2, 6 and 12 tried (docs/ACCURACY.md, "Objects baked from
// meshes").
inline constexpr double kBakeDiscontinuityTexels = 12.0;

struct BakedObject {
    BakeBox box;
    std::array<BakedFace, 6> faces;  // in kFaceKeys order
    std::vector<std::string> warnings;
};

class MeshRenderer;

// The orthographic view of a relief frame: clip space maps texel coordinates (u, v) of g onto the viewport of
// width x height pixels (x_ndc = 2u/width - 1, y_ndc = 2v/height - 1, so pixel centres are texel centres) and the
// displacement slab [d_lo, d_hi] along f, widened by a small margin, onto depth, nearer +f first.
glm::dmat4 relief_view_clip(const ReliefGeometry& g, int width, int height, double d_lo, double d_hi);
// One view along -f of what lies in the slab [d_lo, d_hi]: colour (alpha 255 seen, 0 empty), displacement clamped
// to the slab (0 where empty) and the range seen ([0, 0] when nothing). key is left empty. cull_back_faces: faces
// seen from behind (wound clockwise as seen from +f) are not recorded (MeshRenderer::render).
BakedFace bake_view(MeshRenderer& renderer, const ReliefGeometry& g, int width, int height, double d_lo, double d_hi,
                    bool cull_back_faces = false);

// Renders the six views through MeshRenderer; needs a current GlContext. `progress(done, 6)` after each face.
BakedObject bake_object(const TriangleMesh& mesh, int n, const std::function<void(int, int)>& progress = {});

// Writes DIR/NAME.object.json with the images beside it (NAME_px_color.png, NAME_px_disp.png, ... for +x, -x ->
// px, nx, ...): RGBA8 colour, 16-bit displacement normalized over each face's range. Images first, the manifest
// last and atomically; on failure nothing written by this call is left. Returns the manifest's path.
std::string write_object(const std::string& dir, const std::string& name, const BakedObject& obj,
                         const std::string& source = {});

}  // namespace rtm
