#include "texmap/camera_rig.h"

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace rtm {

glm::dvec3 orbit_eye(const glm::dvec3& centre, double radius, const OrbitPose& o) {
    const double az = glm::radians(o.azimuth), el = glm::radians(o.elevation);
    const double r = std::max(radius, 1e-12) * o.distance;
    return centre + r * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
}

Camera aimed_camera(const glm::dvec3& eye, const glm::dvec3& look_at, int width, int height) {
    Camera cam;
    cam.width = width;
    cam.height = height;
    cam.fov_deg = 45.0;
    cam.eye = eye;
    cam.look_at = look_at;
    cam.up = {0, 1, 0};
    return cam;
}

Camera orbit_camera(const glm::dvec3& centre, double radius, const OrbitPose& o, int width, int height) {
    Camera cam = aimed_camera(orbit_eye(centre, radius, o), centre, width, height);
    cam.fit_clip_planes(centre, std::max(radius, 1e-12));
    return cam;
}

}  // namespace rtm
