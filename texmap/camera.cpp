#include "texmap/camera.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rtm {
namespace {

// Clip planes used when none were chosen (z_near == 0): wide enough for a unit-scale scene.
constexpr double kDefaultNear = 0.01;
constexpr double kDefaultFar = 1000.0;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string str(const glm::dvec3& v) {
    std::ostringstream os;
    os.precision(9);
    os << "(" << v.x << "," << v.y << "," << v.z << ")";
    return os.str();
}

std::string str(double d) {
    std::ostringstream os;
    os.precision(9);
    os << d;
    return os.str();
}

}  // namespace

glm::dmat4 Camera::view() const { return glm::lookAt(eye, look_at, up); }

glm::dmat4 Camera::projection() const {
    double n = z_near, f = z_far;
    if (!(n > 0.0) || !(f > n)) {
        n = kDefaultNear;
        f = kDefaultFar;
    }
    return glm::perspective(glm::radians(fov_deg), double(width) / double(height), n, f);
}

void Camera::ray(double px, double py, glm::dvec3& origin, glm::dvec3& dir) const {
    const glm::dvec3 forward = glm::normalize(look_at - eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
    const glm::dvec3 true_up = glm::cross(right, forward);
    const double tan_half = std::tan(glm::radians(fov_deg) * 0.5);
    const double aspect = double(width) / double(height);
    // Normalized device coordinates of the pixel centre; py counts from the top row, NDC y points up.
    const double x_ndc = 2.0 * (px + 0.5) / double(width) - 1.0;
    const double y_ndc = 1.0 - 2.0 * (py + 0.5) / double(height);
    origin = eye;
    dir = glm::normalize(forward + (x_ndc * tan_half * aspect) * right + (y_ndc * tan_half) * true_up);
}

void Camera::fit_clip_planes(const glm::dvec3& centre, double radius) {
    if (!finite(centre) || !std::isfinite(radius)) return;  // validate() reports the camera; keep defaults
    radius = std::max(radius, 1e-9);
    const double d = glm::length(centre - eye);
    // 1% margins so geometry on the bounding sphere is not clipped by rounding.
    z_far = (d + radius) * 1.01;
    // A 24-bit depth buffer is comfortable with far/near up to ~1e4; an eye inside the sphere gets that ratio.
    z_near = std::max((d - radius) * 0.99, z_far * 1e-4);
}

CameraProblem Camera::check() const {
    using F = CameraField;
    if (!finite(eye)) return {F::eye, "eye " + str(eye) + " is not finite"};
    if (!finite(look_at)) return {F::look_at, "look-at " + str(look_at) + " is not finite"};
    if (!finite(up)) return {F::up, "up " + str(up) + " is not finite"};
    if (!std::isfinite(fov_deg) || !(fov_deg > 0.0 && fov_deg < 180.0))
        return {F::fov, "fov " + str(fov_deg) + " degrees is outside (0, 180)"};
    if (width <= 0 || height <= 0)
        return {F::size, "image size " + std::to_string(width) + "x" + std::to_string(height) + " is not positive"};
    const glm::dvec3 view_dir = look_at - eye;
    const double dist = glm::length(view_dir);
    const double scale = std::max({glm::length(eye), glm::length(look_at), 1.0});
    if (!(dist > 1e-12 * scale)) {
        if (eye == look_at) return {F::eye_and_look_at, "eye " + str(eye) + " equals look-at " + str(look_at)};
        return {F::eye_and_look_at, "eye " + str(eye) + " and look-at " + str(look_at) +
                                        " are closer than 1e-12 times the larger of 1 and their distance from the "
                                        "origin: the same point to the camera"};
    }
    const double up_len = glm::length(up);
    if (!(up_len > 0.0)) return {F::up, "up " + str(up) + " is the zero vector"};
    const double sin_angle = glm::length(glm::cross(view_dir / dist, up / up_len));
    if (!(sin_angle > 1e-9))
        return {F::up, "up " + str(up) + " is parallel to the view direction " + str(view_dir / dist)};
    if (!std::isfinite(z_near) || !std::isfinite(z_far)) return {F::clip_planes, "clip planes are not finite"};
    if (z_near < 0.0) return {F::clip_planes, "near plane " + str(z_near) + " is negative"};
    if (z_near > 0.0 && !(z_far > z_near))
        return {F::clip_planes, "far plane " + str(z_far) + " is not beyond the near plane " + str(z_near)};
    return {};
}

std::string Camera::to_string() const {
    std::ostringstream os;
    os << "Camera{eye=" << str(eye) << " look_at=" << str(look_at) << " up=" << str(up) << " fov=" << str(fov_deg)
       << " size=" << width << "x" << height << " near=" << str(z_near) << " far=" << str(z_far) << "}";
    return os.str();
}

}  // namespace rtm
