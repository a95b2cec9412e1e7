#include "warp/quadrants.h"

#include <algorithm>

namespace rtm {

QuadrantOverlay quadrant_overlay(const glm::dvec2& p0, const glm::dvec2& p1, const glm::dvec2& epipole) {
    QuadrantOverlay o;
    const glm::dvec2 e{std::clamp(epipole.x, p0.x, p1.x), std::clamp(epipole.y, p0.y, p1.y)};
    o.epipole = e;
    o.inside = e == epipole;
    o.quadrants[0] = {p0, e, {255, 60, 60, 40}};
    o.quadrants[1] = {{e.x, p0.y}, {p1.x, e.y}, {60, 255, 60, 40}};
    o.quadrants[2] = {{p0.x, e.y}, {e.x, p1.y}, {60, 120, 255, 40}};
    o.quadrants[3] = {e, p1, {255, 255, 60, 40}};
    return o;
}

}  // namespace rtm
