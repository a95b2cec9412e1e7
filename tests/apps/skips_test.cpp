// The skips of ReliefQuad::draw (issue "relief texture pyramids, and skipping what a scene does not need"):
// each fires when its condition holds, not otherwise, and what it draws stays close to the full work.
#include <gtest/gtest.h>

#include <algorithm>

#include "objects/compare.h"
#include "objects/image_diff.h"
#include "objects/procedural_media.h"
#include "objects/relief_manifest.h"
#include "objects/render_relief.h"
#include "objects/view_analysis.h"
#include "texmap/gl_context.h"

namespace rtm {
namespace {

bool fired(const DrawReport& r, const char* name) {
    return std::find(r.skips.begin(), r.skips.end(), std::string(name)) != r.skips.end();
}

struct Frame {
    std::unique_ptr<GlContext> ctx = GlContext::create_offscreen(128, 128);
    Renderer r;
    ImageRGBA8 draw(ReliefQuad& q, const Camera& cam, DrawReport& rep, bool skips = true, int level = 0) {
        RenderSettings s;
        s.method = RenderMethod::two_pass;
        s.prewarp.keep_outliers = true;
        s.draw.skips = skips;
        s.draw.level = level;
        StageTimes t;
        return render_relief_frame(q, &r, cam, s, t, &rep);
    }
};

Camera orbit(const ReliefQuad& q, double az, double el, double dist) {
    return compare_camera(q, {"v", az, el, dist}, 128, 128);
}

TEST(Skips, BackFacingAndOutsideFrustum) {
    Frame f;
    ReliefQuad q(to_relief(make_bumps(32)));
    DrawReport rep;
    f.draw(q, orbit(q, 180, 10, 2.5), rep);  // behind the relief
    EXPECT_TRUE(fired(rep, kSkipBackFacing));
    Camera away = orbit(q, 0, 10, 2.5);
    away.look_at = away.eye + (away.eye - away.look_at);  // looking away from the relief
    const ImageRGBA8 img = f.draw(q, away, rep);
    EXPECT_TRUE(fired(rep, kSkipOutsideFrustum));
    for (const Rgba8& p : img.pixels) ASSERT_FALSE(covered(p));
    f.draw(q, orbit(q, 20, 10, 2.5), rep);
    EXPECT_FALSE(fired(rep, kSkipBackFacing));
    EXPECT_FALSE(fired(rep, kSkipOutsideFrustum));
}

TEST(Skips, SubpixelParallaxDrawsAPlainTexture) {
    Frame f;
    ReliefQuad q(to_relief(make_bumps(32)));
    DrawReport rep;
    // 500 radii away the whole relief covers a few pixels: its parallax is far below a quarter pixel.
    const Camera far = orbit(q, 30, 20, 500);
    const ImageRGBA8 skipped = f.draw(q, far, rep);
    EXPECT_TRUE(fired(rep, kSkipSubpixelParallax));
    const ImageRGBA8 full = f.draw(q, far, rep, false);
    const DiffResult d = diff_images(full, skipped);
    // Sub-quarter-pixel parallax: the silhouettes agree up to a pixel of a tiny footprint.
    EXPECT_GT(d.iou, 0.6) << d.to_string();
    f.draw(q, orbit(q, 30, 20, 2), rep);
    EXPECT_FALSE(fired(rep, kSkipSubpixelParallax));
}

TEST(Skips, ReuseWhenTheEyeBarelyMovesAndPartialUpload) {
    Frame f;
    ReliefQuad q(to_relief(make_bumps(64)));
    DrawReport rep;
    Camera cam = orbit(q, 30, 20, 2.0);
    const ImageRGBA8 a = f.draw(q, cam, rep);
    EXPECT_FALSE(fired(rep, kSkipReuse));
    const ImageRGBA8 b = f.draw(q, cam, rep);  // same eye
    EXPECT_TRUE(fired(rep, kSkipReuse));
    EXPECT_TRUE(fired(rep, kSkipPartialUpload));
    EXPECT_EQ(rep.uploaded_texels, 0);
    EXPECT_EQ(a, b);
    cam.eye += glm::dvec3(1e-7, 0, 0);  // far below the 0.05-texel tolerance
    f.draw(q, cam, rep);
    EXPECT_TRUE(fired(rep, kSkipReuse));
    cam.eye += glm::dvec3(0.2, 0.05, 0);  // a real move: pre-warped again
    const ImageRGBA8 c = f.draw(q, cam, rep);
    EXPECT_FALSE(fired(rep, kSkipReuse));
    // The partial upload leaves the texture equal to a full upload.
    const ImageRGBA8 full = f.draw(q, cam, rep, false);
    EXPECT_EQ(c, full);
}

TEST(Skips, InsideTheSlabFallsBackToMicroPolygons) {
    Frame f;
    ReliefQuad q(load_relief(std::string(RTM_SOURCE_DIR) + "/media/facade.relief.json"));
    DrawReport rep;
    Camera cam = orbit(q, 0, 0, 2);
    cam.eye = q.relief().geometry.origin + q.relief().geometry.a * 128.0 + q.relief().geometry.b * 60.0 +
              q.relief().geometry.f() * 0.06;  // between the wall (0) and the top of the frames (0.12)
    cam.look_at = cam.eye + glm::dvec3(0, 0.3, -1);
    cam.fit_clip_planes(relief_bounds(q.relief()).centre(), relief_bounds(q.relief()).radius());
    ASSERT_TRUE(eye_inside_slab(q.relief(), cam.eye));
    const ImageRGBA8 img = f.draw(q, cam, rep);
    EXPECT_TRUE(fired(rep, kSkipInsideSlab));
    int n = 0;
    for (const Rgba8& p : img.pixels) n += covered(p);
    EXPECT_GT(n, 100);
}

TEST(Skips, AutoLevelMatchesTexelDensity) {
    Frame f;
    ReliefQuad q(to_relief(make_bumps(256)));
    DrawReport rep;
    // A 256^2 relief (65536 texels) in a 128^2 view with a 45-degree field of view, seen head-on; the bounding
    // radius is ~0.71, so D radii away the unit quad spans 128 / (2 * 0.71 * D * tan 22.5deg) pixels:
    //   D = 1.2: ~180 px wide, ~33000 px^2, 2 texels per pixel -> level 0;
    //   D = 2.5: ~87 px, ~7600 px^2, 8.6 texels per pixel -> level 1 (each level divides by 4);
    //   D = 20: ~11 px, ~118 px^2, 555 texels per pixel -> level 4.
    f.draw(q, orbit(q, 0, 0, 1.2), rep, true, -1);
    EXPECT_EQ(rep.level, 0);
    f.draw(q, orbit(q, 0, 0, 2.5), rep, true, -1);
    EXPECT_EQ(rep.level, 1);
    f.draw(q, orbit(q, 0, 0, 20), rep, true, -1);
    EXPECT_EQ(rep.level, 4);
    f.draw(q, orbit(q, 0, 0, 1.2), rep, true, 3);
    EXPECT_EQ(rep.level, 3);
}

TEST(ViewAnalysis, ParallaxAndMotion) {
    const ReliefTexture t = to_relief(make_bumps(32));
    const glm::dvec3 c = relief_bounds(t).centre();
    const PrewarpCoefficients k0 = compute_coefficients(t.geometry, c + glm::dvec3(0.1, 0.2, 2.0));
    EXPECT_EQ(max_texel_motion(t, k0, k0), 0.0);
    const PrewarpCoefficients k1 = compute_coefficients(t.geometry, c + glm::dvec3(0.1, 0.2, 2000.0));
    EXPECT_LT(max_parallax_texels(t, k1), max_parallax_texels(t, k0) / 100);
    // Brute force over every texel agrees with the corner bound.
    double worst = 0;
    for (int r = 0; r < t.height; ++r)
        for (int x = 0; x < t.width; ++x) {
            double u, v;
            ASSERT_TRUE(k0.warp(x + 0.5, (t.height - 1 - r) + 0.5, t.displ(x, r), u, v));
            worst = std::max(worst, std::hypot(u - (x + 0.5), v - (t.height - 1 - r + 0.5)));
        }
    EXPECT_LE(worst, max_parallax_texels(t, k0) + 1e-9);
}

}  // namespace
}  // namespace rtm
