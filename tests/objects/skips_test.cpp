// The skips of ReliefQuad::draw (issue "relief texture pyramids, and skipping what a scene does not need"):
// each fires when its condition holds, not otherwise, and what it draws stays close to the full work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <tuple>

#include "measure/compare.h"
#include "measure/image_diff.h"
#include "procedural/procedural_media.h"
#include "formats/relief_manifest.h"
#include "objects/render_relief.h"
#include "objects/view_analysis.h"
#include "texmap/gl_context.h"
#include "warp/simd/schedule.h"
#include "warp/test_util.h"

namespace rtm {
namespace {

bool fired(const DrawReport& r, const char* name) {
    return std::find(r.skips.begin(), r.skips.end(), std::string(name)) != r.skips.end();
}

struct Frame {
    std::unique_ptr<GlContext> ctx = GlContext::create_offscreen(128, 128);
    Renderer r;
    ImageRGBA8 draw(ReliefQuad& q, const Camera& cam, DrawReport& rep, bool skips = true, int level = 0,
                    bool sidewalls = true, RenderMethod method = RenderMethod::two_pass, bool fast = true,
                    bool cull = true) {
        RenderSettings s;
        s.draw.cull = cull;
        s.method = method;
        s.prewarp.keep_outliers = sidewalls;
        s.prewarp.isa = fast ? Isa::automatic : Isa::generic;
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
    // Every bump moves, so every pixel may change: the whole texture goes up (a partial upload would not pay).
    EXPECT_FALSE(fired(rep, kSkipPartialUpload));
    EXPECT_EQ(rep.uploaded_texels, (long long)q.prewarped().width * q.prewarped().height);
    const ImageRGBA8 full = f.draw(q, cam, rep, false);
    EXPECT_EQ(c, full);
}

// A flat wall (zero displacement) with one raised block: only the pixels the block's texels can reach change
// between views, and only those are uploaded; the picture is the one a full upload gives.
ReliefTexture block_wall(int n, int x0, int x1) {
    return test::make_test_relief(n, n, 0.0, 0.1,
                                  [&](int x, int r) { return x >= x0 && x < x1 && r >= x0 && r < x1 ? 0.1 : 0.0; });
}

TEST(Skips, PartialUploadOfWhatMovingTexelsReach) {
    Frame f;
    ReliefTexture t = block_wall(128, 20, 36);
    t.geometry.a = {1.0 / 128, 0, 0};
    t.geometry.b = {0, 1.0 / 128, 0};
    ReliefQuad q(std::move(t));
    const long long all = 128 * 128;
    for (RenderMethod m : {RenderMethod::two_pass, RenderMethod::pipelined}) {
        SCOPED_TRACE(to_string(m));
        DrawReport rep;
        f.draw(q, orbit(q, 20, 15, 2.0), rep, false, 0, false, m);  // skips off: nothing known on the GPU
        f.draw(q, orbit(q, 20, 15, 2.0), rep, true, 0, false, m);   // skips on: uploads everything once
        EXPECT_FALSE(fired(rep, kSkipPartialUpload));
        EXPECT_EQ(rep.uploaded_texels, all);
        for (double az : {23.0, 27.0, 20.0}) {
            const Camera cam = orbit(q, az, 15 + az / 10, 2.0);
            const ImageRGBA8 partial = f.draw(q, cam, rep, true, 0, false, m);
            EXPECT_FALSE(fired(rep, kSkipReuse));
            EXPECT_TRUE(fired(rep, kSkipPartialUpload));
            // The block covers 1.6% of the texels; with its parallax in two views, well under a tenth.
            EXPECT_GT(rep.uploaded_texels, 16 * 16);
            EXPECT_LT(rep.uploaded_texels, all / 10);
            const ImageRGBA8 full = f.draw(q, cam, rep, false, 0, false, m);
            EXPECT_EQ(rep.uploaded_texels, all);
            EXPECT_EQ(partial, full) << "azimuth " << az;
            f.draw(q, cam, rep, true, 0, false, m);  // skips on again: the texture is known once more
        }
    }
}

// The footprint bound itself, on the CPU over random reliefs and pairs of views: pixels outside the union of the
// two views' moving footprints are the same in both pre-warps (both reconstructions, both paths, margins, marks).
TEST(ViewAnalysis, MovingFootprintHoldsEveryChange) {
    const uint64_t seed = test::test_seed(91001);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int compared = 0, small = 0;
    for (int i = 0; i < 400; ++i) {
        const int w = 8 + int(rng() % 60), h = 8 + int(rng() % 60);
        const int bx = int(rng() % uint64_t(w)), by = int(rng() % uint64_t(h)), bs = 1 + int(rng() % 8);
        const double amp = 0.05 + U(rng) * 0.3, lo = rng() % 2 ? -amp : 0.0;
        const uint32_t salt = uint32_t(rng());
        ReliefTexture t = test::make_test_relief(w, h, lo, amp, [&](int x, int r) {
            if (x < bx || x >= bx + bs || r < by || r >= by + bs) return 0.0;  // the still wall
            const uint32_t s = (uint32_t(x) * 0x9E3779B1u) ^ (uint32_t(r) * 0x85EBCA77u) ^ salt;
            return lo + (amp - lo) * double((s * 2654435761u) >> 8) / 16777216.0;
        });
        t.geometry.a = {1.0 / w, 0, 0};
        t.geometry.b = {0, 1.0 / h, 0};
        if (rng() % 3 == 0) mark_discontinuities(t, amp * 0.3);
        if (rng() % 4 == 0)
            for (size_t k = 0; k < t.texels.size(); k += 5) t.texels.edit()[k].q = kEmptyIndex;
        PrewarpOptions o;
        o.method = rng() % 2 ? Reconstruction::two_pass : Reconstruction::pipelined;
        o.exact = rng() % 2;
        o.keep_outliers = rng() % 2;
        o.isa = rng() % 2 ? Isa::automatic : Isa::generic;
        if (o.method == Reconstruction::two_pass && rng() % 3 == 0) o.filter = Filter::coverage;
        auto eye = [&] {
            return glm::dvec3(U(rng) * 3 - 1, U(rng) * 3 - 1, (rng() % 4 == 0 ? 0.1 + amp * U(rng) : 0.5 + U(rng) * 3));
        };
        const glm::dvec3 e0 = eye(), e1 = rng() % 2 ? eye() : e0 + glm::dvec3(U(rng), U(rng), 0) * 0.05;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i));
        const PrewarpCoefficients k0 = compute_coefficients(t.geometry, e0), k1 = compute_coefficients(t.geometry, e1);
        PrewarpWorkspace ws;
        ImageRGBA8 a, b;
        const PrewarpStats s0 = prewarp(t, k0, o, ws, a), s1 = prewarp(t, k1, o, ws, b);
        if (!(s0.extent == s1.extent)) continue;  // other margins: the whole texture goes up anyway
        const MovingTexels m = moving_texels(t);
        const PixelRect r = united(moving_footprint(t, m, k0, s0.extent), moving_footprint(t, m, k1, s1.extent));
        ++compared;
        small += r.area() * 2 < (long long)a.width * a.height;
        for (int row = 0; row < a.height; ++row)
            for (int x = 0; x < a.width; ++x) {
                if (x >= r.x && x < r.x + r.w && row >= r.row && row < r.row + r.h) continue;
                ASSERT_EQ(a.at(x, row), b.at(x, row)) << "pixel (" << x << ", " << row << ") outside the footprint "
                                                      << r.x << "," << r.row << " " << r.w << "x" << r.h;
            }
    }
    EXPECT_GT(compared, 200);
    EXPECT_GT(small, compared / 2);  // the bound is tight enough to be worth something
}

TEST(Skips, ZeroDisplacementRunsOnTheBrickWall) {
    Frame f;
    ReliefQuad bricks(to_relief(make_brick_wall(64)));
    const long long still = count_still_texels(bricks.relief(), false);
    ASSERT_GT(still, 64 * 64 / 2);  // the bricks themselves are at zero displacement
    const Camera cam = orbit(bricks, 25, 20, 2.0);
    for (RenderMethod m : {RenderMethod::two_pass, RenderMethod::pipelined}) {
        SCOPED_TRACE(to_string(m));
        DrawReport rep;
        // The reference kernels (the paper's scalar setting) count what they copy.
        const ImageRGBA8 with = f.draw(bricks, cam, rep, true, 0, true, m, false);
        EXPECT_TRUE(fired(rep, kSkipZeroRuns));
        EXPECT_EQ(rep.still_texels, still);
        EXPECT_GT(rep.still_copied, still * 9 / 10);
        EXPECT_LE(rep.still_copied, still);
        // --no-skips warps every texel: the same picture.
        const ImageRGBA8 without = f.draw(bricks, cam, rep, false, 0, true, m, false);
        EXPECT_FALSE(fired(rep, kSkipZeroRuns));
        EXPECT_EQ(rep.still_copied, 0);
        EXPECT_EQ(with, without);
        // The fast kernels copy such spans without counting; the skip is reported from the level's count.
        f.draw(bricks, orbit(bricks, 35, 20, 2.0), rep, true, 0, true, m, true);
        EXPECT_EQ(fired(rep, kSkipZeroRuns), rep.still_texels == still);
        if (default_isa() != Isa::generic) {
            EXPECT_TRUE(fired(rep, kSkipZeroRuns));
            EXPECT_EQ(rep.still_copied, 0);
        }
    }
    // A relief with no texel at zero displacement: nothing to copy, nothing reported.
    ReliefQuad raised(test::make_test_relief(32, 32, 0.01, 0.1, [](int x, int) { return 0.01 + 0.001 * x; }));
    DrawReport rep;
    f.draw(raised, orbit(raised, 25, 20, 2.0), rep, true, 0, true, RenderMethod::two_pass, false);
    EXPECT_FALSE(fired(rep, kSkipZeroRuns));
    EXPECT_EQ(rep.still_texels, 0);
    // A reused pre-warp copies nothing either.
    f.draw(bricks, cam, rep, true, 0, true, RenderMethod::two_pass, false);
    f.draw(bricks, cam, rep, true, 0, true, RenderMethod::two_pass, false);
    EXPECT_TRUE(fired(rep, kSkipReuse));
    EXPECT_FALSE(fired(rep, kSkipZeroRuns));
}

// A margin's texel is seen only where its plane point projects into the viewport (texmap/wall_clip.h), so
// visible_margins must keep every such texel: random reliefs' planes and cameras, every margin texel centre whose
// plane point lies strictly inside the viewing cone is within the returned margins; none is ever larger than the
// full margins. Exact geometry, up to the guard (0 here: the test asks for the bare bound).
TEST(ViewAnalysis, VisibleMarginsKeepEveryTexelInView) {
    const uint64_t seed = test::test_seed(20261203);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0), S(0.0, 1.0);
    int cut = 0, checked = 0;
    for (int iter = 0; iter < 300; ++iter) {
        ReliefTexture t;
        t.width = 8 + int(S(rng) * 40);
        t.height = 8 + int(S(rng) * 40);
        t.geometry.origin = {U(rng), U(rng), U(rng)};
        t.geometry.a = glm::dvec3{U(rng), U(rng), U(rng)} * 0.05;
        t.geometry.b = glm::cross(glm::dvec3{U(rng), U(rng), U(rng)}, t.geometry.a);
        if (!(glm::length(t.geometry.b) > 1e-4) || !(glm::length(t.geometry.a) > 1e-3)) continue;
        t.geometry.b = glm::normalize(t.geometry.b) * 0.05 * (0.5 + S(rng));
        const PrewarpExtent full{int(S(rng) * 60), int(S(rng) * 60), int(S(rng) * 60), int(S(rng) * 60)};
        Camera cam;
        cam.width = 64 + int(S(rng) * 128);
        cam.height = 64 + int(S(rng) * 128);
        cam.fov_deg = 20 + 80 * S(rng);
        cam.eye = t.geometry.origin + glm::dvec3{U(rng), U(rng), U(rng)} * 3.0;
        cam.look_at = t.geometry.origin + glm::dvec3{U(rng), U(rng), U(rng)} * 1.5;
        const PrewarpExtent e = visible_margins(cam, t, full, 0.0);
        ASSERT_LE(e.left, full.left);
        ASSERT_LE(e.right, full.right);
        ASSERT_LE(e.bottom, full.bottom);
        ASSERT_LE(e.top, full.top);
        ASSERT_GE(std::min({e.left, e.right, e.bottom, e.top}), 0);
        cut += !(e == full);
        const glm::dmat4 m = cam.projection() * cam.view();
        for (int y = -full.bottom; y < t.height + full.top; ++y)
            for (int x = -full.left; x < t.width + full.right; ++x) {
                const double u = x + 0.5, v = y + 0.5;
                const glm::dvec4 c = m * glm::dvec4(t.geometry.origin + u * t.geometry.a + v * t.geometry.b, 1.0);
                if (!(c.w > 0) || !(std::abs(c.x) < c.w) || !(std::abs(c.y) < c.w)) continue;
                ++checked;
                ASSERT_GE(x, -e.left) << "iter " << iter;
                ASSERT_LT(x, t.width + e.right) << "iter " << iter;
                ASSERT_GE(y, -e.bottom) << "iter " << iter;
                ASSERT_LT(y, t.height + e.top) << "iter " << iter;
            }
    }
    EXPECT_GT(cut, 30);  // the sweep reaches views that cut margins
    EXPECT_GT(checked, 10000);
}

