// The camera: projection and ray() agree with each other and with the command line's conventions.
#include "texmap/camera.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec4.hpp>

#include <cmath>
#include <limits>
#include <random>

namespace rtm {
namespace {

// Window coordinates of a world point: x to the right, y down from the top row (pixel centres at +0.5), and the
// NDC depth in [-1, 1] when inside the clip volume.
glm::dvec3 to_window(const Camera& cam, const glm::dvec3& p) {
    glm::dvec4 c = cam.projection() * cam.view() * glm::dvec4(p, 1.0);
    glm::dvec3 ndc = glm::dvec3(c) / c.w;
    return {(ndc.x + 1.0) * 0.5 * cam.width, (1.0 - ndc.y) * 0.5 * cam.height, ndc.z};
}

Camera oblique_camera() {
    Camera cam;
    cam.eye = {3.0, 2.0, 5.0};
    cam.look_at = {0.5, -0.25, 0.1};
    cam.up = {0.1, 1.0, 0.0};
    cam.fov_deg = 50.0;
    cam.width = 320;
    cam.height = 200;
    return cam;
}

TEST(Camera, LookAtProjectsToTheImageCentre) {
    Camera cam = oblique_camera();
    glm::dvec3 w = to_window(cam, cam.look_at);
    EXPECT_NEAR(w.x, 160.0, 1e-9);
    EXPECT_NEAR(w.y, 100.0, 1e-9);
    EXPECT_GT(w.z, -1.0);
    EXPECT_LT(w.z, 1.0);
}

TEST(Camera, RayThroughTheCentrePixelOfAnOddImagePointsAtLookAt) {
    Camera cam = oblique_camera();
    cam.width = 101;
    cam.height = 51;
    glm::dvec3 o, d;
    cam.ray(50, 25, o, d);
    EXPECT_EQ(o, cam.eye);
    glm::dvec3 expected = glm::normalize(cam.look_at - cam.eye);
    EXPECT_NEAR(glm::length(d - expected), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
}

TEST(Camera, RayAndProjectionAgreeOnEveryPixelCentre) {
    Camera cam = oblique_camera();
    std::mt19937 rng(7);
    for (int i = 0; i < 200; ++i) {
        int px = int(rng() % uint32_t(cam.width)), py = int(rng() % uint32_t(cam.height));
        glm::dvec3 o, d;
        cam.ray(px, py, o, d);
        glm::dvec3 w = to_window(cam, o + 4.0 * d);
        ASSERT_NEAR(w.x, px + 0.5, 1e-8) << "pixel " << px << "," << py;
        ASSERT_NEAR(w.y, py + 0.5, 1e-8) << "pixel " << px << "," << py;
    }
}

TEST(Camera, TopRowLooksUpAndLeftColumnLooksLeft) {
    Camera cam;  // eye on +z looking at the origin, up +y
    glm::dvec3 o, top, left;
    cam.ray(cam.width / 2, 0, o, top);
    cam.ray(0, cam.height / 2, o, left);
    EXPECT_GT(top.y, 0.0);
    EXPECT_LT(left.x, 0.0);
    // The top row's ray is half the field of view above the axis, less half a pixel.
    double half_fov = std::atan(std::tan(glm::radians(cam.fov_deg) / 2) * (1.0 - 1.0 / cam.height));
    EXPECT_NEAR(std::atan2(top.y, -top.z), half_fov, 1e-12);
}

TEST(Camera, AspectRatioWidensTheHorizontalField) {
    Camera cam;
    cam.width = 200;
    cam.height = 100;
    cam.fov_deg = 90.0;  // vertical: at distance 1 the view is 2 high and 4 wide
    glm::dvec3 w = to_window(cam, {2.0, 1.0, 0.0});
    EXPECT_NEAR(w.x, 200.0, 1e-9);
    EXPECT_NEAR(w.y, 0.0, 1e-9);
}

TEST(Camera, DefaultClipPlanesWhenNearIsZero) {
    Camera cam;  // z_near == 0
    cam.eye = {0, 0, 0};
    cam.look_at = {0, 0, -1};
    EXPECT_GT(to_window(cam, {0, 0, -0.011}).z, -1.0);  // just beyond near = 0.01
    EXPECT_LT(to_window(cam, {0, 0, -0.009}).z, -1.0);
    EXPECT_LT(to_window(cam, {0, 0, -999.0}).z, 1.0);  // just before far = 1000
    EXPECT_GT(to_window(cam, {0, 0, -1001.0}).z, 1.0);
}

TEST(Camera, FitClipPlanesEnclosesTheSphere) {
    Camera cam = oblique_camera();
    glm::dvec3 centre{0.5, -0.25, 0.1};
    double radius = 2.0;
    cam.fit_clip_planes(centre, radius);
    EXPECT_EQ(cam.validate(), "");
    glm::dvec3 toward = glm::normalize(cam.eye - centre);
    double front = to_window(cam, centre + radius * toward).z, back = to_window(cam, centre - radius * toward).z;
    EXPECT_GT(front, -1.0);
    EXPECT_LT(back, 1.0);
    EXPECT_LT(front, back);

    // Eye inside the sphere: near stays positive and small, far reaches past the sphere.
    cam.fit_clip_planes(cam.eye, 10.0);
    EXPECT_GT(cam.z_near, 0.0);
    EXPECT_GE(cam.z_far, 10.0);
    EXPECT_EQ(cam.validate(), "");
}

TEST(Camera, ValidateAcceptsTheDefaults) {
    EXPECT_EQ(Camera().validate(), "");
    EXPECT_EQ(oblique_camera().validate(), "");
}

TEST(Camera, ValidateNamesWhatIsWrong) {
    auto message = [](auto change) {
        Camera cam;
        change(cam);
        return cam.validate();
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_NE(message([](Camera& c) { c.look_at = c.eye; }).find("equals look-at"), std::string::npos);
    EXPECT_NE(message([](Camera& c) { c.up = {0, 0, -3}; }).find("parallel"), std::string::npos);
    EXPECT_NE(message([](Camera& c) { c.up = {0, 0, 0}; }).find("zero"), std::string::npos);
    for (double fov : {0.0, -10.0, 180.0, 200.0, nan})
        EXPECT_NE(message([&](Camera& c) { c.fov_deg = fov; }).find("fov"), std::string::npos) << fov;
    EXPECT_NE(message([](Camera& c) { c.width = 0; }).find("size 0x512"), std::string::npos);
    EXPECT_NE(message([](Camera& c) { c.height = -4; }).find("not positive"), std::string::npos);
    EXPECT_NE(message([&](Camera& c) { c.eye.x = nan; }).find("eye"), std::string::npos);
    EXPECT_NE(message([&](Camera& c) { c.look_at.y = inf; }).find("not finite"), std::string::npos);
    EXPECT_NE(message([&](Camera& c) { c.up.z = nan; }).find("up"), std::string::npos);
    EXPECT_NE(message([](Camera& c) {
                  c.z_near = 2.0;
                  c.z_far = 1.0;
              }).find("far plane"),
              std::string::npos);
}

TEST(Camera, ToStringShowsTheValues) {
    Camera cam = oblique_camera();
    std::string s = cam.to_string();
    EXPECT_NE(s.find("eye=(3,2,5)"), std::string::npos) << s;
    EXPECT_NE(s.find("fov=50"), std::string::npos) << s;
    EXPECT_NE(s.find("320x200"), std::string::npos) << s;
}

}  // namespace
}  // namespace rtm
