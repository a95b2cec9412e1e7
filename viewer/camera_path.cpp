#include "viewer/camera_path.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include "formats/image_io.h"
#include "formats/manifest_json.h"
#include "viewer/cameras.h"

namespace rtm::viewer {

namespace {

glm::dvec3 vec3_field(const nlohmann::json& j, const char* field, const std::string& where) {
    const nlohmann::json& v = j.at(field);
    if (!v.is_array() || v.size() != 3) throw IoError(where + ": \"" + field + "\" must be an array of 3 numbers");
    glm::dvec3 r;
    for (int i = 0; i < 3; ++i) {
        if (!v[size_t(i)].is_number()) throw IoError(where + ": \"" + field + "\" must be an array of 3 numbers");
        r[i] = v[size_t(i)].get<double>();
        if (!std::isfinite(r[i])) throw IoError(where + ": \"" + field + "\" has a value that is not finite");
    }
    return r;
}

glm::dvec3 key_eye(const PathKey& k, const Bounds& b) {
    if (!k.is_orbit) return k.eye;
    OrbitCamera o{k.orbit.x, k.orbit.y, k.orbit.z};
    return o.eye(b);
}

}  // namespace

CameraPath parse_camera_path(const std::string& text, const std::string& name) {
    const nlohmann::json j = manifest_json::parse(name, text);
    if (!j.is_object()) throw IoError(name + ": expected a JSON object with \"keys\"");
    CameraPath p;
    if (j.contains("fps")) {
        if (!j["fps"].is_number() || !(j["fps"].get<double>() > 0) || !std::isfinite(j["fps"].get<double>()))
            throw IoError(name + ": \"fps\" must be a number > 0");
        p.fps = j["fps"].get<double>();
    }
    if (!j.contains("keys") || !j["keys"].is_array() || j["keys"].empty())
        throw IoError(name + ": \"keys\" must be a non-empty array");
    for (size_t i = 0; i < j["keys"].size(); ++i) {
        const nlohmann::json& k = j["keys"][i];
        const std::string where = name + ": keys[" + std::to_string(i) + "]";
        if (!k.is_object()) throw IoError(where + ": expected an object");
        PathKey key;
        if (!k.contains("t") || !k["t"].is_number() || !std::isfinite(k["t"].get<double>()))
            throw IoError(where + ": \"t\" (seconds) is missing or not a number");
        key.t = k["t"].get<double>();
        if (i == 0 && key.t != 0) throw IoError(where + ": the first key must be at t = 0");
        if (i > 0 && !(key.t > p.keys.back().t)) throw IoError(where + ": \"t\" must increase from key to key");
        if (k.contains("orbit") == k.contains("eye"))
            throw IoError(where + ": expected exactly one of \"orbit\" and \"eye\"");
        if (k.contains("orbit")) {
            key.is_orbit = true;
            key.orbit = vec3_field(k, "orbit", where);
            if (!(key.orbit.z > 0)) throw IoError(where + ": the orbit distance must be > 0");
        } else {
            key.eye = vec3_field(k, "eye", where);
            if (k.contains("look_at")) {
                key.look_at = vec3_field(k, "look_at", where);
                key.has_look_at = true;
            }
        }
        if (k.contains("fov")) {
            if (!k["fov"].is_number() || !(k["fov"].get<double>() > 0 && k["fov"].get<double>() < 180))
                throw IoError(where + ": \"fov\" must be a number of degrees in (0, 180)");
            key.fov_deg = k["fov"].get<double>();
        }
        p.keys.push_back(key);
    }
    return p;
}

CameraPath load_camera_path(const std::string& path) {
    // A small regular file: a FIFO or a device is refused without being opened (read_text).
    return parse_camera_path(manifest_json::read_text(path, "camera path"), path);
}

namespace {

// The keys around time t and the fraction of the way from the first to the second.
void bracket(const std::vector<PathKey>& keys, double t, size_t& i0, size_t& i1, double& s) {
    i0 = 0;
    while (i0 + 1 < keys.size() && keys[i0 + 1].t <= t) ++i0;
    i1 = std::min(i0 + 1, keys.size() - 1);
    s = i0 == i1 ? 0.0 : (t - keys[i0].t) / (keys[i1].t - keys[i0].t);
}

}  // namespace

double CameraPath::fov_at(double t) const {
    if (keys.empty()) return 0;
    size_t i0 = 0, i1 = 0;
    double s = 0;
    bracket(keys, std::clamp(t, 0.0, duration()), i0, i1, s);
    if (keys[i0].fov_deg <= 0 || keys[i1].fov_deg <= 0) return 0;
    return keys[i0].fov_deg + s * (keys[i1].fov_deg - keys[i0].fov_deg);
}

void CameraPath::at(double t, const Bounds& b, glm::dvec3& eye, glm::dvec3& look_at) const {
    if (keys.empty()) return;
    t = std::clamp(t, 0.0, duration());
    size_t i0 = 0, i1 = 0;
    double s = 0;
    bracket(keys, t, i0, i1, s);
    const PathKey& k0 = keys[i0];
    const PathKey& k1 = keys[i1];
    auto target = [&](const PathKey& k) { return k.has_look_at ? k.look_at : b.centre(); };
    if (k0.is_orbit && k1.is_orbit) {
        PathKey mid = k0;
        mid.orbit = k0.orbit + s * (k1.orbit - k0.orbit);
        eye = key_eye(mid, b);
        look_at = b.centre();
        return;
    }
    eye = key_eye(k0, b) + s * (key_eye(k1, b) - key_eye(k0, b));
    look_at = target(k0) + s * (target(k1) - target(k0));
}

}  // namespace rtm::viewer
