// Overlay geometry: projection to pixels agrees with the camera's rays; inset positions of the texture's corners.
#include <gtest/gtest.h>

#include "viewer/frame_stats.h"
#include "viewer/overlays.h"

namespace rtm::viewer {
namespace {

TEST(Overlays, ProjectInvertsCameraRay) {
    Camera cam;
    cam.eye = {0.3, 0.5, 4};
    cam.look_at = {0.1, 0, 0};
    cam.width = 200;
    cam.height = 100;
    cam.fit_clip_planes({0, 0, 0}, 1.0);
    for (double px : {0.0, 57.0, 199.0})
        for (double py : {0.0, 33.0, 99.0}) {
            glm::dvec3 o, d;
            cam.ray(px, py, o, d);
            glm::dvec2 p;
            ASSERT_TRUE(project(cam, o + 3.0 * d, p));
            // Double precision through the projection matrix: far below a pixel.
            EXPECT_NEAR(p.x, px + 0.5, 1e-9);
            EXPECT_NEAR(p.y, py + 0.5, 1e-9);
        }
    glm::dvec2 p;
    EXPECT_FALSE(project(cam, cam.eye + (cam.eye - cam.look_at), p));  // behind the eye
}

TEST(Overlays, InsetPositionMapsTheTextureWithItsMargins) {
    DrawnQuad q;
    q.width = 100;
    q.height = 50;
    q.margins = {10, 30, 5, 15};  // left, right, bottom, top: texture 140 x 70
    const glm::dvec2 size(140, 70);
    EXPECT_EQ(inset_position(q, {-10, 65}, size), glm::dvec2(0, 0));     // top-left of the texture
    EXPECT_EQ(inset_position(q, {130, -5}, size), glm::dvec2(140, 70));  // bottom-right
    EXPECT_EQ(inset_position(q, {0, 50}, size), glm::dvec2(10, 15));     // the quad's top-left corner
}

TEST(FrameStats, OtherIsTheRestAndFpsCountsTheLastSecond) {
    FrameStats st(3);
    for (int i = 0; i < 5; ++i) {
        FrameSample s;
        s.frame_ms = 10;
        s.stages.prewarp_ms = 2;
        s.stages.upload_ms = 1;
        s.stages.texture_map_ms = 3;
        s.texels_warped = 100;
        st.add(s, 0.1 * i);
    }
    EXPECT_EQ(st.samples().size(), 3u);
    EXPECT_NEAR(st.fps(), 10.0, 1e-9);
    const FrameSample m = st.mean();
    EXPECT_DOUBLE_EQ(m.other_ms(), 4.0);
    EXPECT_EQ(m.texels_warped, 100);
    EXPECT_EQ(st.series(4), (std::vector<float>{4.f, 4.f, 4.f}));
}

}  // namespace
}  // namespace rtm::viewer
