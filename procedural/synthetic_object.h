// Six-face objects of known geometry for tests and media (paper section 4.1): an analytic shape inside the box
// [-1, 1]^3, sampled on each face of the box by orthographic ray casting into the box (the face's parallel
// projection: from each texel centre on the face, along -f), giving colour and depth. Texels whose ray misses the
// shape get alpha 0. Deterministic.
//   sphere     - the unit sphere at the origin, coloured by longitude and latitude bands;
//   cross-box  - the cube [-0.8, 0.8]^3 with a raised cross on each face (arms 0.3 wide and 1.4 long, standing
//                0.2 out to the bounding box), coloured per part with a checker;
//   rounded-cube - the cube [-1, 1]^3 cut by the sphere of radius 1.3: flat discs on the faces of the box and rounded
//                edges and corners, so that the surface meets the box along every edge's middle (for crack tests).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "warp/box_faces.h"
#include "warp/image.h"

namespace rtm {

enum class SyntheticShape { sphere, cross_box, rounded_cube };

SyntheticShape parse_synthetic_shape(
    const std::string& s);  // "sphere", "cross-box", "rounded-cube"; throws std::invalid_argument
std::string to_string(SyntheticShape s);

// The first hit of the ray origin + t*dir (t > 0, dir unit length) with the shape: its distance and colour.
bool synthetic_hit(SyntheticShape s, const glm::dvec3& origin, const glm::dvec3& dir, double& t, Rgba8& color);

struct SyntheticFace {
    ImageRGBA8 color;     // alpha 0 where the ray missed
    ImageF displacement;  // world units along the outward normal, <= 0 (0 where empty)
};

inline const Box kSyntheticBox{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}};

// The six faces at n x n texels each, in kFaceKeys order.
std::array<SyntheticFace, kFaceCount> synthetic_faces(SyntheticShape s, int n);
// The discontinuity threshold the synthetic objects use: three texel spacings (a slope steeper than about 72
// degrees between neighbours is left to the adjacent faces, paper section 4.1.1).
double synthetic_discontinuity(int n);
// The object itself (relief textures with their discontinuities marked), as load_object would give it.
SixFaceObject make_synthetic_object(SyntheticShape s, int n);

}  // namespace rtm
