// NAME.scene.json reading and writing (docs/SCENES.md). Errors: one line, "<path>: item N: <what is wrong>".
#include "formats/scene_manifest.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "formats/atomic_file.h"
#include "formats/manifest_json.h"

namespace rtm {

using namespace manifest_json;

namespace {

// A scene is a list of placements; refuse absurd ones before allocating for them.
constexpr size_t kMaxItems = 100000;
constexpr int kMaxPathFrames = 1000000;
constexpr size_t kMaxPathKeys = 10000;
constexpr const char* kKinds = "\"relief\", \"polygon\", \"object\" or \"mesh\"";

double get_number(const std::string& path, const json& j, const std::string& where, const char* key,
                  const char* expected) {
    const json& v = required(path, j, where, key, expected);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        fail(path, where + "field \"" + key + "\" must be " + expected + ", found " + describe(v));
    return v.get<double>();
}

bool within_limit(const glm::dvec3& v) { return largest_coordinate(v) <= kMaxCoordinate; }

// `what` (e.g. "field \"eye\" ") is v; fails naming it when a coordinate lies beyond the limit.
void check_coordinates(const std::string& path, const std::string& where, const std::string& what,
                       const glm::dvec3& v) {
    if (!within_limit(v)) fail(path, where + what + fmt_vec(v) + " has a coordinate beyond +-1e30");
}

// get_vec3, within the coordinate limit.
glm::dvec3 get_point(const std::string& path, const json& j, const std::string& where, const char* key) {
    const glm::dvec3 v = get_vec3(path, j, where, key);
    check_coordinates(path, where, std::string("field \"") + key + "\" ", v);
    return v;
}

// A quad given by 4 coplanar points (the first three not collinear, unit normal n) must be strictly convex: the
// cross products of consecutive edges all point along n. The tolerance is on the sine of each corner's turn,
// |e_i x e_i+1| . n / (|e_i| |e_i+1|) > 1e-9: relative to the edge lengths, so independent of the quad's size, far
// above double rounding (1e-16 of the coordinates) and far below any corner a person draws (1e-9 radians). Returns
// what is wrong, or an empty string.
std::string convexity_problem(const std::vector<glm::dvec3>& v, const glm::dvec3& n) {
    constexpr double kMinTurn = 1e-9;
    double turn[4];
    int forward = 0, backward = 0;
    for (size_t i = 0; i < 4; ++i) {
        const glm::dvec3 e0 = v[(i + 1) % 4] - v[i], e1 = v[(i + 2) % 4] - v[(i + 1) % 4];
        const double l0 = glm::length(e0), l1 = glm::length(e1);
        if (!(l0 > 0))
            return "vertices " + std::to_string(i) + " and " + std::to_string((i + 1) % 4) + " are the same point";
        turn[i] = glm::dot(glm::cross(e0, e1), n) / (l0 * l1);  // the corner at vertex i + 1
        forward += turn[i] > kMinTurn;
        backward += turn[i] < -kMinTurn;
    }
    for (size_t i = 0; i < 4; ++i)
        if (!(std::abs(turn[i]) > kMinTurn))
            return "its corner at vertex " + std::to_string((i + 1) % 4) + " is straight";
    if (forward == 2 && backward == 2) return "its edges cross (a bow-tie: vertices in the wrong order)";
    for (size_t i = 0; i < 4; ++i)
        if ((turn[i] > 0) == (forward == 1))
            return "its corner at vertex " + std::to_string((i + 1) % 4) + " bends inward";
    return {};
}

SceneTransform parse_transform(const std::string& path, const json& item, const std::string& where) {
    SceneTransform t;
    auto it = item.find("transform");
    if (it == item.end()) return t;
    const json& tj = *it;
    if (!tj.is_object()) fail(path, where + "field \"transform\" must be an object, found " + describe(tj));
    const std::string w = where + "transform: ";
    if (tj.contains("translate")) t.translate = get_point(path, tj, w, "translate");
    if (tj.contains("scale")) {
        t.scale = get_number(path, tj, w, "scale", "a finite number > 0");
        if (!(t.scale > 0)) fail(path, w + "field \"scale\" must be > 0, found " + fmt_double(t.scale));
        // Squared lengths of the scaled axes must neither overflow nor underflow (the placement's similarity check),
        // and a unit-sized item scaled past 1e30 lies beyond the coordinate limit.
        if (!(t.scale >= 1.0 / kMaxCoordinate && t.scale <= kMaxCoordinate))
            fail(path, w + "field \"scale\" must be within 1e-30..1e30, found " + fmt_double(t.scale));
    }
    if (auto r = tj.find("rotate"); r != tj.end()) {
        // One rotation [ax, ay, az, deg] or a list of them.
        const bool single = r->is_array() && !r->empty() && (*r)[0].is_number();
        const json list = single ? json::array({*r}) : *r;
        if (!list.is_array() || list.size() > 16)
            fail(path, w + "field \"rotate\" must be [ax, ay, az, degrees] or a list of up to 16 of them, found " +
                           describe(*r));
        for (size_t i = 0; i < list.size(); ++i) {
            const json holder = {{"rotate", list[i]}};
            const std::vector<double> v = get_numbers(path, holder, w + "rotation " + std::to_string(i) + ": ",
                                                      "rotate", 4, "[ax, ay, az, degrees], 4 finite numbers");
            const glm::dvec3 axis(v[0], v[1], v[2]);
            if (!(glm::length(axis) > 1e-12))
                fail(path, w + "rotation " + std::to_string(i) + ": the axis " + fmt_vec(axis) + " has no direction");
            t.rotate.emplace_back(v[0], v[1], v[2], v[3]);
        }
    }
    return t;
}

SceneCameraKey parse_camera(const std::string& path, const json& j, const std::string& where) {
    if (!j.is_object()) fail(path, where + "must be an object, found " + describe(j));
    SceneCameraKey c;
    c.eye = get_point(path, j, where, "eye");
    c.look_at = get_point(path, j, where, "look_at");
    if (j.contains("up")) c.up = get_point(path, j, where, "up");
    if (j.contains("fov")) c.fov_deg = get_number(path, j, where, "fov", "degrees in (0, 180)");
    if (!(c.fov_deg > 0 && c.fov_deg < 180))
        fail(path, where + "field \"fov\" must be in (0, 180) degrees, found " + fmt_double(c.fov_deg));
    const glm::dvec3 d = c.look_at - c.eye;
    // Relative, as the camera's own check (Camera::check, texmap/camera.cpp): far from the origin, two points
    // closer than rounding can tell apart are the same point.
    const double scale = std::max({glm::length(c.eye), glm::length(c.look_at), 1.0});
    if (!(glm::length(d) > 1e-12 * scale)) {
        if (c.eye == c.look_at) fail(path, where + "\"eye\" and \"look_at\" are the same point " + fmt_vec(c.eye));
        fail(path, where + "\"eye\" " + fmt_vec(c.eye) + " and \"look_at\" " + fmt_vec(c.look_at) +
                       " are the same point to the camera (closer than 1e-12 times the larger of 1 and their distance "
                       "from the origin)");
    }
    if (!(glm::length(glm::cross(d, c.up)) > 1e-12 * glm::length(d) * glm::length(c.up)))
        fail(path, where + "\"up\" " + fmt_vec(c.up) + " is parallel to the view direction");
    return c;
}

SceneItem parse_item(const std::string& path, const json& j, size_t index) {
    const std::string where = "item " + std::to_string(index) + ": ";
    if (!j.is_object()) fail(path, where + "must be an object, found " + describe(j));
    const json& type = required(path, j, where, "type", kKinds);
    if (!type.is_string()) fail(path, where + "field \"type\" must be " + kKinds + ", found " + describe(type));
    const std::string& kind = type.get_ref<const std::string&>();
    SceneItem item;
    item.transform = parse_transform(path, j, where);
    if (kind == "relief") {
        item.kind = SceneItem::Kind::relief;
        item.relief_path = resolve(path, get_file_name(path, j, where, "relief"));
    } else if (kind == "polygon") {
        item.kind = SceneItem::Kind::polygon;
        const json& vs = required(path, j, where, "vertices", "3 or 4 points [x, y, z]");
        if (!vs.is_array() || vs.size() < 3 || vs.size() > 4)
            fail(path, where + "field \"vertices\" must be 3 or 4 points [x, y, z], found " + describe(vs));
        const glm::dmat4 m = item.transform.matrix();
        for (size_t i = 0; i < vs.size(); ++i) {
            const json holder = {{"vertex", vs[i]}};
            const std::string vertex = "vertices[" + std::to_string(i) + "]";
            const glm::dvec3 p = get_vec3(path, holder, where + vertex + ": ", "vertex");
            check_coordinates(path, where, vertex + " ", p);
            const glm::dvec3 placed(m * glm::dvec4(p, 1.0));
            check_coordinates(path, where, vertex + " " + fmt_vec(p) + " placed by the transform at ", placed);
            item.vertices.push_back(placed);
        }
        const glm::dvec3 n = glm::cross(item.vertices[1] - item.vertices[0], item.vertices[2] - item.vertices[0]);
        if (!(glm::length(n) > 0)) fail(path, where + "the polygon's first three vertices are collinear");
        if (item.vertices.size() == 4) {
            const glm::dvec3 un = glm::normalize(n);
            const double off = std::abs(glm::dot(item.vertices[3] - item.vertices[0], un));
            const double size = glm::length(item.vertices[2] - item.vertices[0]);
            if (off > 1e-6 * size) fail(path, where + "the polygon's fourth vertex is off the plane of the others");
            if (const std::string why = convexity_problem(item.vertices, un); !why.empty())
                fail(path, where + "the polygon is not convex: " + why);
        }
        if (j.contains("color")) {
            const std::vector<double> c = get_numbers(path, j, where, "color", 3, "[r, g, b], each in 0..1");
            for (double v : c)
                if (v < 0 || v > 1)
                    fail(path,
                         where + "field \"color\" must be [r, g, b], each in 0..1, found " + describe(j["color"]));
            item.color = {c[0], c[1], c[2]};
        }
    } else if (kind == "object") {
        item.kind = SceneItem::Kind::object;
        item.file_path = resolve(path, get_file_name(path, j, where, "object"));
    } else if (kind == "mesh") {
        item.kind = SceneItem::Kind::mesh;
        item.file_path = resolve(path, get_file_name(path, j, where, "mesh"));
    } else {
        fail(path, where + "field \"type\" must be " + kKinds + ", found " + describe(type));
    }
    return item;
}

json vec_json(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

// The transform's fields that differ from the identity (an empty object for none).
json transform_json(const SceneTransform& tr) {
    json t = json::object();
    if (tr.translate != glm::dvec3(0.0)) t["translate"] = vec_json(tr.translate);
    if (!tr.rotate.empty()) {
        json r = json::array();
        for (const glm::dvec4& q : tr.rotate) r.push_back(json::array({q.x, q.y, q.z, q.w}));
        t["rotate"] = r;
    }
    if (tr.scale != 1.0) t["scale"] = tr.scale;
    return t;
}

json camera_json(const SceneCameraKey& c) {
    return {{"eye", vec_json(c.eye)}, {"look_at", vec_json(c.look_at)}, {"up", vec_json(c.up)}, {"fov", c.fov_deg}};
}

}  // namespace

glm::dmat4 SceneTransform::matrix() const {
    glm::dmat4 r(1.0);
    for (const glm::dvec4& q : rotate)
        r = glm::rotate(glm::dmat4(1.0), glm::radians(q.w), glm::normalize(glm::dvec3(q))) * r;
    return glm::translate(glm::dmat4(1.0), translate) * r * glm::scale(glm::dmat4(1.0), glm::dvec3(scale));
}

SceneManifest parse_scene_manifest(const std::string& path) {
    const json j = parse(path, read_text(path, "scene manifest"));
    if (!j.is_object()) fail(path, "a scene manifest must be a JSON object, found " + describe(j));
    SceneManifest m;
    m.path = path;
    if (auto n = j.find("name"); n != j.end()) {
        if (!n->is_string()) fail(path, "field \"name\" must be a string, found " + describe(*n));
        m.name = n->get<std::string>();
    } else {
        std::string stem = std::filesystem::path(path).filename().string();
        for (const char* suffix : {".json", ".scene"})
            if (stem.size() > std::string(suffix).size() && stem.ends_with(suffix))
                stem.resize(stem.size() - std::string(suffix).size());
        m.name = stem;
    }
    const json& items = required(path, j, "", "items", "a list of items");
    if (!items.is_array() || items.empty() || items.size() > kMaxItems)
        fail(path, "field \"items\" must be a list of 1 to " + std::to_string(kMaxItems) + " items, found " +
                       describe(items));
    for (size_t i = 0; i < items.size(); ++i) m.items.push_back(parse_item(path, items[i], i));
    if (auto c = j.find("camera"); c != j.end()) m.camera = parse_camera(path, *c, "camera: ");
    if (auto p = j.find("camera_path"); p != j.end()) {
        if (!p->is_object()) fail(path, "field \"camera_path\" must be an object, found " + describe(*p));
        const double frames = get_number(path, *p, "camera_path: ", "frames", "an integer >= 2");
        if (!(frames >= 2 && frames <= kMaxPathFrames && frames == std::floor(frames)))
            fail(path, "camera_path: field \"frames\" must be an integer in 2.." + std::to_string(kMaxPathFrames) +
                           ", found " + fmt_double(frames));
        m.path_frames = int(frames);
        const json& keys = required(path, *p, "camera_path: ", "keys", "a list of at least 2 camera keys");
        if (!keys.is_array() || keys.size() < 2 || keys.size() > kMaxPathKeys)
            fail(path, "camera_path: field \"keys\" must be a list of 2 to " + std::to_string(kMaxPathKeys) +
                           " camera keys, found " + describe(keys));
        for (size_t i = 0; i < keys.size(); ++i)
            m.path_keys.push_back(parse_camera(path, keys[i], "camera_path: key " + std::to_string(i) + ": "));
    }
    return m;
}

void write_scene_manifest(const std::string& path, const SceneManifest& m) {
    json items = json::array();
    for (const SceneItem& it : m.items) {
        json j;
        if (it.kind != SceneItem::Kind::polygon) {
            const char* key = it.kind == SceneItem::Kind::relief   ? "relief"
                              : it.kind == SceneItem::Kind::object ? "object"
                                                                   : "mesh";
            j["type"] = key;
            j[key] = relative_to_manifest(path, it.kind == SceneItem::Kind::relief ? it.relief_path : it.file_path);
            if (json t = transform_json(it.transform); !t.empty()) j["transform"] = t;
        } else {
            j["type"] = "polygon";
            json vs = json::array();
            for (const glm::dvec3& v : it.vertices) vs.push_back(vec_json(v));
            j["vertices"] = vs;
            j["color"] = vec_json(it.color);
        }
        items.push_back(j);
    }
    json out = {{"name", m.name}, {"items", items}};
    if (m.camera) out["camera"] = camera_json(*m.camera);
    if (!m.path_keys.empty()) {
        json keys = json::array();
        for (const SceneCameraKey& k : m.path_keys) keys.push_back(camera_json(k));
        out["camera_path"] = {{"frames", m.path_frames}, {"keys", keys}};
    }
    write_text_atomically(path, out.dump(2) + "\n");
}

SceneCameraKey camera_path_frame(const std::vector<SceneCameraKey>& keys, int k, int n) {
    if (keys.size() < 2) throw std::invalid_argument("a camera path needs at least 2 keys");
    if (n < 2) throw std::invalid_argument("a camera path needs at least 2 frames, found " + std::to_string(n));
    if (k < 0 || k >= n)
        throw std::invalid_argument("frame " + std::to_string(k) + " is outside the path's 0.." +
                                    std::to_string(n - 1));
    const double t = double(k) * double(keys.size() - 1) / double(n - 1);
    const size_t i = std::min(size_t(t), keys.size() - 2);
    const double s = t - double(i);
    auto key = [&](long j) -> const SceneCameraKey& { return keys[size_t(std::clamp(j, 0L, long(keys.size()) - 1))]; };
    // Uniform Catmull-Rom through p1 and p2 with tangents from their neighbours.
    auto spline = [&](const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3) {
        const double s2 = s * s, s3 = s2 * s;
        return 0.5 * ((2.0 * p1) + (-p0 + p2) * s + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * s2 +
                      (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * s3);
    };
    const long li = long(i);
    SceneCameraKey c;
    c.eye = spline(key(li - 1).eye, key(li).eye, key(li + 1).eye, key(li + 2).eye);
    c.look_at = spline(key(li - 1).look_at, key(li).look_at, key(li + 1).look_at, key(li + 2).look_at);
    c.up = glm::normalize(glm::mix(key(li).up, key(li + 1).up, s));
    c.fov_deg = key(li).fov_deg + (key(li + 1).fov_deg - key(li).fov_deg) * s;
    return c;
}

}  // namespace rtm
