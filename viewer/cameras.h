// The viewer's two cameras, pure maths (no window). Orbit: azimuth, elevation and distance (in bounding-sphere
// radii) about the centre of what is loaded, as the command line's --orbit AZ,EL,D, or about a pivot (--orbit with
// --look-at: the point looked at). Fly: an eye with a heading
// (yaw about +y, pitch) moved with WASD and turned by the mouse. Both give a Camera for a bounding sphere.
#pragma once

#include <glm/vec3.hpp>

#include <optional>

#include "objects/bounds.h"
#include "texmap/camera.h"

namespace rtm::viewer {

struct OrbitCamera {
    OrbitCamera() = default;
    OrbitCamera(double azimuth, double elevation, double distance) : az(azimuth), el(elevation), dist(distance) {}
    double az = 30, el = 20, dist = 2.2;  // degrees, degrees, radii
    // The point orbited and looked at; none: the centre of what is loaded.
    std::optional<glm::dvec3> pivot;
    // The eye exactly as given (orbit_about), until the camera moves: az, el and dist recomputed from it give it back
    // only to within rounding, and the first frame is then the picture rtm render draws.
    std::optional<glm::dvec3> given_eye;
    void drag(double dx_pixels, double dy_pixels);  // 0.3 degree per pixel, elevation within +-89
    void zoom(double wheel_notches);                // 0.9 per notch, distance within [0.05, 1000]
    glm::dvec3 centre(const Bounds& b) const { return pivot ? *pivot : b.centre(); }
    glm::dvec3 eye(const Bounds& b) const;
    // F: back to the default distance about the centre of what is loaded.
    void frame() {
        dist = 2.2;
        pivot.reset();
        given_eye.reset();
    }
};

// The orbit camera about `pivot` that starts at `eye` (its distance in radii of `b`): --orbit AZ,EL,D with --look-at
// P starts at the view rtm render draws (the eye at AZ,EL,D about the centre, looking at P) and orbits P.
// `eye` != `pivot` (the command line's camera check).
OrbitCamera orbit_about(const glm::dvec3& pivot, const glm::dvec3& eye, const Bounds& b);

struct FlyCamera {
    glm::dvec3 eye{0.0, 0.0, 1.0};
    double yaw = 0, pitch = 0;  // degrees; forward = (sin yaw cos pitch, sin pitch, -cos yaw cos pitch)
    double speed = 1.0;         // world units per second
    glm::dvec3 forward() const;
    glm::dvec3 right() const;                       // horizontal, perpendicular to forward
    void look(double dx_pixels, double dy_pixels);  // 0.2 degree per pixel, pitch within +-89
    // Moves by `seconds` of travel at `speed` along forward (z), right (x) and +y (y).
    void move(const glm::dvec3& axes, double seconds);
    void scroll_speed(double wheel_notches);  // x1.25 per notch
    // Looks from `eye` at `target` (the heading of the orbit camera it takes over from).
    void look_from(const glm::dvec3& eye, const glm::dvec3& target);
    // F: frames what is loaded: keeps the heading, backs away from the centre to 2.2 radii.
    void frame(const Bounds& b);
};

// The camera looking from `eye` at `look_at` with the image size and field of view of `base`, its clip planes
// fitted to the bounds.
Camera make_camera(const Camera& base, const glm::dvec3& eye, const glm::dvec3& look_at, const Bounds& b);

}  // namespace rtm::viewer
