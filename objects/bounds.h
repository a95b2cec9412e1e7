// Axis-aligned bounds of what is rendered; the orbit camera and the clip planes use the bounding sphere
// (centre of the box, radius = half its diagonal; docs/FORMATS.md, "CAMERA").
#pragma once

#include <glm/vec3.hpp>

#include <limits>

#include "warp/relief_texture.h"

namespace rtm {

struct Bounds {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()};
    glm::dvec3 hi{-std::numeric_limits<double>::infinity()};

    void extend(const glm::dvec3& p);
    void extend(const Bounds& b);
    bool empty() const { return !(lo.x <= hi.x); }
    glm::dvec3 centre() const { return (lo + hi) * 0.5; }
    double radius() const;  // half the diagonal
};

// The relief quad swept along f over the displacement range.
Bounds relief_bounds(const ReliefTexture& t);

}  // namespace rtm
