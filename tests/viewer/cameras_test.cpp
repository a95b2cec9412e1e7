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

// --orbit with --look-at: the orbit starts at the eye given and turns about the point looked at.
TEST(OrbitCamera, AboutAPivotStartsAtTheEyeAndKeepsItsDistance) {
    const Bounds b = unit_box();
    const glm::dvec3 pivot(2.5, -1.0, 0.5);
    OrbitCamera about_centre{40, 25, 1.7};
    const glm::dvec3 eye = about_centre.eye(b);  // render's eye for --orbit 40,25,1.7
    OrbitCamera o = orbit_about(pivot, eye, b);
    EXPECT_EQ(o.eye(b), eye);  // exactly: the first frame is render's picture
    EXPECT_EQ(o.centre(b), pivot);
    // The angles and distance recomputed from it give the eye back to rounding (degrees through asin and atan2 and
    // back through sin and cos: a few ulps of the coordinates, about 1e-15 here).
    OrbitCamera moved = o;
    moved.drag(0, 0);
    EXPECT_FALSE(moved.given_eye.has_value());
    EXPECT_NEAR(glm::length(moved.eye(b) - eye), 0.0, 1e-13);
    // A drag turns about the pivot at the same distance; a zoom scales that distance.
    const double r = glm::length(eye - pivot);
    moved.drag(120, -35);
    EXPECT_NEAR(glm::length(moved.eye(b) - pivot), r, 1e-13);
    EXPECT_GT(glm::length(moved.eye(b) - eye), 0.1);
    moved.zoom(2);
    EXPECT_NEAR(glm::length(moved.eye(b) - pivot), 0.81 * r, 1e-13);
    // F frames what is loaded: its centre at the default distance.
    moved.frame();
    EXPECT_EQ(moved.centre(b), b.centre());
    EXPECT_NEAR(glm::length(moved.eye(b) - b.centre()), 2.2 * b.radius(), 1e-13);
    // An eye straight above the pivot: elevation held at the drag's 89 degrees, the given eye still exact.
    const OrbitCamera above = orbit_about(pivot, pivot + glm::dvec3(0, 3, 0), b);
    EXPECT_EQ(above.el, 89.0);
    EXPECT_EQ(above.eye(b), pivot + glm::dvec3(0, 3, 0));
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
