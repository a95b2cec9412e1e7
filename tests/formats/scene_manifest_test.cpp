// NAME.scene.json: the write -> parse round trip, the camera path's interpolation, and hostile scenes: one IoError
// line that starts with the manifest's path and names the item and the field.
#include "formats/scene_manifest.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/io_error.h"
#include "common/temp_dir.h"
#include "formats/image_io.h"

namespace rtm {
namespace {

using objects_testing::expect_io_error;
using objects_testing::TempDir;
using objects_testing::write_file;

SceneManifest sample(const std::string& dir) {
    SceneManifest m;
    m.path = dir + "/s.scene.json";
    m.name = "s";
    SceneItem r;
    r.kind = SceneItem::Kind::relief;
    r.relief_path = dir + "/media/wall.relief.json";
    r.transform.translate = {1, 2, 3};
    r.transform.rotate = {{0, 1, 0, 90}, {1, 0, 0, -30}};
    r.transform.scale = 0.5;
    m.items.push_back(r);
    SceneItem p;
    p.kind = SceneItem::Kind::polygon;
    p.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 0, -1}, {0, 0, -1}};
    p.color = {0.25, 0.5, 1.0};
    m.items.push_back(p);
    SceneItem o;
    o.kind = SceneItem::Kind::object;
    o.file_path = dir + "/media/duck.object.json";
    o.transform.translate = {0, 0.5, 0};
    o.transform.rotate = {{0, 1, 0, 30}};
    m.items.push_back(o);
    SceneItem mesh;
    mesh.kind = SceneItem::Kind::mesh;
    mesh.file_path = dir + "/meshes/room.ply";
    mesh.transform.scale = 2;
    m.items.push_back(mesh);
    m.camera = SceneCameraKey{{0, 1, 5}, {0, 0, 0}, {0, 1, 0}, 50};
    m.path_keys = {{{0, 1, 5}, {0, 0, 0}, {0, 1, 0}, 40}, {{5, 1, 5}, {5, 0, 0}, {0, 1, 0}, 60}};
    m.path_frames = 30;
    return m;
}

TEST(SceneManifest, RoundTrip) {
    TempDir dir;
    const SceneManifest m = sample(dir.path().string());
    write_scene_manifest(m.path, m);
    const SceneManifest r = parse_scene_manifest(m.path);
    EXPECT_EQ(r.name, "s");
    ASSERT_EQ(r.items.size(), 4u);
    EXPECT_EQ(r.items[0].relief_path, m.items[0].relief_path);
    EXPECT_EQ(r.items[0].transform.translate, m.items[0].transform.translate);
    ASSERT_EQ(r.items[0].transform.rotate.size(), 2u);
    EXPECT_EQ(r.items[0].transform.rotate[1], m.items[0].transform.rotate[1]);
    EXPECT_EQ(r.items[0].transform.scale, 0.5);
    EXPECT_EQ(r.items[1].vertices, m.items[1].vertices);
    EXPECT_EQ(r.items[1].color, m.items[1].color);
    EXPECT_EQ(r.items[2].kind, SceneItem::Kind::object);
    EXPECT_EQ(r.items[2].file_path, m.items[2].file_path);
    EXPECT_EQ(r.items[2].transform.translate, m.items[2].transform.translate);
    ASSERT_EQ(r.items[2].transform.rotate.size(), 1u);
    EXPECT_EQ(r.items[3].kind, SceneItem::Kind::mesh);
    EXPECT_EQ(r.items[3].file_path, m.items[3].file_path);
    EXPECT_EQ(r.items[3].transform.scale, 2.0);
    // Paths are written relative to the manifest.
    std::ifstream in(m.path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"meshes/room.ply\""), std::string::npos) << text;
    ASSERT_TRUE(r.camera.has_value());
    EXPECT_EQ(r.camera->eye, m.camera->eye);
    EXPECT_EQ(r.path_frames, 30);
    ASSERT_EQ(r.path_keys.size(), 2u);
    EXPECT_EQ(r.path_keys[1].fov_deg, 60.0);
}

TEST(SceneManifest, TransformIsTranslateRotateScale) {
    SceneTransform t;
    t.translate = {1, 2, 3};
    t.rotate = {{0, 1, 0, 90}, {1, 0, 0, 90}};  // about y first, then about x
    t.scale = 2;
    const glm::dvec3 p = glm::dvec3(t.matrix() * glm::dvec4(1, 0, 0, 1));
    // scale: (2,0,0); about y by 90: (0,0,-2); about x by 90: (0,2,0); translate: (1,4,3).
    EXPECT_NEAR(p.x, 1, 1e-12);
    EXPECT_NEAR(p.y, 4, 1e-12);
    EXPECT_NEAR(p.z, 3, 1e-12);
}

