// The decisions of a frame without OpenGL (objects/frame_plan.h): every skip's rule, the level choice, the reuse
// tolerance and the partial-upload decisions. ReliefQuad::draw carries these plans out (skips_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>

#include "objects/frame_plan.h"
#include "objects/bounds.h"
#include "objects/level_choice.h"
#include "procedural/procedural_media.h"
#include "texmap/camera_rig.h"
#include "warp/pyramid.h"

namespace rtm {
namespace {

bool has(const FramePlan& p, const char* skip) {
    return std::find(p.skips.begin(), p.skips.end(), std::string(skip)) != p.skips.end();
}

struct Relief {
    ReliefTexture t = to_relief(make_bumps(32));
    std::vector<ReliefTexture> pyramid;
    Relief() {
        for (int i = 1; i < pyramid_levels(t.width, t.height); ++i)
            pyramid.push_back(downsample(pyramid.empty() ? t : pyramid.back(), t));
    }
    LevelSource levels() const {
        return [this](int i) -> const ReliefTexture& { return i == 0 ? t : pyramid.at(size_t(i) - 1); };
    }
    Camera orbit(double az, double el, double dist) const {
        const Bounds b = relief_bounds(t);
        return orbit_camera(b.centre(), b.radius(), {az, el, dist}, 128, 128);
    }
    FramePlan plan(const Camera& cam, const DrawOptions& d = {}, RenderMethod m = RenderMethod::two_pass,
                   const LastPrewarp& last = {}, const PrewarpOptions& o = {}) const {
        return plan_frame(cam, m, o, d, t, levels(), last);
    }
};

DrawOptions no_skips() {
    DrawOptions d;
    d.skips = false;
    return d;
}

TEST(FramePlan, PyramidLevelsCountDownTo1x1) {
    EXPECT_EQ(pyramid_levels(1, 1), 1);
    EXPECT_EQ(pyramid_levels(2, 1), 2);
    EXPECT_EQ(pyramid_levels(3, 3), 3);  // 3 -> 2 -> 1
    EXPECT_EQ(pyramid_levels(256, 256), 9);
    EXPECT_EQ(pyramid_levels(256, 4), 9);
}

TEST(FramePlan, AFrontViewPrewarpsLevelZero) {
    const Relief r;
    const FramePlan p = r.plan(r.orbit(20, 10, 2.5));
    EXPECT_EQ(p.action, FrameAction::prewarp) << p.to_string();
    EXPECT_TRUE(p.skips.empty()) << p.to_string();
    EXPECT_TRUE(p.draw);
    EXPECT_EQ(p.level, 0);
    EXPECT_EQ(p.prewarp.method, Reconstruction::two_pass);
    EXPECT_TRUE(p.prewarp.copy_still_runs);
    EXPECT_EQ(p.setup, (PrewarpSetup{0, RenderMethod::two_pass, false, false, false, Filter::point}));
    EXPECT_EQ(p.to_string(), "FramePlan{prewarp level=0 skips=[] setup=two-pass}");
    const FramePlan q = r.plan(r.orbit(20, 10, 2.5), {}, RenderMethod::pipelined);
    EXPECT_EQ(q.prewarp.method, Reconstruction::pipelined);
    EXPECT_EQ(q.setup.method, RenderMethod::pipelined);
}

TEST(FramePlan, OnlyTextureMethodsArePlanned) {
    const Relief r;
    EXPECT_THROW(r.plan(r.orbit(20, 10, 2.5), {}, RenderMethod::micromesh), std::invalid_argument);
    EXPECT_THROW(r.plan(r.orbit(20, 10, 2.5), {}, RenderMethod::raycast), std::invalid_argument);
}

TEST(FramePlan, OutsideFrustum) {
    const Relief r;
    Camera away = r.orbit(0, 10, 2.5);
    away.look_at = away.eye + (away.eye - away.look_at);  // looking away from the relief
    const FramePlan p = r.plan(away);
    EXPECT_EQ(p.action, FrameAction::nothing);
    EXPECT_EQ(p.skips, std::vector<std::string>{kSkipOutsideFrustum});
    // Skips off: the work is done (it is in front of the quad, so it is drawn, off screen).
    const FramePlan q = r.plan(away, no_skips());
    EXPECT_EQ(q.action, FrameAction::prewarp);
    EXPECT_TRUE(q.skips.empty());
    EXPECT_TRUE(q.draw);
}

TEST(FramePlan, BackFacing) {
    const Relief r;
    const FramePlan p = r.plan(r.orbit(180, 10, 2.5));
    EXPECT_EQ(p.action, FrameAction::nothing);
    EXPECT_EQ(p.skips, std::vector<std::string>{kSkipBackFacing});
    // Skips off: pre-warped to be measured, not drawn; copies of still runs off (every texel warped).
    const FramePlan q = r.plan(r.orbit(180, 10, 2.5), no_skips());
    EXPECT_EQ(q.action, FrameAction::prewarp);
    EXPECT_FALSE(q.draw);
    EXPECT_FALSE(q.prewarp.copy_still_runs);
    EXPECT_NE(q.to_string().find("not-drawn"), std::string::npos) << q.to_string();
}

TEST(FramePlan, InsideTheSlabDrawsTheMicromeshForWarpingMethodsOnly) {
    const Relief r;
    ASSERT_GT(r.t.quant.max, 0.0);
    Camera cam = r.orbit(20, 10, 2.5);
    const ReliefGeometry& g = r.t.geometry;
    // Above the quad's plane at half the largest displacement: some texels are above the eye's plane.
    cam.eye = g.origin + g.a * (0.5 * r.t.width) + g.b * (0.5 * r.t.height) + g.f() * (0.5 * r.t.quant.max);
    cam.look_at = cam.eye + g.a - g.f() * 0.1;
    cam.fit_clip_planes(relief_bounds(r.t).centre(), relief_bounds(r.t).radius());
    ASSERT_TRUE(eye_inside_slab(r.t, cam.eye));
    const FramePlan p = r.plan(cam);
    EXPECT_EQ(p.action, FrameAction::micromesh);
    EXPECT_EQ(p.skips, std::vector<std::string>{kSkipInsideSlab});
    EXPECT_EQ(r.plan(cam, {}, RenderMethod::flat).action, FrameAction::flat);
    EXPECT_FALSE(has(r.plan(cam, no_skips()), kSkipInsideSlab));
}

TEST(FramePlan, LevelIsClampedOrChosenForTheDensity) {
    const Relief r;
    const int top = pyramid_levels(r.t.width, r.t.height) - 1;
    DrawOptions d;
    d.level = 99;
    EXPECT_EQ(r.plan(r.orbit(20, 10, 2.5), d).level, top);
    d.level = 2;
    const FramePlan two = r.plan(r.orbit(20, 10, 2.5), d);
    EXPECT_EQ(two.level, 2);
    EXPECT_EQ(two.setup.level, 2);
    // The level's coefficients, not level 0's.
    EXPECT_EQ(two.k.k3, compute_coefficients(r.pyramid[1].geometry, r.orbit(20, 10, 2.5).eye).k3);
    d.level = -1;
    for (double dist : {1.2, 2.5, 10.0, 40.0}) {
        const Camera cam = r.orbit(20, 10, dist);
        EXPECT_EQ(r.plan(cam, d).level, choose_level(cam, r.t, level_displacement_spreads(r.t), d.level_error_px))
            << dist;
    }
    // 32x32 texels on a 128x128 image: level 0 close up, coarser levels further away.
    EXPECT_EQ(auto_level(r.orbit(20, 10, 1.2), r.t), 0);
    EXPECT_GT(auto_level(r.orbit(20, 10, 40), r.t), 0);
}

TEST(FramePlan, SubpixelParallaxDrawsFlat) {
    const Relief r;
    const Camera far = r.orbit(30, 20, 500);
    const FramePlan p = r.plan(far);
    EXPECT_EQ(p.action, FrameAction::flat);
    EXPECT_EQ(p.skips, std::vector<std::string>{kSkipSubpixelParallax});
    // The rule: the largest parallax in texels times the pixels per texel against the threshold.
    DrawOptions d;
    d.subpixel_parallax = 0.0;
    EXPECT_EQ(r.plan(far, d).action, FrameAction::prewarp);
    EXPECT_EQ(r.plan(far, no_skips()).action, FrameAction::prewarp);
    EXPECT_EQ(r.plan(r.orbit(30, 20, 2)).action, FrameAction::prewarp);
    // Method flat: a plain texture without the skip.
    const FramePlan f = r.plan(far, {}, RenderMethod::flat);
    EXPECT_EQ(f.action, FrameAction::flat);
    EXPECT_TRUE(f.skips.empty());
}

TEST(FramePlan, ReuseWithinTheToleranceOfTheSameSetup) {
    const Relief r;
    Camera cam = r.orbit(30, 20, 2.0);
    const FramePlan first = r.plan(cam);
    ASSERT_EQ(first.action, FrameAction::prewarp);
    const LastPrewarp last{true, first.setup, first.k, {}};
    const FramePlan same = r.plan(cam, {}, RenderMethod::two_pass, last);
    EXPECT_EQ(same.action, FrameAction::reuse);
    EXPECT_EQ(same.skips, std::vector<std::string>{kSkipReuse});
    // Not without a last pre-warp, with skips off, or with another setup.
    EXPECT_EQ(r.plan(cam, {}, RenderMethod::two_pass, {false, first.setup, first.k, {}}).action, FrameAction::prewarp);
    EXPECT_EQ(r.plan(cam, no_skips(), RenderMethod::two_pass, last).action, FrameAction::prewarp);
    EXPECT_EQ(r.plan(cam, {}, RenderMethod::pipelined, last).action, FrameAction::prewarp);
    PrewarpOptions exact;
    exact.exact = true;
    EXPECT_EQ(r.plan(cam, {}, RenderMethod::two_pass, last, exact).action, FrameAction::prewarp);
    PrewarpOptions walls;
    walls.keep_outliers = true;
    EXPECT_EQ(r.plan(cam, {}, RenderMethod::two_pass, last, walls).action, FrameAction::prewarp);
    DrawOptions depth;
    depth.depth_correction = true;
    EXPECT_EQ(r.plan(cam, depth, RenderMethod::two_pass, last).action, FrameAction::prewarp);
    DrawOptions lvl;
    lvl.level = 1;
    EXPECT_EQ(r.plan(cam, lvl, RenderMethod::two_pass, last).action, FrameAction::prewarp);
    // The tolerance: a move whose largest texel motion m is reused when m < tolerance, not when m >= tolerance.
    cam.eye += glm::dvec3(0.01, 0.005, 0);
    const double m = max_texel_motion(r.t, first.k, compute_coefficients(r.t.geometry, cam.eye));
    ASSERT_GT(m, 0.0);
    DrawOptions d;
    d.reuse_tolerance = m * 1.001;
    EXPECT_EQ(r.plan(cam, d, RenderMethod::two_pass, last).action, FrameAction::reuse);
    d.reuse_tolerance = m;
    EXPECT_EQ(r.plan(cam, d, RenderMethod::two_pass, last).action, FrameAction::prewarp);
}

UploadedTexture prewarp_texture(long long version, PixelRect moving) {
    UploadedTexture u;
    u.content = {TextureContent::Source::prewarp, 0};
    u.version = version;
    u.width = 100;
    u.height = 80;
    u.setup = {0, RenderMethod::two_pass, false, true, false, Filter::point};
    u.extent = {1, 2, 3, 4};
    u.moving = moving;
    return u;
}

TEST(FramePlan, UploadEverythingTheFirstTimeAndWithSkipsOff) {
    const UploadedTexture now = prewarp_texture(1, {10, 10, 5, 5});
    const UploadPlan first = plan_upload(now, {}, true);
    EXPECT_FALSE(first.partial);
    EXPECT_EQ(first.rect.area(), 100 * 80);
    EXPECT_EQ(first.next.content, now.content);
    EXPECT_EQ(first.next.version, 1);
    const UploadPlan off = plan_upload(prewarp_texture(2, {10, 10, 5, 5}), now, false);
    EXPECT_FALSE(off.partial);
    EXPECT_EQ(off.rect.area(), 100 * 80);
    EXPECT_EQ(off.next.content.source, TextureContent::Source::none);  // nothing remembered
}

TEST(FramePlan, UploadNothingForTheSameImage) {
    const UploadedTexture now = prewarp_texture(3, {10, 10, 5, 5});
    const UploadPlan again = plan_upload(now, now, true);  // a reused pre-warp
    EXPECT_TRUE(again.partial);
    EXPECT_TRUE(again.rect.empty());
    UploadedTexture flat;
    flat.content = {TextureContent::Source::flat, 2};
    flat.width = 8;
    flat.height = 8;
    EXPECT_TRUE(plan_upload(flat, flat, true).rect.empty());
    UploadedTexture other = flat;
    other.content.level = 1;
    EXPECT_EQ(plan_upload(other, flat, true).rect.area(), 64);  // another level's colours
}

TEST(FramePlan, UploadTheUnionOfTheMovingFootprints) {
    const UploadedTexture last = prewarp_texture(3, {10, 10, 5, 5});
    const UploadedTexture now = prewarp_texture(4, {20, 12, 5, 5});
    const UploadPlan u = plan_upload(now, last, true);
    EXPECT_TRUE(u.partial);
    EXPECT_EQ(u.rect.x, 10);
    EXPECT_EQ(u.rect.row, 10);
    EXPECT_EQ(u.rect.w, 15);
    EXPECT_EQ(u.rect.h, 7);
    EXPECT_EQ(u.next.moving.x, 20);
    // Depth correction does not change the colours: still partial.
    UploadedTexture depth = now;
    depth.setup.displ = true;
    EXPECT_TRUE(plan_upload(depth, last, true).partial);
    // Other margins, size, setup or level: everything.
    UploadedTexture e = now;
    e.extent.left = 0;
    EXPECT_FALSE(plan_upload(e, last, true).partial);
    UploadedTexture s = now;
    s.width = 99;
    EXPECT_FALSE(plan_upload(s, last, true).partial);
    UploadedTexture m = now;
    m.setup.method = RenderMethod::pipelined;
    EXPECT_FALSE(plan_upload(m, last, true).partial);
    UploadedTexture x = now;
    x.setup.exact = true;
    EXPECT_FALSE(plan_upload(x, last, true).partial);
    UploadedTexture l = now;
    l.content.level = 1;
    l.setup.level = 1;
    EXPECT_FALSE(plan_upload(l, last, true).partial);
    // Footprints covering the image: the whole image, reported as a full upload.
    const UploadPlan full = plan_upload(prewarp_texture(5, {0, 0, 100, 80}), last, true);
    EXPECT_FALSE(full.partial);
    EXPECT_EQ(full.rect.area(), 100 * 80);
}

TEST(FramePlan, ZeroRunsFireOnlyWithStillTexels) {
    const Relief r;
    const FramePlan p = r.plan(r.orbit(20, 10, 2.5));
    PrewarpStats stats;
    stats.still_copied = 5;
    EXPECT_TRUE(zero_runs_fired(stats, 10));
    EXPECT_FALSE(zero_runs_fired(stats, 0));
    // The SIMD kernels copy still spans without counting them: every target but generic fires on still texels alone.
    stats.still_copied = 0;
    for (Isa isa : {Isa::avx512, Isa::avx3, Isa::avx2, Isa::sse4, Isa::neon, Isa::sve}) {
        stats.isa = isa;
        EXPECT_TRUE(zero_runs_fired(stats, 10)) << isa_name(isa);
        EXPECT_FALSE(zero_runs_fired(stats, 0)) << isa_name(isa);
    }
    stats.isa = Isa::generic;  // the reference kernels copied nothing
    EXPECT_FALSE(zero_runs_fired(stats, 10));
}

TEST(FramePlan, Names) {
    EXPECT_EQ(to_string(FrameAction::reuse), "reuse");
    EXPECT_EQ(to_string(TextureContent{TextureContent::Source::flat, 3}), "flat level 3");
    EXPECT_EQ(to_string(TextureContent{}), "none");
}

// The margins are cut to the largest texture (DrawOptions::max_texture_size) in proportion, each side never grows,
// and what is left of the budget is used exactly; within the budget nothing changes. Exact integer arithmetic.
TEST(FramePlan, MarginsAreCutToTheLargestTexture) {
    EXPECT_EQ(fit_texture_size({10, 30, 5, 5}, 100, 50, 120), (PrewarpExtent{5, 15, 5, 5}));
    EXPECT_EQ(fit_texture_size({10, 30, 5, 5}, 100, 50, 140), (PrewarpExtent{10, 30, 5, 5}));
    EXPECT_EQ(fit_texture_size({3, 4, 864, 0}, 16384, 1, 16384), (PrewarpExtent{0, 0, 864, 0}));  // a 16384x1 relief
    EXPECT_EQ(fit_texture_size({0, 0, 9000, 9000}, 64, 64, 16384), (PrewarpExtent{0, 0, 8160, 8160}));
    const unsigned seed = 20261207;
    std::printf("MarginsAreCutToTheLargestTexture: seed %u\n", seed);
    std::srand(seed);
    for (int i = 0; i < 10000; ++i) {
        const int w = 1 + std::rand() % 300, h = 1 + std::rand() % 300, max = 1 + std::rand() % 600;
        const PrewarpExtent e{std::rand() % 400, std::rand() % 400, std::rand() % 400, std::rand() % 400};
        const PrewarpExtent f = fit_texture_size(e, w, h, max);
        EXPECT_TRUE(f.left <= e.left && f.right <= e.right && f.bottom <= e.bottom && f.top <= e.top);
        EXPECT_TRUE(f.left >= 0 && f.right >= 0 && f.bottom >= 0 && f.top >= 0);
        for (const auto& [n, lo, hi, flo, fhi] : {std::array<int, 5>{w, e.left, e.right, f.left, f.right},
                                                  std::array<int, 5>{h, e.bottom, e.top, f.bottom, f.top}}) {
            const int budget = std::max(0, max - n);
            if (lo + hi <= budget)
                EXPECT_TRUE(flo == lo && fhi == hi);
            else
                EXPECT_EQ(flo + fhi, budget) << n << " " << lo << " " << hi << " " << max;
        }
    }
}

// The plan applies the cut to a relief seen at a grazing angle, with or without skips: the pre-warp it asks for fits.
TEST(FramePlan, GrazingMarginsFitTheLargestTexture) {
    const Relief r;
    PrewarpOptions o;
    o.keep_outliers = true;
    const Camera cam = r.orbit(80, 3, 2.2);
    const FramePlan free_plan = r.plan(cam, {}, RenderMethod::two_pass, {}, o);
    const PrewarpExtent all = prewarp_extent(r.t, free_plan.k, free_plan.prewarp);
    ASSERT_GT(all.left + all.right + all.bottom + all.top, 8) << "the view must ask for margins";
    for (bool skips : {true, false}) {
        DrawOptions d;
        d.skips = skips;
        d.max_texture_size = 36;  // 32 texels and 4 of margin along each axis
        const FramePlan p = r.plan(cam, d, RenderMethod::two_pass, {}, o);
        const PrewarpExtent e = prewarp_extent(r.t, p.k, p.prewarp);
        EXPECT_LE(r.t.width + e.left + e.right, 36) << skips;
        EXPECT_LE(r.t.height + e.bottom + e.top, 36) << skips;
    }
}

}  // namespace
}  // namespace rtm
