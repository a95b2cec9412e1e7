// The pyramid level of a six-face object's faces at `--level auto` (objects/object_plan.h): each visible face takes
// the relief quad's parallax-bounded choice on its own texture (objects/level_choice.h), the level a ReliefQuad of
// that face draws from the same camera, both in the plan (without OpenGL) and in what ReliefObject::draw reports.
// Before, a face took the density level alone. rtm prewarp --object --level auto picks the same levels as render
// (tests/cli/object_level.sh).
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "common/seed.h"
#include "objects/level_choice.h"
#include "objects/object_plan.h"
#include "objects/relief_object.h"
#include "procedural/synthetic_object.h"
#include "texmap/gl_context.h"

namespace rtm {
namespace {

constexpr int kTexels = 128;  // per face side: levels 0 to 7
constexpr int kPixels = 256;

// The cross-box: arms standing 0.2 out of each face, so a block straddling an arm's edge spreads its displacements
// and the parallax bound can hold a face finer than its density level.
SixFaceObject cross_box() { return make_synthetic_object(SyntheticShape::cross_box, kTexels); }

Camera camera(const glm::dvec3& eye) {
    Camera cam;
    cam.eye = eye;
    cam.look_at = glm::dvec3(0.0);
    cam.width = cam.height = kPixels;
    cam.fit_clip_planes(glm::dvec3(0.0), std::sqrt(3.0));
    return cam;
}

glm::dvec3 orbit(double az_deg, double el_deg, double d) {
    const double az = glm::radians(az_deg), el = glm::radians(el_deg), r = std::sqrt(3.0) * d;
    return r * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
}

// A random sweep of views around the box, near and far: for every visible face, the plan's level is the relief
// quad's on the face's texture. The sweep must reach views where the bound holds a face finer than its density
// level, and views where a face still goes coarse (else it would not tell the two rules apart).
TEST(ObjectFaceLevel, EachFaceTakesTheLevelItsReliefQuadDraws) {
    const uint64_t seed = test::test_seed(20261202);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::printf("seed %llu\n", (unsigned long long)seed);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> az(0.0, 360.0), el(-85.0, 85.0), logd(std::log(1.3), std::log(60.0));
    const SixFaceObject object = cross_box();
    std::vector<std::unique_ptr<ReliefQuad>> alone;
    for (const ReliefTexture& t : object.faces) alone.push_back(std::make_unique<ReliefQuad>(t));
    DrawOptions d;
    d.level = -1;
    d.skips = false;  // every visible face reaches the level choice (no outside-frustum or subpixel-parallax first)
    int bounded = 0, coarse = 0, faces = 0;
    const int cases = test::sweep_cases(400);
    for (int i = 0; i < cases; ++i) {
        const Camera cam = camera(orbit(az(rng), el(rng), std::exp(logd(rng))));
        const ObjectRegion region = classify_region(object.box, cam.eye);
        ASSERT_FALSE(region.inside());
        for (int f : region.visible_faces()) {
            ReliefQuad& q = *alone[size_t(f)];
            const ObjectFacePlan p = plan_object_face(
                cam, RenderMethod::two_pass, PrewarpOptions{}, d, region, f, q.relief(),
                [&](int l) -> const ReliefTexture& { return q.level(l); }, object.box.extent()[face_axis(f)], {},
                &q.spreads());
            const int want = q.choose_level(cam, d.level_error_px);
            ASSERT_EQ(p.level, want) << "case " << i << " face " << kFaceKeys[size_t(f)];
            // Without the cached spreads the plan computes them itself: the same level.
            const ObjectFacePlan own = plan_object_face(cam, RenderMethod::two_pass, PrewarpOptions{}, d, region, f,
                                                        q.relief(),
                                                        [&](int l) -> const ReliefTexture& { return q.level(l); },
                                                        object.box.extent()[face_axis(f)], {});
            ASSERT_EQ(own.level, want) << "case " << i << " face " << kFaceKeys[size_t(f)];
            ++faces;
            bounded += want < auto_level(cam, q.relief());
            coarse += want > 0;
        }
    }
    std::printf("%d faces over %d views: %d held finer than the density level, %d coarser than level 0\n", faces, cases,
                bounded, coarse);
    EXPECT_GT(bounded, 0);
    EXPECT_GT(coarse, 0);
}

// What ReliefObject::draw reports as each face's level is the same choice, and a fixed level still overrides it.
TEST(ObjectFaceLevel, TheObjectDrawsEachFaceAtThatLevel) {
    auto ctx = GlContext::create_offscreen(kPixels, kPixels);
    Renderer renderer;
    const SixFaceObject object = cross_box();
    ReliefObject drawn(object);
    std::vector<std::unique_ptr<ReliefQuad>> alone;
    for (const ReliefTexture& t : object.faces) alone.push_back(std::make_unique<ReliefQuad>(t));
    PrewarpOptions o;
    DrawOptions d;
    d.level = -1;
    d.depth_correction = true;
    int bounded = 0;
    for (const glm::dvec3& eye : {orbit(45, 35, 3), orbit(80, 5, 6), orbit(10, 80, 12), orbit(200, -30, 25),
                                  orbit(89, 1, 40), orbit(135, 20, 9)}) {
        const Camera cam = camera(eye);
        StageTimes t;
        ObjectReport rep;
        render_object_frame(drawn, renderer, cam, RenderMethod::two_pass, o, d, t, &rep);
        ASSERT_FALSE(rep.faces.empty());
        for (const ObjectFaceReport& fr : rep.faces) {
            ReliefQuad& q = *alone[size_t(fr.face)];
            EXPECT_EQ(fr.level, q.choose_level(cam, d.level_error_px)) << "face " << kFaceKeys[size_t(fr.face)];
            bounded += fr.level < auto_level(cam, q.relief());
        }
        DrawOptions fixed = d;
        fixed.level = 1;
        render_object_frame(drawn, renderer, cam, RenderMethod::two_pass, o, fixed, t, &rep);
        for (const ObjectFaceReport& fr : rep.faces) EXPECT_EQ(fr.level, 1);
    }
    EXPECT_GT(bounded, 0);  // these views include faces the parallax bound holds finer than the density rule would
}

}  // namespace
}  // namespace rtm
