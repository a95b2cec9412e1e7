#include "viewer/cameras.h"

#include "texmap/camera_rig.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace rtm::viewer {

namespace {
double radius_of(const Bounds& b) { return std::max(b.radius(), 1e-12); }
}  // namespace

void OrbitCamera::drag(double dx, double dy) {
    given_eye.reset();
    az -= 0.3 * dx;
    el = std::clamp(el + 0.3 * dy, -89.0, 89.0);
}

void OrbitCamera::zoom(double notches) {
    if (notches != 0) given_eye.reset();
    dist = std::clamp(dist * std::pow(0.9, notches), 0.05, 1000.0);
}

glm::dvec3 OrbitCamera::eye(const Bounds& b) const {
    if (given_eye) return *given_eye;
    return orbit_eye(centre(b), radius_of(b), {az, el, dist});  // --orbit's formula (texmap/camera_rig.h)
}

OrbitCamera orbit_about(const glm::dvec3& pivot, const glm::dvec3& eye, const Bounds& b) {
    OrbitCamera o;
    const glm::dvec3 d = eye - pivot;
    const double len = glm::length(d);
    o.pivot = pivot;
    o.given_eye = eye;
    o.dist = len / radius_of(b);
    // The inverse of eye()'s direction: elevation from y, azimuth about +y from +z towards +x; the elevation within
    // the drag's +-89 degrees, so that the first drag turns from here (straight above or below: azimuth 0).
    o.el = len > 0 ? std::clamp(glm::degrees(std::asin(std::clamp(d.y / len, -1.0, 1.0))), -89.0, 89.0) : 0.0;
    o.az = d.x != 0 || d.z != 0 ? glm::degrees(std::atan2(d.x, d.z)) : 0.0;
    return o;
}

glm::dvec3 FlyCamera::forward() const {
    const double y = glm::radians(yaw), p = glm::radians(pitch);
    return {std::sin(y) * std::cos(p), std::sin(p), -std::cos(y) * std::cos(p)};
}

glm::dvec3 FlyCamera::right() const {
    const double y = glm::radians(yaw);
    return {std::cos(y), 0.0, std::sin(y)};
}

void FlyCamera::look(double dx, double dy) {
    yaw += 0.2 * dx;
    pitch = std::clamp(pitch - 0.2 * dy, -89.0, 89.0);
}

void FlyCamera::move(const glm::dvec3& axes, double seconds) {
    eye += speed * seconds * (axes.z * forward() + axes.x * right() + axes.y * glm::dvec3(0, 1, 0));
}

void FlyCamera::scroll_speed(double notches) { speed = std::clamp(speed * std::pow(1.25, notches), 1e-9, 1e12); }

void FlyCamera::look_from(const glm::dvec3& from, const glm::dvec3& target) {
    eye = from;
    const glm::dvec3 d = target - from;
    const double len = glm::length(d);
    if (!(len > 0)) return;
    pitch = glm::degrees(std::asin(std::clamp(d.y / len, -1.0, 1.0)));
    yaw = glm::degrees(std::atan2(d.x, -d.z));
}

void FlyCamera::frame(const Bounds& b) { eye = b.centre() - forward() * (2.2 * radius_of(b)); }

Camera make_camera(const Camera& base, const glm::dvec3& eye, const glm::dvec3& look_at, const Bounds& b) {
    Camera c = base;
    c.eye = eye;
    c.look_at = look_at;
    c.z_near = c.z_far = 0.0;
    c.fit_clip_planes(b.centre(), radius_of(b));
    return c;
}

}  // namespace rtm::viewer
