// The viewer's cameras: the orbit camera is the command line's --orbit; the fly camera takes over its view.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "viewer/cameras.h"

namespace rtm::viewer {
namespace {

Bounds unit_box() { return Bounds{glm::dvec3(-1, -2, -3), glm::dvec3(3, 2, 1)}; }

TEST(OrbitCamera, ZeroAzimuthAndElevationIsOnThePlusZSide) {
    const Bounds b = unit_box();
    OrbitCamera o{0, 0, 2};
    const glm::dvec3 e = o.eye(b);
    EXPECT_DOUBLE_EQ(e.x, b.centre().x);
    EXPECT_DOUBLE_EQ(e.y, b.centre().y);
    EXPECT_DOUBLE_EQ(e.z, b.centre().z + 2 * b.radius());
}

TEST(OrbitCamera, DragClampsElevationAndZoomClampsDistance) {
    OrbitCamera o;
    o.drag(0, 1e6);
    EXPECT_EQ(o.el, 89.0);
    o.drag(0, -1e6);
    EXPECT_EQ(o.el, -89.0);
    o.zoom(-1e4);
    EXPECT_EQ(o.dist, 1000.0);
    o.zoom(1e4);
    EXPECT_EQ(o.dist, 0.05);
    o.frame();
    EXPECT_EQ(o.dist, 2.2);
}

TEST(FlyCamera, LookFromFacesTheTarget) {
    FlyCamera f;
    const glm::dvec3 eye(1, 2, 3), target(-2, 0.5, -1);
    f.look_from(eye, target);
    const glm::dvec3 want = glm::normalize(target - eye);
    // Degrees through asin/atan2 and back through sin/cos: a few ulps.
    EXPECT_NEAR(glm::length(f.forward() - want), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(f.right(), f.forward()), 0.0, 1e-12);
    EXPECT_EQ(f.right().y, 0.0);
}

TEST(FlyCamera, MoveIsSpeedTimesTimeAlongTheAxes) {
    FlyCamera f;
    f.eye = {0, 0, 0};
    f.yaw = 0;
    f.pitch = 0;  // forward -z, right +x
    f.speed = 2;
    f.move({0, 0, 1}, 0.5);
    EXPECT_NEAR(f.eye.z, -1.0, 1e-15);
    f.move({1, 1, 0}, 0.25);
    EXPECT_NEAR(f.eye.x, 0.5, 1e-15);
    EXPECT_NEAR(f.eye.y, 0.5, 1e-15);
    f.scroll_speed(1);
    EXPECT_DOUBLE_EQ(f.speed, 2.5);
}

TEST(FlyCamera, FrameBacksAwayFromTheCentreKeepingTheHeading) {
    const Bounds b = unit_box();
    FlyCamera f;
    f.yaw = 40;
    f.pitch = -10;
    f.frame(b);
    EXPECT_NEAR(glm::length(f.eye - b.centre()), 2.2 * b.radius(), 1e-12);
    EXPECT_NEAR(glm::length(glm::normalize(b.centre() - f.eye) - f.forward()), 0.0, 1e-12);
}

TEST(MakeCamera, FitsClipPlanesToTheBounds) {
    const Bounds b = unit_box();
    Camera base;
    base.width = 64;
    base.height = 32;
    const Camera c = make_camera(base, b.centre() + glm::dvec3(0, 0, 10), b.centre(), b);
    EXPECT_EQ(c.width, 64);
    EXPECT_GT(c.z_near, 0.0);
    EXPECT_LE(c.z_near, 10 - b.radius());
    EXPECT_GE(c.z_far, 10 + b.radius());
}

}  // namespace
}  // namespace rtm::viewer
