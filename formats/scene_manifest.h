// NAME.scene.json: relief quads and plain polygons placed in one world, with an optional default camera and an
// optional camera path (paper sections 1 and 4.4: relief textures as the building blocks of environments).
// Documented in docs/SCENES.md:
//   { "name": "town",
//     "items": [
//       { "type": "relief", "relief": "facade.relief.json",
//         "transform": { "translate": [x, y, z], "rotate": [[ax, ay, az, deg], ...], "scale": s } },
//       { "type": "polygon", "vertices": [[x, y, z], [x, y, z], [x, y, z], [x, y, z]], "color": [r, g, b] },
//       { "type": "object", "object": "duck.object.json", "transform": { ... } },
//       { "type": "mesh", "mesh": "room.ply", "transform": { ... } } ],
//     "camera": { "eye": [..], "look_at": [..], "up": [..], "fov": 45 },
//     "camera_path": { "frames": 120, "keys": [ { "eye": [..], "look_at": [..], "fov": 45 }, ... ] } }
// A transform is T * R * S: scale (uniform, > 0) first, then the rotations in the order listed (each about a
// non-zero axis through the origin, right-handed, degrees), then the translation. Relief quads and six-face
// objects keep their shape (a similarity), so displacements scale with `scale`; a mesh (any file assimp reads) has
// its vertices transformed. Polygons are convex, planar, 3 or 4 vertices, colour
// components in 0..1. Every point (translate, vertices before and after the transform, camera eye, look_at, up) lies
// within +-1e30 per coordinate, and scale within 1e-30..1e30. Unknown fields are ignored, malformed ones rejected:
// every error is an rtm::IoError, one line that starts with the scene manifest's path and names the item and the field.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <vector>

namespace rtm {

struct SceneTransform {
    glm::dvec3 translate{0.0};
    std::vector<glm::dvec4> rotate;  // (axis x, y, z, degrees), applied in order
    double scale = 1.0;
    glm::dmat4 matrix() const;  // T * R_n * ... * R_1 * S
};

struct SceneItem {
    enum class Kind { relief, polygon, object, mesh };
    Kind kind = Kind::relief;
    std::string relief_path;  // relief: resolved against the scene manifest's folder
    std::string file_path;    // object (NAME.object.json) or mesh (any file assimp reads): resolved likewise
    SceneTransform transform;
    std::vector<glm::dvec3> vertices;  // polygon: world positions (the transform already applied)
    glm::dvec3 color{0.5};             // polygon: linear 0..1
};

struct SceneCameraKey {
    glm::dvec3 eye{0.0}, look_at{0.0, 0.0, -1.0}, up{0.0, 1.0, 0.0};
    double fov_deg = 45.0;
};

struct SceneManifest {
    std::string path;
    std::string name;  // "name" field, or the file stem without ".scene"
    std::vector<SceneItem> items;
    std::optional<SceneCameraKey> camera;
    std::vector<SceneCameraKey> path_keys;  // camera_path.keys (at least 2 when present)
    int path_frames = 0;                    // camera_path.frames (>= 2 when present)
};

// Parses the JSON; does not read the reliefs it names (load_scene in objects/scene.h does).
SceneManifest parse_scene_manifest(const std::string& path);
// Writes the manifest (relief paths relative to its folder) atomically.
void write_scene_manifest(const std::string& path, const SceneManifest& m);

// The camera of frame k of n along the keys: a Catmull-Rom spline through the eyes and the look-at points (the end
// keys repeated as their own neighbours), field of view interpolated linearly; frame 0 is the first key and
// frame n - 1 the last. Throws std::invalid_argument for fewer than 2 keys, n < 2 or k outside 0..n-1.
SceneCameraKey camera_path_frame(const std::vector<SceneCameraKey>& keys, int k, int n);

}  // namespace rtm