// offscreen-margins: close to a tall relief, most of its margins project outside the viewport and are not
// pre-warped; the picture is the one the full margins give, and far away (the whole relief in view) nothing is cut.
TEST(Skips, OffscreenMarginsKeepThePicture) {
    Frame f;
    ReliefQuad q(to_relief(make_ridges(64)));
    DrawReport rep;
    int fired_views = 0;
    for (const auto& [az, el, dist] :
         {std::tuple{20.0, 35.0, 0.9}, {-40.0, 25.0, 0.8}, {60.0, 50.0, 1.0}, {0.0, 70.0, 0.7}, {-75.0, 20.0, 1.2}}) {
        SCOPED_TRACE("az " + std::to_string(az) + " el " + std::to_string(el) + " dist " + std::to_string(dist));
        Camera cam = orbit(q, az, el, dist);
        // Look past the quad's centre so that part of the relief and its margins leave the view.
        cam.look_at += (cam.look_at - cam.eye) * 0.2 + glm::dvec3(0.15, 0.1, 0.0);
        const ImageRGBA8 cut = f.draw(q, cam, rep);
        fired_views += fired(rep, kSkipOffscreenMargins);
        const PrewarpExtent used = q.last_stats().extent;
        const ImageRGBA8 tex_cut = q.prewarped();
        const ImageRGBA8 whole = f.draw(q, cam, rep, true, 0, true, RenderMethod::two_pass, true, false);
        EXPECT_FALSE(fired(rep, kSkipOffscreenMargins));
        const PrewarpExtent all = q.last_stats().extent;
        {
            const ImageRGBA8& tw = q.prewarped();
            int tdiff = 0;
            for (int y = 0; y < tex_cut.height; ++y)
                for (int x = 0; x < tex_cut.width; ++x) {
                    const Rgba8 a = tex_cut.at(x, y), b = tw.at(x + all.left - used.left, y + all.top - used.top);
                    tdiff += !(a == b);
                }
            // The kept part is the same pre-warp: only a sample's position rounds differently now and then, its
            // pixel index being the sum of the position and another margin (float).
            EXPECT_LE(tdiff * 1000, tex_cut.width * tex_cut.height) << tdiff << " texels differ";
        }
        EXPECT_LE(used.left + used.right + used.bottom + used.top, all.left + all.right + all.bottom + all.top);
        int differ = 0, maxd = 0;
        for (size_t i = 0; i < cut.pixels.size(); ++i) {
            const Rgba8 a = cut.pixels[i], b = whole.pixels[i];
            const int d = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b),
                                    std::abs(a.a - b.a)});
            differ += d != 0;
            maxd = std::max(maxd, d);
        }
        // The texture has another size, so the texture coordinates of the quad and side polygons differ and
        // llvmpipe's interpolation rounds otherwise at a few pixels: one level, at most 0.1% of the pixels.
        EXPECT_LE(maxd, 1);
        EXPECT_LE(differ * 1000, int(cut.pixels.size())) << differ << " pixels differ";
    }
    EXPECT_GE(fired_views, 3);
    f.draw(q, orbit(q, 20, 35, 4.0), rep);  // the whole relief and its margins in view
    EXPECT_FALSE(fired(rep, kSkipOffscreenMargins));
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
