// The six faces of an object's bounding box as relief textures (paper section 4.1, Figure 13): each face is a
// parallel-projection image with depth looking into the box, whose quad is the box face and whose normal f points
// out of the box, so displacements are <= 0 (the surface lies inside the box).
//
// Face frames (origin, a direction, b direction); |a| = box extent along a's axis / width, |b| likewise:
//     +z: origin (x0,y0,z1), a +x, b +y        -z: origin (x1,y0,z0), a -x, b +y
//     +x: origin (x1,y0,z1), a -z, b +y        -x: origin (x0,y0,z0), a +z, b +y
//     +y: origin (x0,y1,z1), a +x, b -z        -y: origin (x0,y0,z0), a +x, b +z
// cross(a, b) is the outward normal in each case. Face indices follow kFaceKeys: +x, -x, +y, -y, +z, -z, so face
// i's axis is i / 2 and its opposite is i ^ 1.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <string>

#include "relief_texture.h"

namespace rtm {

inline constexpr int kFaceCount = 6;
inline constexpr std::array<const char*, kFaceCount> kFaceKeys = {"+x", "-x", "+y", "-y", "+z", "-z"};

// Index of a face key ("+x" ...), or -1.
int face_index(const std::string& key);
inline int face_axis(int face) { return face / 2; }
inline int opposite_face(int face) { return face ^ 1; }
inline double face_sign(int face) { return (face & 1) ? -1.0 : 1.0; }

struct Box {
    glm::dvec3 lo{0.0}, hi{0.0};
    glm::dvec3 extent() const { return hi - lo; }
    std::string to_string() const;
};

// The axis (0, 1, 2) that a face's a (which = 0) or b (which = 1) direction runs along.
int face_step_axis(int face, int which);
// The relief geometry of face `face` of `box` for an image of width x height texels (the table above).
ReliefGeometry box_face_geometry(const Box& box, int face, int width, int height);

// Six relief textures on the faces of a box: an image-based object (paper section 4.1).
struct SixFaceObject {
    std::string name;
    Box box;
    std::array<ReliefTexture, kFaceCount> faces;
};

}  // namespace rtm
