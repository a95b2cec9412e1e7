// Camera paths: exact at the keys, linear between them, clamped outside, and errors that name the field.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/io_error.h"
#include "common/temp_dir.h"

#include "formats/image_io.h"
#include "viewer/camera_path.h"
#include "viewer/cameras.h"
#include "viewer/loaded_scene.h"

namespace rtm::viewer {
namespace {

const Bounds kBox{glm::dvec3(0), glm::dvec3(2, 2, 0.5)};

TEST(CameraPath, ExactAtKeysLinearBetween) {
    const CameraPath p = parse_camera_path(R"({"fps": 10, "keys": [
        {"t": 0, "eye": [0, 0, 5], "look_at": [0, 0, 0]},
        {"t": 2, "eye": [4, 0, 5]},
        {"t": 3, "orbit": [30, 20, 2.2]}, {"t": 4, "orbit": [50, 40, 1.2]}]})",
                                           "p.json");
    EXPECT_EQ(p.fps, 10);
    EXPECT_EQ(p.duration(), 4);
    glm::dvec3 e, l;
    p.at(0, kBox, e, l);
    EXPECT_EQ(e, glm::dvec3(0, 0, 5));
    EXPECT_EQ(l, glm::dvec3(0));
    p.at(1, kBox, e, l);  // halfway; the second key looks at the centre by default
    EXPECT_EQ(e, glm::dvec3(2, 0, 5));
    EXPECT_EQ(l, 0.5 * kBox.centre());
    p.at(3, kBox, e, l);
    EXPECT_EQ(e, (OrbitCamera{30, 20, 2.2}.eye(kBox)));
    p.at(3.5, kBox, e, l);  // between two orbit keys: the orbit parameters are interpolated
    EXPECT_NEAR(glm::length(e - OrbitCamera{40, 30, 1.7}.eye(kBox)), 0.0, 1e-12);
    p.at(99, kBox, e, l);
    EXPECT_EQ(e, (OrbitCamera{50, 40, 1.2}.eye(kBox)));
    p.at(-1, kBox, e, l);
    EXPECT_EQ(e, glm::dvec3(0, 0, 5));
}

// A camera path file is read like a manifest: a FIFO and a device are refused without being opened (the viewer
// waited for ever on either), a folder is named as one.
TEST(CameraPath, RefusesWhatIsNotARegularFile) {
    objects_testing::TempDir dir;
    objects_testing::expect_refuses_non_regular_files([](const std::string& p) { (void)load_camera_path(p); },
                                                      dir.path().string());
}

TEST(CameraPath, ErrorsNameTheFileAndField) {
    auto message = [](const std::string& text) {
        try {
            parse_camera_path(text, "bad.json");
        } catch (const IoError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("{").find("bad.json: truncated JSON"), std::string::npos);
    EXPECT_NE(message(R"({"keys": []})").find("\"keys\""), std::string::npos);
    EXPECT_NE(message(R"({"keys": [{"t": 1, "orbit": [0,0,1]}]})").find("t = 0"), std::string::npos);
    EXPECT_NE(message(R"({"keys": [{"t": 0, "orbit": [0,0,1]}, {"t": 0, "orbit": [0,0,1]}]})").find("keys[1]"),
              std::string::npos);
    EXPECT_NE(message(R"({"keys": [{"t": 0, "orbit": [0,0,0]}]})").find("distance"), std::string::npos);
    EXPECT_NE(message(R"({"keys": [{"t": 0, "eye": [0,0]}]})").find("\"eye\""), std::string::npos);
    EXPECT_NE(message(R"({"keys": [{"t": 0}]})").find("exactly one"), std::string::npos);
    EXPECT_NE(message(R"({"fps": 0, "keys": [{"t": 0, "eye": [0,0,1]}]})").find("\"fps\""), std::string::npos);
}

TEST(CameraPath, FieldOfViewBetweenKeysThatGiveOne) {
    const CameraPath p = parse_camera_path(R"({"keys": [{"t": 0, "eye": [0, 0, 1], "fov": 40},
        {"t": 2, "eye": [0, 0, 2], "fov": 60}, {"t": 3, "eye": [0, 0, 3]}]})",
                                           "p.json");
    EXPECT_EQ(p.fov_at(0), 40);
    EXPECT_EQ(p.fov_at(1), 50);
    EXPECT_EQ(p.fov_at(-1), 40);  // clamped
    EXPECT_EQ(p.fov_at(2.5), 0);  // the next key gives none: the viewer's own
    EXPECT_EQ(p.fov_at(3), 0);
    EXPECT_THROW(parse_camera_path(R"({"keys": [{"t": 0, "eye": [0, 0, 1], "fov": 180}]})", "p.json"), IoError);
}

// A scene's path as the viewer plays it: key k at t = k / fps is the scene's frame k (rtm render --scene
// --camera-path k), so scripted frame k shows it exactly.
TEST(CameraPath, SceneFramesAreKeys) {
    SceneManifest m;
    m.path_keys = {SceneCameraKey{glm::dvec3(0, 1, 5), glm::dvec3(0), glm::dvec3(0, 1, 0), 40},
                   SceneCameraKey{glm::dvec3(4, 1, 5), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), 60},
                   SceneCameraKey{glm::dvec3(4, 3, 1), glm::dvec3(1, 1, 0), glm::dvec3(0, 1, 0), 50}};
    m.path_frames = 7;
    const CameraPath p = scene_camera_path(m, 30);
    ASSERT_EQ(p.keys.size(), 7u);
    EXPECT_EQ(p.fps, 30);
    for (int k = 0; k < 7; ++k) {
        const SceneCameraKey want = camera_path_frame(m.path_keys, k, 7);
        glm::dvec3 e, l;
        p.at(k / 30.0, kBox, e, l);
        EXPECT_EQ(e, want.eye) << k;
        EXPECT_EQ(l, want.look_at) << k;
        EXPECT_EQ(p.fov_at(k / 30.0), want.fov_deg) << k;
    }
    EXPECT_TRUE(scene_camera_path(SceneManifest{}).keys.empty());
}

}  // namespace
}  // namespace rtm::viewer
