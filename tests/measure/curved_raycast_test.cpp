// The CPU ray caster of the relief bent over a cylinder or sphere patch (measure/curved_raycast.h), the curved base's
// second truth: known answers on the step relief (a ray down the patch's normal onto a texel centre, on the block or
// on the ground, returns that texel's colour; oblique rays onto the block's top stop there; a ray past the patch
// returns the background) and the same image for any number of threads. Its agreement with the curved micro-polygon
// mesh is checked by tests/cli/compare.sh.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "measure/curved_raycast.h"
#include "objects/bounds.h"
#include "procedural/known_answer.h"
#include "procedural/procedural_media.h"
#include "texmap/camera_rig.h"

namespace rtm {
namespace {

// A 3x3 camera whose middle pixel's ray runs from `eye` through `at` (the pixel centre is the image centre).
Camera narrow_camera(const glm::dvec3& eye, const glm::dvec3& at, const glm::dvec3& up) {
    Camera cam;
    cam.eye = eye;
    cam.look_at = at;
    cam.up = up;
    cam.fov_deg = 1.0;
    cam.width = cam.height = 3;
    cam.fit_clip_planes(at, 2.0);
    return cam;
}

TEST(CurvedRaycast, ARayDownTheNormalOntoATexelCentreReturnsItsColour) {
    const ReliefTexture t = to_relief(make_step(64));
    const CurvedPatch p = curved_patch_for(t);
    const double range = t.quant.max - t.quant.min;
    ASSERT_GT(range, 0);
    // On the block (depth 0; texel 20 is the block's first column, next to the wall), on the ground (depth 1) in
    // the middle and near the borders.
    const std::pair<int, int> texels[] = {{32, 32}, {20, 33}, {40, 25}, {5, 5}, {60, 50}, {12, 40}};
    int block = 0, ground = 0;
    for (const auto& [i, row] : texels) {
        SCOPED_TRACE(std::to_string(i) + ", " + std::to_string(row));
        // Texture coordinates of the texel centre as curved_micromesh places it (row 0 at t = 1).
        const double s = (i + 0.5) / t.width, tt = (t.height - 1 - row + 0.5) / t.height;
        const double d = (t.quant.max - t.displ(i, row)) / range;
        block += d == 0.0;
        ground += d == 1.0;
        const Camera cam = narrow_camera(p.point(s, tt, d - 4.0), p.point(s, tt, d), p.b_hat);
        const ImageRGBA8 img = raycast_curved_relief(t, p, cam, 1);
        const ReliefTexel& x = t.texel(i, row);
        const Rgba8 got = img.at(1, 1), want{x.r, x.g, x.b, 255};
        EXPECT_EQ(got, want) << int(got.r) << " " << int(got.g) << " " << int(got.b) << " against " << int(x.r) << " "
                             << int(x.g) << " " << int(x.b);
    }
    EXPECT_EQ(block, 3);  // the texels above are what they are meant to test
    EXPECT_EQ(ground, 3);
    // Past the patch along b (t = 1.5): nothing to hit, the background.
    const Camera past = narrow_camera(p.point(0.5, 1.5, -4.0), p.point(0.5, 1.5, 0.0), p.b_hat);
    EXPECT_EQ(raycast_curved_relief(t, p, past, 1).at(1, 1), (Rgba8{0, 0, 0, 255}));
}

// The step's block lies at the top of the range, on the outer surface of the shell. Rays onto it from oblique
// directions, on both shapes, must stop there: with the shell exactly at the top, rounding put the first sample under
// the block's top for some of them, and they went through the block (speckles on it in the shadow truth). Each ray
// aims at a texel centre inside the block, from above, at 10 to 70 degrees from the normal in several azimuths; the
// colour must be that texel's (the block is coloured smoothly, so a ray through it lands elsewhere with another).
TEST(CurvedRaycast, ObliqueRaysOntoTheTopOfTheRangeStopThere) {
    const ReliefTexture t = to_relief(make_step(64));
    for (CurvedShape shape : {CurvedShape::cylinder, CurvedShape::sphere}) {
        const CurvedPatch p = curved_patch_for(t, shape);
        int tested = 0;
        for (int i = 22; i <= 42; i += 4)
            for (int row = 22; row <= 42; row += 5) {
                const double s = (i + 0.5) / t.width, tt = (t.height - 1 - row + 0.5) / t.height;
                ASSERT_EQ(t.displ(i, row), t.quant.max);  // on the block
                const glm::dvec3 at = p.point(s, tt), N = p.normal(s, tt), T = p.tangent(s, tt), B = p.binormal(s, tt);
                for (double deg : {10.0, 40.0, 70.0})
                    for (double az : {0.0, 1.3, 2.9, 4.4}) {
                        const double a = deg * M_PI / 180.0;
                        const glm::dvec3 from = at + 0.05 * (std::cos(a) * N +
                                                             std::sin(a) * (std::cos(az) * T + std::sin(az) * B));
                        const Camera cam = narrow_camera(from, at, std::abs(glm::dot(N, B)) < 0.9 ? B : T);
                        const Rgba8 got = raycast_curved_relief(t, p, cam, 1).at(1, 1);
                        const ReliefTexel& x = t.texel(i, row);
                        EXPECT_EQ(got, (Rgba8{x.r, x.g, x.b, 255})) << to_string(shape) << " texel " << i << "," << row
                                                                    << " at " << deg << " degrees, azimuth " << az;
                        ++tested;
                    }
            }
        EXPECT_EQ(tested, 6 * 5 * 12);
    }
}

TEST(CurvedRaycast, TheImageDoesNotDependOnTheThreadCount) {
    const ReliefTexture t = to_relief(make_bumps(64));
    const CurvedPatch p = curved_patch_for(t);
    const Bounds b = relief_bounds(t);
    const Camera cam = orbit_camera(b.centre(), b.radius(), {40, 20, 2.2}, 64, 48);
    const ImageRGBA8 one = raycast_curved_relief(t, p, cam, 1), two = raycast_curved_relief(t, p, cam, 2);
    EXPECT_EQ(one.pixels, two.pixels);
    int covered = 0;
    for (const Rgba8& x : one.pixels) covered += x.r || x.g || x.b;
    EXPECT_GT(covered, 64 * 48 / 10);  // the patch fills a good part of the frame
}

}  // namespace
}  // namespace rtm
