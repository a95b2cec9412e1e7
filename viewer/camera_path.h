// A camera path for the viewer (--camera-path FILE): keyframes in time, played, paused and scrubbed. The file:
//   { "fps": 30,
//     "keys": [ { "t": 0.0, "orbit": [30, 20, 2.2] },
//               { "t": 2.0, "eye": [0.5, 1.2, 3.0], "look_at": [1.28, 0.64, 0.1], "fov": 50 } ] }
// "orbit" is AZ,EL,D as on the command line (about the centre of what is loaded); "eye" with an optional "look_at"
// (default: that centre) is a free camera; an optional "fov" (degrees) sets the vertical field of view. Times in
// seconds, strictly increasing from 0. Between two orbit keys the orbit parameters are interpolated linearly, otherwise
// the eye and look-at points are. Scripted (--frames), frame i shows time i / fps, so a run is the same frame by frame
// whatever the machine's speed.
#pragma once

#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "objects/bounds.h"

namespace rtm::viewer {

struct PathKey {
    double t = 0;
    bool is_orbit = false;
    glm::dvec3 orbit{0.0};  // az, el, d when is_orbit
    glm::dvec3 eye{0.0}, look_at{0.0};
    bool has_look_at = false;
    double fov_deg = 0;  // > 0: the field of view at this key; 0: the viewer's own
};

struct CameraPath {
    double fps = 30;
    std::vector<PathKey> keys;
    double duration() const { return keys.empty() ? 0.0 : keys.back().t; }
    // The eye and look-at at time t (clamped to [0, duration]).
    void at(double t, const Bounds& b, glm::dvec3& eye, glm::dvec3& look_at) const;
    // The field of view at time t, interpolated between keys that both give one; 0 when a key around t gives none.
    double fov_at(double t) const;
};

// Throws IoError naming the file and the field that is wrong.
CameraPath load_camera_path(const std::string& path);
CameraPath parse_camera_path(const std::string& json_text, const std::string& name);

}  // namespace rtm::viewer