TEST(SceneManifest, CameraPathPassesThroughItsKeys) {
    std::vector<SceneCameraKey> keys = {{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 40},
                                        {{1, 0, 0}, {1, 0, -1}, {0, 1, 0}, 50},
                                        {{2, 1, 0}, {2, 1, -1}, {0, 1, 0}, 60}};
    // 5 frames over 3 keys: frames 0, 2 and 4 are the keys themselves (Catmull-Rom interpolates).
    for (int k : {0, 2, 4}) {
        const SceneCameraKey c = camera_path_frame(keys, k, 5);
        EXPECT_NEAR(glm::length(c.eye - keys[size_t(k / 2)].eye), 0.0, 1e-12) << "frame " << k;
        EXPECT_NEAR(c.fov_deg, keys[size_t(k / 2)].fov_deg, 1e-12);
    }
    const SceneCameraKey mid = camera_path_frame(keys, 1, 5);
    EXPECT_NEAR(mid.fov_deg, 45.0, 1e-12);  // linear in fov
    EXPECT_GT(mid.eye.x, 0.0);
    EXPECT_LT(mid.eye.x, 1.0);
    EXPECT_THROW(camera_path_frame(keys, 5, 5), std::invalid_argument);
    EXPECT_THROW(camera_path_frame(keys, 0, 1), std::invalid_argument);
    EXPECT_THROW(camera_path_frame({keys[0]}, 0, 2), std::invalid_argument);
}

struct Hostile {
    const char* label;
    const char* json;
    std::vector<std::string> parts;  // what the message must name
};

