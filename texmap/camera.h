// A perspective pinhole camera (docs/FORMATS.md, "CAMERA"): eye, look-at, up, vertical field of
// view in degrees, image size. Right-handed, looking down -z in eye space as OpenGL does. Double precision.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <string>

namespace rtm {

// Which setting makes a camera unusable (Camera::check): the one a user changes to fix it.
enum class CameraField { none, eye, look_at, eye_and_look_at, up, fov, size, clip_planes };

struct CameraProblem {
    CameraField field = CameraField::none;  // none: usable
    std::string message;                    // empty when usable, else what is wrong, naming the values
};

struct Camera {
    glm::dvec3 eye{0.0, 0.0, 1.0};
    glm::dvec3 look_at{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fov_deg = 45.0;
    int width = 512;
    int height = 512;
    double z_near = 0.0;  // 0 = chosen from the scene bounds by fit_clip_planes
    double z_far = 0.0;

    glm::dmat4 view() const;
    glm::dmat4 projection() const;
    // Ray through the pixel centre (px + 0.5, py + 0.5), py counted from the TOP row; direction normalized.
    void ray(double px, double py, glm::dvec3& origin, glm::dvec3& dir) const;
    // Chooses near/far planes that enclose a bounding sphere (centre, radius) seen from the eye.
    void fit_clip_planes(const glm::dvec3& centre, double radius);
    // Whether the camera is usable, else which setting is wrong and how (eye == look_at, up parallel to view, fov
    // range, ...).
    CameraProblem check() const;
    // check().message: an empty string when usable, else what is wrong.
    std::string validate() const { return check().message; }
    std::string to_string() const;
};

}  // namespace rtm
