// Six-face objects in a scene (objects/scene.h, objects/scene_items.h): the faces' reuse skip in the scene's frame
// loop, with the relief quads' tolerance and semantics (DrawOptions::reuse_tolerance: no point of the box behind a
// face moved by that many texels since its pre-warp, and the same adjacent faces), counted in the frame's report
// (object_faces_prewarped, object_face_skips; rtm render --scene --json); the pictures of a walk with the reuse
// against the same walk without it within the relief quads' stated tolerance (tests/objects/quad_frame_test.cpp);
// and each face's level at `auto` as the object alone chooses it in its own frame.
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "measure/image_diff.h"
#include "objects/scene.h"
#include "texmap/gl_context.h"

namespace rtm {
namespace {

constexpr int kW = 160, kH = 120;

// The shipped sphere (64 texels a face) placed by a similarity, on a grey ground polygon.
SceneTransform placement() {
    SceneTransform t;
    t.translate = {2.0, 0.5, -1.0};
    t.rotate = {{0, 1, 0, 30}};
    t.scale = 0.5;
    return t;
}

Scene sphere_scene() {
    SceneManifest m;
    m.path = "test.scene.json";
    m.name = "test";
    SceneItem o;
    o.kind = SceneItem::Kind::object;
    o.file_path = std::string(RTM_SOURCE_DIR) + "/media/sphere.object.json";
    o.transform = placement();
    m.items.push_back(o);
    SceneItem g;
    g.kind = SceneItem::Kind::polygon;
    g.vertices = {{-1, 0, 2}, {5, 0, 2}, {5, 0, -4}, {-1, 0, -4}};
    m.items.push_back(g);
    return Scene(std::move(m));
}

Camera camera(const Scene& s, const glm::dvec3& eye) {
    Camera cam;
    cam.width = kW;
    cam.height = kH;
    cam.eye = eye;
    cam.look_at = {2.0, 0.5, -1.0};
    const Bounds b = s.bounds();
    cam.fit_clip_planes(b.centre(), b.radius());
    return cam;
}

DrawOptions options() {
    DrawOptions d;
    d.depth_correction = true;
    d.level = -1;  // as rtm render --scene draws
    return d;
}

int count(const std::map<std::string, int>& m, const char* k) { return m.count(k) ? m.at(k) : 0; }

struct Gl {
    std::unique_ptr<GlContext> ctx = GlContext::create_offscreen(kW, kH);
    Renderer renderer;
};

TEST(SceneObject, TheSameEyeReusesEveryFaceAndDrawsTheSamePicture) {
    Gl gl;
    Scene scene = sphere_scene();
    const Camera cam = camera(scene, {3.2, 1.4, 1.5});
    SceneFrameReport first, again;
    scene.draw(gl.renderer, cam, RenderMethod::two_pass, PrewarpOptions{}, options(), first);
    const ImageRGBA8 a = gl.renderer.read_pixels(kW, kH);
    scene.draw(gl.renderer, cam, RenderMethod::two_pass, PrewarpOptions{}, options(), again);
    const ImageRGBA8 b = gl.renderer.read_pixels(kW, kH);
    ASSERT_GE(first.object_faces_drawn, 2);
    EXPECT_EQ(first.object_faces_prewarped, first.object_faces_drawn);
    EXPECT_EQ(count(first.object_face_skips, kSkipReuse), 0);
    EXPECT_GT(first.object_texels_warped, 0);
    EXPECT_EQ(count(first.object_face_skips, kSkipBackFacing), 6 - first.object_faces_drawn);
    EXPECT_EQ(again.object_faces_drawn, first.object_faces_drawn);
    EXPECT_EQ(again.object_faces_prewarped, 0);
    EXPECT_EQ(again.object_texels_warped, 0);
    EXPECT_EQ(count(again.object_face_skips, kSkipReuse), again.object_faces_drawn);
    EXPECT_EQ(count(again.object_face_skips, kSkipPartialUpload), again.object_faces_drawn);  // nothing uploaded
    EXPECT_TRUE(a.pixels == b.pixels);
}

// The reuse fires for a move below the tolerance and not for a larger one, however the faces' decisions come out
// alone: a face of the placed object decides as the object itself decides from the camera moved into its frame.
TEST(SceneObject, ReuseFiresOnlyWhileTheEyeBarelyMoves) {
    Gl gl;
    Scene scene = sphere_scene();
    const glm::dvec3 eye{3.2, 1.4, 1.5};
    SceneFrameReport r0, tiny, large;
    scene.draw(gl.renderer, camera(scene, eye), RenderMethod::two_pass, PrewarpOptions{}, options(), r0);
    scene.draw(gl.renderer, camera(scene, eye + glm::dvec3(1e-5, 0, 0)), RenderMethod::two_pass, PrewarpOptions{},
               options(), tiny);
    EXPECT_EQ(count(tiny.object_face_skips, kSkipReuse), tiny.object_faces_drawn);
    EXPECT_EQ(tiny.object_faces_prewarped, 0);
    scene.draw(gl.renderer, camera(scene, eye + glm::dvec3(0.2, 0, 0)), RenderMethod::two_pass, PrewarpOptions{},
               options(), large);
    EXPECT_EQ(count(large.object_face_skips, kSkipReuse), 0);
    EXPECT_EQ(large.object_faces_prewarped, large.object_faces_drawn);
    // Skips off: pre-warped every frame.
    DrawOptions off = options();
    off.skips = false;
    SceneFrameReport r_off;
    scene.draw(gl.renderer, camera(scene, eye + glm::dvec3(0.2, 0, 0)), RenderMethod::two_pass, PrewarpOptions{}, off,
               r_off);
    EXPECT_EQ(r_off.object_faces_prewarped, r_off.object_faces_drawn);
    EXPECT_EQ(count(r_off.object_face_skips, kSkipReuse), 0);
}

// A slow walk towards the object and around it (60 frames, steps from 1e-4 to 2e-2 units): with the reuse against
// the same walk with reuse_tolerance 0 (every face pre-warped every frame). A frame that reuses nothing is the same
// picture; one that reuses is within the relief quads' stated tolerance (at most 0.1% of the pixels more than 8
// levels off, coverage IoU >= 0.999). The reuse must fire on some frames and not on others.
TEST(SceneObject, AWalkReusesWithinTheReliefQuadsTolerance) {
    Gl gl;
    Scene with = sphere_scene(), without = sphere_scene();
    DrawOptions no_reuse = options();
    no_reuse.reuse_tolerance = 0.0;
    int reused = 0, warped_frames = 0;
    glm::dvec3 eye{3.6, 1.3, 1.8};
    for (int k = 0; k < 60; ++k) {
        const double step = k < 30 ? 1e-4 * (k % 10) : 2e-2;  // still, creeping, then walking
        eye += glm::dvec3(-step, 0.0, -0.5 * step);
        const Camera cam = camera(with, eye);
        SceneFrameReport rw, rn;
        with.draw(gl.renderer, cam, RenderMethod::two_pass, PrewarpOptions{}, options(), rw);
        const ImageRGBA8 a = gl.renderer.read_pixels(kW, kH);
        without.draw(gl.renderer, cam, RenderMethod::two_pass, PrewarpOptions{}, no_reuse, rn);
        const ImageRGBA8 b = gl.renderer.read_pixels(kW, kH);
        EXPECT_EQ(count(rn.object_face_skips, kSkipReuse), 0);
        const int n = count(rw.object_face_skips, kSkipReuse);
        EXPECT_EQ(n + rw.object_faces_prewarped, rw.object_faces_drawn) << "frame " << k;
        reused += n;
        warped_frames += n == 0;
        int off = 0, worst = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            const Rgba8 p = a.pixels[i], q = b.pixels[i];
            const int d = std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
            off += d > 8;
            worst = std::max(worst, d);
        }
        const DiffResult diff = diff_images(b, a);
        std::printf("frame %d: %d faces reused of %d, %d pixels off by > 8 (worst %d), iou %.4f\n", k, n,
                    rw.object_faces_drawn, off, worst, diff.iou);
        if (n == 0) {
            EXPECT_TRUE(a.pixels == b.pixels) << "frame " << k;
            continue;
        }
        EXPECT_LE(off, kW * kH / 1000) << "frame " << k;
        EXPECT_GE(diff.iou, 0.999) << "frame " << k;
    }
    EXPECT_GT(reused, 0);
    EXPECT_GT(warped_frames, 1);
}

// The level per face at `auto` in a scene: what the object decides in its own frame (object_frame_camera), the
// relief quad's rule on each face (tests/objects/object_face_level_test.cpp).
TEST(SceneObject, EachFaceTakesTheReliefQuadsLevelInTheObjectsFrame) {
    Gl gl;
    Scene scene = sphere_scene();
    ASSERT_EQ(scene.objects().size(), 1u);
    const glm::dmat4 m = placement().matrix();
    for (const glm::dvec3& eye : {glm::dvec3{3.2, 1.4, 1.5}, glm::dvec3{12, 3, 9}, glm::dvec3{2.1, 6, -0.8}}) {
        const Camera cam = camera(scene, eye);
        gl.renderer.begin_frame(cam);
        StageTimes t;
        ObjectReport rep;
        scene.objects()[0].draw(gl.renderer, cam, RenderMethod::two_pass, PrewarpOptions{}, options(), t, &rep);
        const Camera local = object_frame_camera(cam, m);
        ASSERT_FALSE(rep.faces.empty());
        for (const ObjectFaceReport& fr : rep.faces) {
            ReliefQuad alone(scene.objects()[0].object().face(fr.face).relief());
            EXPECT_EQ(fr.level, alone.choose_level(local, options().level_error_px)) << kFaceKeys[size_t(fr.face)];
        }
    }
}

}  // namespace
}  // namespace rtm