TEST(SceneManifest, HostileScenesGiveOneLineNamingTheField) {
    const std::vector<Hostile> cases = {
        {"not an object", "[1, 2]", {"JSON object"}},
        {"truncated", R"({"items": [)", {"truncated"}},
        {"no items", R"({"name": "x"})", {"\"items\"", "missing"}},
        {"empty items", R"({"items": []})", {"\"items\""}},
        {"unknown type", R"({"items": [{"type": "teapot"}]})", {"item 0", "\"type\"", "teapot"}},
        {"relief without file", R"({"items": [{"type": "relief"}]})", {"item 0", "\"relief\""}},
        {"object without file", R"({"items": [{"type": "object"}]})", {"item 0", "\"object\""}},
        {"object file a number", R"({"items": [{"type": "object", "object": 7}]})", {"item 0", "\"object\""}},
        {"mesh without file", R"({"items": [{"type": "mesh", "file": "room.ply"}]})", {"item 0", "\"mesh\""}},
        {"mesh empty name", R"({"items": [{"type": "mesh", "mesh": ""}]})", {"item 0", "\"mesh\""}},
        {"mesh bad transform",
         R"({"items": [{"type": "mesh", "mesh": "a.ply", "transform": {"rotate": [[0, 1, 0]]}}]})",
         {"item 0", "rotat"}},
        {"object type not a string",
         R"({"items": [{"type": ["object"], "object": "a.object.json"}]})",
         {"item 0", "\"type\"", "\"mesh\""}},
        {"nan translate",
         R"({"items": [{"type": "relief", "relief": "a.relief.json", "transform": {"translate": [0, "x", 0]}}]})",
         {"item 0", "translate"}},
        {"zero scale",
         R"({"items": [{"type": "relief", "relief": "a.json", "transform": {"scale": 0}}]})",
         {"item 0", "scale"}},
        {"zero axis",
         R"({"items": [{"type": "relief", "relief": "a.json", "transform": {"rotate": [0, 0, 0, 30]}}]})",
         {"item 0", "axis"}},
        {"two vertices", R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0]]}]})", {"item 0", "vertices"}},
        {"collinear",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[2,0,0]]}]})",
         {"item 0", "collinear"}},
        {"off plane",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,1]]}]})",
         {"item 0", "off the plane"}},
        {"colour range",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0]], "color": [2,0,0]}]})",
         {"item 0", "color"}},
        {"second item bad",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0]]}, 7]})",
         {"item 1"}},
        {"camera eye at look_at",
         R"({"items": [{"type": "relief", "relief": "a.json"}], "camera": {"eye": [1,1,1], "look_at": [1,1,1]}})",
         {"camera", "same point"}},
        {"camera fov",
         R"({"items": [{"type": "relief", "relief": "a.json"}],
                          "camera": {"eye": [0,0,1], "look_at": [0,0,0], "fov": 190}})",
         {"camera", "fov"}},
        {"path one frame",
         R"({"items": [{"type": "relief", "relief": "a.json"}], "camera_path": {"frames": 1,
                              "keys": [{"eye": [0,0,1], "look_at": [0,0,0]}, {"eye": [1,0,1], "look_at": [0,0,0]}]}})",
         {"camera_path", "frames"}},
        {"path one key",
         R"({"items": [{"type": "relief", "relief": "a.json"}], "camera_path": {"frames": 10,
                             "keys": [{"eye": [0,0,1], "look_at": [0,0,0]}]}})",
         {"camera_path", "keys"}},
        // The coordinate limit (+-1e30, docs/DESIGN.md "Input limits"): refused here, naming the item and the field,
        // not later by the camera flag that placed an eye about them.
        {"translate beyond the limit",
         R"({"items": [{"type": "relief", "relief": "a.json", "transform": {"translate": [1e300, 0, 0]}}]})",
         {"item 0: transform: field \"translate\" [1e+300, 0.0, 0.0] has a coordinate beyond +-1e30"}},
        {"translate of an object just beyond",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0]]},
                       {"type": "object", "object": "o.object.json", "transform": {"translate": [0, 0, -2e30]}}]})",
         {"item 1: transform: field \"translate\" [0.0, 0.0, -2e+30] has a coordinate beyond +-1e30"}},
        {"huge scale",
         R"({"items": [{"type": "mesh", "mesh": "m.ply", "transform": {"scale": 1e300}}]})",
         {"item 0: transform: field \"scale\" must be within 1e-30..1e30, found 1e+300"}},
        {"tiny scale",
         R"({"items": [{"type": "relief", "relief": "a.json", "transform": {"scale": 1e-300}}]})",
         {"item 0: transform: field \"scale\" must be within 1e-30..1e30, found 1e-300"}},
        {"vertex beyond the limit",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0],[1e300,1,0]]}]})",
         {"item 0: vertices[3] [1e+300, 1.0, 0.0] has a coordinate beyond +-1e30"}},
        {"vertex placed beyond the limit",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1e10,0,0],[0,1,0]],
                        "transform": {"scale": 1e30}}]})",
         {"item 0: vertices[1] [10000000000.0, 0.0, 0.0] placed by the transform at [1e+40, 0.0, 0.0]",
          "beyond +-1e30"}},
        {"camera eye beyond the limit",
         R"({"items": [{"type": "relief", "relief": "a.json"}], "camera": {"eye": [1e300,0,0], "look_at": [0,0,0]}})",
         {"camera: field \"eye\" [1e+300, 0.0, 0.0] has a coordinate beyond +-1e30"}},
        {"camera look_at beyond the limit",
         R"({"items": [{"type": "relief", "relief": "a.json"}], "camera": {"eye": [0,0,1], "look_at": [0,-1e31,0]}})",
         {"camera: field \"look_at\" [0.0, -1e+31, 0.0] has a coordinate beyond +-1e30"}},
        {"camera up beyond the limit",
         R"({"items": [{"type": "relief", "relief": "a.json"}],
             "camera": {"eye": [0,0,1], "look_at": [0,0,0], "up": [0,1e40,0]}})",
         {"camera: field \"up\" [0.0, 1e+40, 0.0] has a coordinate beyond +-1e30"}},
        {"path key beyond the limit",
         R"({"items": [{"type": "relief", "relief": "a.json"}], "camera_path": {"frames": 10,
             "keys": [{"eye": [0,0,1], "look_at": [0,0,0]}, {"eye": [5e30,0,1], "look_at": [0,0,0]}]}})",
         {"camera_path: key 1: field \"eye\" [5e+30, 0.0, 1.0] has a coordinate beyond +-1e30"}},
        // As Camera::check: closer than 1e-12 times the larger of 1 and their distance from the origin is one point.
        {"camera eye at look_at within rounding",
         R"({"items": [{"type": "relief", "relief": "a.json"}], "camera": {"eye": [1e20,0,0], "look_at": [1e20,1,0]}})",
         {"camera: \"eye\" [1e+20, 0.0, 0.0] and \"look_at\" [1e+20, 1.0, 0.0] are the same point to the camera"}},
        // Convexity of 4-vertex polygons (docs/SCENES.md: "3 or 4 vertices, convex and planar").
        {"bow-tie",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,1,0],[1,0,0],[0,1,0]]}]})",
         {"item 0: the polygon is not convex: its edges cross"}},
        {"bow-tie placed second",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
                       {"type": "polygon", "vertices": [[0,0,0],[1,0,1],[1,0,0],[0,0,1]],
                        "transform": {"rotate": [1, 2, 3, 40], "translate": [5, 5, 5]}}]})",
         {"item 1: the polygon is not convex: its edges cross"}},
        {"reflex corner",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[0.1,0.1,0],[0,1,0]]}]})",
         {"item 0: the polygon is not convex: its corner at vertex 2 bends inward"}},
        {"reflex corner at the first vertex",
         R"({"items": [{"type": "polygon", "vertices": [[0.1,0.1,0],[0,1,0],[0,0,0],[1,0,0]]}]})",
         {"item 0: the polygon is not convex: its corner at vertex 0 bends inward"}},
        {"straight corner",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0.5,0.5,0]]}]})",
         {"item 0: the polygon is not convex: its corner at vertex 3 is straight"}},
        {"repeated vertex",
         R"({"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0],[1,1,0]]}]})",
         {"item 0: the polygon is not convex: vertices 2 and 3 are the same point"}},
    };
    TempDir dir;
    for (const Hostile& h : cases) {
        const std::string path = (dir.path() / "bad.scene.json").string();
        write_file(path, h.json);
        expect_io_error([&] { parse_scene_manifest(path); }, path, h.parts, h.label);
    }
    EXPECT_THROW(parse_scene_manifest((dir.path() / "missing.scene.json").string()), IoError);
}

