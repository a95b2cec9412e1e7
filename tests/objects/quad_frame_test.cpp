// A frame of many relief quads (objects/quad_frame.h): the pre-warp schedule; along the relief town's camera path,
// concurrent pre-warps and one finish per frame give bit-identical frames and the same decisions as serial
// pre-warps with a finish per quad; each quad's decisions with the level chosen per quad are those it makes alone;
// quads outside the frustum or facing away cost nothing; the pre-warp reuse fires along the path and the pictures
// stay within its tolerance.
#include "objects/quad_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/temp_dir.h"
#include "measure/image_diff.h"
#include "objects/scene.h"
#include "procedural/town.h"
#include "texmap/gl_context.h"

namespace rtm {
namespace {

using objects_testing::TempDir;

TEST(SchedulePrewarps, LargestFirstOverQuadsWhenThereAreAtLeastAsManyAsThreads) {
    const std::vector<long long> texels = {0, 64, 256, 0, 256, 16};
    const PrewarpSchedule s = schedule_prewarps(texels, 2, true);
    EXPECT_EQ(s.order, (std::vector<size_t>{2, 4, 1, 5}));  // equal sizes keep the quads' order
    EXPECT_TRUE(s.over_quads);
    EXPECT_EQ(s.threads, 2);
    EXPECT_FALSE(schedule_prewarps(texels, 2, false).over_quads);  // serial on request
    EXPECT_FALSE(schedule_prewarps(texels, 8, true).over_quads);   // fewer quads than threads: each warp in parallel
    EXPECT_TRUE(schedule_prewarps(texels, 4, true).over_quads);
    EXPECT_FALSE(schedule_prewarps({0, 5, 0}, 1, true).over_quads);  // one quad: nothing to run side by side
    EXPECT_TRUE(schedule_prewarps({0, 0}, 2, true).order.empty());
}

class TownFrameTest : public ::testing::Test {
public:
    static constexpr int kW = 160, kH = 120;
    static void SetUpTestSuite() {
        dir_ = new TempDir;
        TownOptions o;
        o.texels = 128;  // levels 0..7: the level per quad has something to choose
        o.path_frames = 24;
        path_ = new std::string(write_town(dir_->path().string(), o));
    }
    static void TearDownTestSuite() {
        delete dir_;
        delete path_;
    }
    static Camera camera(const Scene& scene, int k) {
        Camera size;
        size.width = kW;
        size.height = kH;
        return scene_path_camera(scene, k, size);
    }
    // The options rtm render --scene draws with: side polygons, depth correction, the level per quad.
    static PrewarpOptions prewarp_options(int threads) {
        PrewarpOptions o;
        o.keep_outliers = true;
        o.threads = threads;
        return o;
    }
    static DrawOptions draw_options(bool skips = true) {
        DrawOptions d;
        d.depth_correction = true;
        d.level = -1;
        d.skips = skips;
        return d;
    }
    static TempDir* dir_;
    static std::string* path_;
};
TempDir* TownFrameTest::dir_ = nullptr;
std::string* TownFrameTest::path_ = nullptr;

std::string decisions(const SceneFrameReport& r) {
    std::string s = std::to_string(r.drawn) + " " + std::to_string(r.prewarped) + " " + std::to_string(r.texels_warped);
    for (size_t q = 0; q < r.quad_skips.size(); ++q) {
        s += " |" + std::to_string(r.quad_levels[q]);
        for (const std::string& k : r.quad_skips[q]) s += " " + k;
    }
    return s;
}

TEST_F(TownFrameTest, ConcurrentPrewarpsGiveBitIdenticalFramesToSerialOnes) {
    auto ctx = GlContext::create_offscreen(kW, kH);
    Renderer renderer;
    Scene concurrent = Scene::load(*path_), serial = Scene::load(*path_);
    const QuadFrameOptions serial_options{.concurrent = false, .finish_each = true};  // the old frame loop
    int frames_over_quads = 0;
    for (int k = 0; k < concurrent.manifest().path_frames; ++k) {
        const Camera cam = camera(concurrent, k);
        SceneFrameReport rc, rs;
        // Two threads: on this machine's 2 cores, and elsewhere, the concurrent schedule really runs over quads.
        concurrent.draw(renderer, cam, RenderMethod::two_pass, prewarp_options(2), draw_options(), rc);
        const ImageRGBA8 a = renderer.read_pixels(kW, kH);
        serial.draw(renderer, cam, RenderMethod::two_pass, prewarp_options(2), draw_options(), rs, serial_options);
        const ImageRGBA8 b = renderer.read_pixels(kW, kH);
        ASSERT_EQ(decisions(rc), decisions(rs)) << "frame " << k;
        ASSERT_TRUE(a.pixels == b.pixels) << "frame " << k;
        frames_over_quads += rc.prewarped >= 2;
    }
    EXPECT_GT(frames_over_quads, 0);  // the concurrent schedule was exercised
}

TEST_F(TownFrameTest, EachQuadDecidesAsItWouldAloneWithTheLevelPerQuad) {
    auto ctx = GlContext::create_offscreen(kW, kH);
    Renderer renderer;
    Scene scene = Scene::load(*path_);
    std::vector<ReliefQuad> alone;
    for (ReliefQuad& q : scene.quads()) alone.emplace_back(q.relief());
    int coarser = 0;
    for (int k = 0; k < scene.manifest().path_frames; ++k) {
        const Camera cam = camera(scene, k);
        SceneFrameReport rep;
        scene.draw(renderer, cam, RenderMethod::two_pass, prewarp_options(0), draw_options(), rep);
        int hidden = 0;
        for (size_t q = 0; q < alone.size(); ++q) {
            renderer.begin_frame(cam);
            StageTimes st;
            DrawReport dr;
            alone[q].draw(renderer, cam, RenderMethod::two_pass, prewarp_options(0), st, draw_options(), &dr);
            ASSERT_EQ(dr.skips, rep.quad_skips[q]) << "frame " << k << " quad " << q;
            ASSERT_EQ(dr.level, rep.quad_levels[q]) << "frame " << k << " quad " << q;
            coarser += dr.level > 0;
            for (const std::string& s : dr.skips) hidden += s == kSkipBackFacing || s == kSkipOutsideFrustum;
        }
        // Every quad is either hidden (one of the two skips) or drawn.
        EXPECT_EQ(rep.drawn + hidden, rep.quads) << "frame " << k;
    }
    EXPECT_GT(coarser, 0);  // far houses use coarser levels
}

TEST_F(TownFrameTest, QuadsOutsideTheFrustumOrFacingAwayCostNothing) {
    auto ctx = GlContext::create_offscreen(kW, kH);
    Renderer renderer;
    Scene scene = Scene::load(*path_);
    int hidden = 0;
    for (int k = 0; k < scene.manifest().path_frames; ++k) {
        SceneFrameReport rep;
        scene.draw(renderer, camera(scene, k), RenderMethod::two_pass, prewarp_options(0), draw_options(), rep);
        for (size_t q = 0; q < rep.quad_skips.size(); ++q) {
            const std::vector<std::string>& s = rep.quad_skips[q];
            if (s.empty() || (s[0] != kSkipBackFacing && s[0] != kSkipOutsideFrustum)) continue;
            ++hidden;
            // No stage ran for it: its times are not measured at all, so exactly zero.
            EXPECT_EQ(s.size(), 1u) << "frame " << k << " quad " << q;
            EXPECT_EQ(rep.quad_times[q].prewarp_ms, 0.0);
            EXPECT_EQ(rep.quad_times[q].upload_ms, 0.0);
            EXPECT_EQ(rep.quad_times[q].texture_map_ms, 0.0);
        }
    }
    EXPECT_GT(hidden, scene.manifest().path_frames * int(scene.quads().size()) / 3);
}

// The reuse along the path: with it against the same skips without it (reuse_tolerance 0: every drawn quad is
// pre-warped every frame), 40 frames at the spacing of the shipped town's 120-frame walk. A reused pre-warp is one
// for which no texel moved by more than 0.05 texels of its level since: each texture sample moves by less than
// that, which changes a colour by a twentieth of the step between neighbouring texels and flips coverage only
// where a bilinear alpha sits within that of one half (silhouettes).
TEST_F(TownFrameTest, ReuseFiresAlongThePathAndPicturesStayWithinItsTolerance) {
    auto ctx = GlContext::create_offscreen(kW, kH);
    Renderer renderer;
    Scene with = Scene::load(*path_), without = Scene::load(*path_);
    const SceneManifest& m = with.manifest();
    const Bounds bounds = with.bounds();
    DrawOptions no_reuse = draw_options();
    no_reuse.reuse_tolerance = 0.0;
    int reused = 0;
    for (int k = 0; k < 40; ++k) {
        Camera cam;
        cam.width = kW;
        cam.height = kH;
        cam = key_camera(camera_path_frame(m.path_keys, k, 120), cam);
        cam.fit_clip_planes(bounds.centre(), bounds.radius());
        SceneFrameReport rw, rn;
        with.draw(renderer, cam, RenderMethod::two_pass, prewarp_options(0), draw_options(), rw);
        const ImageRGBA8 a = renderer.read_pixels(kW, kH);
        without.draw(renderer, cam, RenderMethod::two_pass, prewarp_options(0), no_reuse, rn);
        const ImageRGBA8 b = renderer.read_pixels(kW, kH);
        const int n = rw.skips.count(kSkipReuse) ? rw.skips.at(kSkipReuse) : 0;
        EXPECT_EQ(rn.skips.count(kSkipReuse), 0u);
        reused += n;
        int off = 0, worst = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            const Rgba8 p = a.pixels[i], q = b.pixels[i];
            const int d = std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
            off += d > 8;
            worst = std::max(worst, d);
        }
        const DiffResult diff = diff_images(b, a);
        std::printf("frame %d: %d quads reused, %d pixels off by > 8 (worst %d), iou %.4f, psnr %.2f\n", k, n, off,
                    worst, diff.iou, diff.psnr);
        if (n == 0) {  // nothing reused: the same frame
            EXPECT_TRUE(a.pixels == b.pixels) << "frame " << k;
            continue;
        }
        EXPECT_LE(off, kW * kH / 1000) << "frame " << k;
        EXPECT_GE(diff.iou, 0.999) << "frame " << k;
    }
    EXPECT_GT(reused, 0);
}

}  // namespace
}  // namespace rtm
