// The viewer's region around an object's bounding box (paper section 4.1, Figure 14 in 3-D): on each axis the eye
// is below the box (-1), level with it (0, the closed slab min <= e <= max) or above it (+1). The 3 x 3 x 3 cells are
// the 26 regions around the box plus the inside. A face is visible when the eye is strictly outside its plane: one,
// two or three faces. An eye exactly on a face's plane does not see that face (it is edge-on); that face and its
// opposite are then treated as the faces "beside" the view on that axis.
//
// Which faces are pre-warped onto a visible face F (the paper's order: these first, then F over them): every
// adjacent face G (perpendicular to F) except those whose opposite face is visible. In the paper's 2-D terms: in
// an odd region (one face seen, front) both left and right are pre-warped onto front; in an even region (two
// faces seen) only the other seen face is, onto each. In 3-D: four adjacent faces for a one-face view, three for
// each face of a two-face view and two for each face of a three-face view.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <string>
#include <vector>

#include "warp/box_faces.h"

namespace rtm {

struct ObjectRegion {
    std::array<int, 3> side{0, 0, 0};  // per axis: -1 below min, 0 within [min, max], +1 above max

    bool inside() const { return side[0] == 0 && side[1] == 0 && side[2] == 0; }
    // 0..26 in base 3 (side + 1 per axis, x most significant); 13 is the inside.
    int index() const { return (side[0] + 1) * 9 + (side[1] + 1) * 3 + (side[2] + 1); }
    bool visible(int face) const { return side[size_t(face_axis(face))] == int(face_sign(face)); }
    std::vector<int> visible_faces() const;  // in kFaceKeys order; 0 (inside) to 3
    std::string to_string() const;           // e.g. "region 22 (+x +z): faces +x +z"
};

ObjectRegion classify_region(const Box& box, const glm::dvec3& eye);

// The adjacent faces pre-warped onto visible face `face` (see the top of this file), in kFaceKeys order.
std::vector<int> faces_warped_onto(const ObjectRegion& region, int face);

}  // namespace rtm