// What the new checks must still accept: convex quads in either winding and every starting vertex, placed by a
// rotation; corners turning by far less than a person draws but more than the 1e-9 tolerance; points at the limit.
TEST(SceneManifest, ConvexQuadsAndPointsAtTheLimitAreAccepted) {
    TempDir dir;
    const std::string path = (dir.path() / "ok.scene.json").string();
    const std::string rotated = R"(, "transform": {"rotate": [[1, 2, 3, 70]], "translate": [4, 5, 6]})";
    const std::vector<std::pair<std::string, std::string>> quads = {
        {"[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]", rotated},                         // counter-clockwise about +z
        {"[[0,1,0],[1,1,0],[1,0,0],[0,0,0]]", rotated},                         // clockwise
        {"[[1,1,0],[0,1,0],[0,0,0],[1,0,0]]", rotated},                         // another starting vertex
        {"[[0,0,0],[2,0,0],[1.01,0.5,0],[0,1,0]]", rotated},                    // nearly a triangle, still convex
        {"[[0,0,0],[1,0,0],[1,1,0],[0.5,0.5000001,0]]", rotated},               // a corner turning by about 2e-7
        {"[[0,0,0],[0,0,3],[0,2,3],[0,2,0]]", ""},                              // in another plane
        {"[[-1e30,-1e30,0],[1e30,-1e30,0],[1e30,1e30,0],[-1e30,1e30,0]]", ""},  // at the limit
    };
    for (const auto& [q, transform] : quads) {
        write_file(path, R"({"items": [{"type": "polygon", "vertices": )" + q + transform + "}]}");
        SceneManifest m;
        ASSERT_NO_THROW(m = parse_scene_manifest(path)) << q;
        EXPECT_EQ(m.items.at(0).vertices.size(), 4u) << q;
    }
    write_file(path, R"({"items": [{"type": "relief", "relief": "a.json",
                                    "transform": {"translate": [1e30, -1e30, 0], "scale": 1e30}},
                                   {"type": "relief", "relief": "a.json", "transform": {"scale": 1e-30}}],
                         "camera": {"eye": [1e30, 0, 0], "look_at": [0, 0, -1e30], "up": [0, 1e30, 0]},
                         "camera_path": {"frames": 2, "keys": [{"eye": [-1e30, 0, 1], "look_at": [0, 0, 0]},
                                                               {"eye": [0, 0, 1e30], "look_at": [0, 0, 0]}]}})");
    const SceneManifest m = parse_scene_manifest(path);
    EXPECT_EQ(m.items[0].transform.translate, glm::dvec3(1e30, -1e30, 0));
    EXPECT_EQ(m.items[0].transform.scale, 1e30);
    EXPECT_EQ(m.items[1].transform.scale, 1e-30);
    EXPECT_EQ(m.camera->eye, glm::dvec3(1e30, 0, 0));
    EXPECT_EQ(m.path_keys.at(1).eye, glm::dvec3(0, 0, 1e30));
}

}  // namespace
}  // namespace rtm
