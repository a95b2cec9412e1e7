// The per-face decisions of an object's frame without OpenGL (objects/object_plan.h): outside-frustum, the level,
// subpixel-parallax, reuse when no point of the box behind the face moved (and only with the same adjacent faces and
// setup), and nothing skipped with skips off. ReliefObject::draw carries these plans out (object_render_test.cpp).
#include "objects/object_plan.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "objects/bounds.h"
#include "procedural/synthetic_object.h"
#include "texmap/camera_rig.h"
#include "warp/pyramid.h"

namespace rtm {
namespace {

constexpr int kPlusX = 0, kPlusZ = 4;

bool has(const ObjectFacePlan& p, const char* skip) {
    return std::find(p.skips.begin(), p.skips.end(), std::string(skip)) != p.skips.end();
}

struct Object {
    SixFaceObject o = make_synthetic_object(SyntheticShape::sphere, 32);
    std::vector<ReliefTexture> pyramid;  // of face +z
    Object() {
        const ReliefTexture& t = o.faces[kPlusZ];
        for (int i = 1; i < pyramid_levels(t.width, t.height); ++i)
            pyramid.push_back(downsample(pyramid.empty() ? t : pyramid.back(), t));
    }
    LevelSource levels() const {
        return [this](int i) -> const ReliefTexture& { return i == 0 ? o.faces[kPlusZ] : pyramid.at(size_t(i) - 1); };
    }
    Camera at(const glm::dvec3& eye) const {
        Camera cam = orbit_camera(centre(), radius(), {0, 0, 2.5}, 128, 128);
        cam.eye = eye;
        cam.fit_clip_planes(centre(), radius());
        return cam;
    }
    glm::dvec3 centre() const { return (o.box.lo + o.box.hi) * 0.5; }
    double radius() const { return glm::length(o.box.hi - o.box.lo) * 0.5; }
    ObjectFacePlan plan(const Camera& cam, const DrawOptions& d = {}, const LastFacePrewarp& last = {},
                        RenderMethod m = RenderMethod::two_pass) const {
        return plan_object_face(cam, m, PrewarpOptions{}, d, classify_region(o.box, cam.eye), kPlusZ, o.faces[kPlusZ],
                                levels(), o.box.extent()[2], last);
    }
};

LastFacePrewarp held(const ObjectFacePlan& p) { return {true, p.setup, p.k}; }

TEST(ObjectPlan, AFrontViewPrewarpsWithItsAdjacentFaces) {
    const Object ob;
    const Camera cam = ob.at(ob.centre() + glm::dvec3(0, 0, 2.5 * ob.radius()));
    const ObjectFacePlan p = ob.plan(cam);
    EXPECT_EQ(p.action, FrameAction::prewarp);
    EXPECT_TRUE(p.skips.empty());
    EXPECT_EQ(p.level, 0);
    EXPECT_EQ(p.setup.adjacent, (std::vector<int>{0, 1, 2, 3}));  // one-face view: the four sides
    EXPECT_FALSE(p.prewarp.keep_outliers);
}

TEST(ObjectPlan, TheSameEyeReusesAndANewEyePrewarps) {
    const Object ob;
    const glm::dvec3 eye = ob.centre() + glm::dvec3(0.1, 0.2, 2.5 * ob.radius());
    const ObjectFacePlan first = ob.plan(ob.at(eye));
    ASSERT_EQ(first.action, FrameAction::prewarp);
    const ObjectFacePlan again = ob.plan(ob.at(eye), {}, held(first));
    EXPECT_EQ(again.action, FrameAction::reuse);
    EXPECT_TRUE(has(again, kSkipReuse));
    // A tiny move stays within the tolerance; a large one does not.
    EXPECT_EQ(ob.plan(ob.at(eye + glm::dvec3(1e-6, 0, 0)), {}, held(first)).action, FrameAction::reuse);
    EXPECT_EQ(ob.plan(ob.at(eye + glm::dvec3(0.3, 0, 0)), {}, held(first)).action, FrameAction::prewarp);
    // Skips off, another setup (depth correction), or nothing held: pre-warp again.
    DrawOptions off;
    off.skips = false;
    EXPECT_EQ(ob.plan(ob.at(eye), off, held(first)).action, FrameAction::prewarp);
    DrawOptions depth;
    depth.depth_correction = true;
    EXPECT_EQ(ob.plan(ob.at(eye), depth, held(first)).action, FrameAction::prewarp);
    EXPECT_EQ(ob.plan(ob.at(eye), {}, {}).action, FrameAction::prewarp);
}

// Crossing into a region where +x is visible changes which faces are warped onto +z (-x no longer is): the held
// pre-warp cannot be reused, however small the move.
TEST(ObjectPlan, ARegionChangeIsNeverReused) {
    const Object ob;
    glm::dvec3 eye = ob.centre() + glm::dvec3(0, 0, 2.5 * ob.radius());
    eye.x = ob.o.box.hi.x - 1e-9;
    const ObjectFacePlan inside = ob.plan(ob.at(eye));
    ASSERT_EQ(inside.action, FrameAction::prewarp);
    eye.x = ob.o.box.hi.x + 1e-9;
    ASSERT_TRUE(classify_region(ob.o.box, eye).visible(kPlusX));
    const ObjectFacePlan outside = ob.plan(ob.at(eye), {}, held(inside));
    EXPECT_NE(outside.setup.adjacent, inside.setup.adjacent);
    EXPECT_EQ(outside.action, FrameAction::prewarp);
}

TEST(ObjectPlan, FarAwayTheFaceIsDrawnFlat) {
    const Object ob;
    const Camera cam = ob.at(ob.centre() + glm::dvec3(0, 0, 1e5 * ob.radius()));
    const ObjectFacePlan p = ob.plan(cam);
    EXPECT_EQ(p.action, FrameAction::flat);
    EXPECT_TRUE(has(p, kSkipSubpixelParallax));
    DrawOptions off;
    off.skips = false;
    EXPECT_EQ(ob.plan(cam, off).action, FrameAction::prewarp);
}

TEST(ObjectPlan, AFaceOutsideTheFrustumCostsNothing) {
    const Object ob;
    Camera cam = ob.at(ob.centre() + glm::dvec3(0, 0, 2.5 * ob.radius()));
    cam.look_at = cam.eye + glm::dvec3(0, 0, 1);  // looking away from the box
    const ObjectFacePlan p = ob.plan(cam);
    EXPECT_EQ(p.action, FrameAction::nothing);
    EXPECT_TRUE(has(p, kSkipOutsideFrustum));
}

TEST(ObjectPlan, TheLevelFollowsTheOptions) {
    const Object ob;
    const Camera cam = ob.at(ob.centre() + glm::dvec3(0, 0, 2.5 * ob.radius()));
    DrawOptions d;
    d.level = 2;
    EXPECT_EQ(ob.plan(cam, d).level, 2);
    d.level = 99;
    EXPECT_EQ(ob.plan(cam, d).level, pyramid_levels(32, 32) - 1);
    EXPECT_THROW(ob.plan(cam, {}, {}, RenderMethod::micromesh), std::invalid_argument);
    EXPECT_EQ(ob.plan(cam, {}, {}, RenderMethod::flat).action, FrameAction::flat);
}

}  // namespace
}  // namespace rtm
