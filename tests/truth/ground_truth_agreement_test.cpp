// The two ground truths agree: the micro-polygon mesh rendered through OpenGL (OSMesa) and the exact ray caster
// of the bilinear height field, for the same relief and camera.
//
// They differ only inside each cell -- two triangles (split along the low-to-high (u, v) diagonal) versus the
// bilinear patch, i.e. heights differing by at most |h00 - h10 - h01 + h11|/4 and colours interpolated linearly
// per triangle versus bilinearly -- and in sampling: OpenGL rasterizes at pixel centres with float vertices and
// 8-bit colour interpolation, the caster traces the same pixel-centre rays in double. Silhouettes (the relief's
// border, the rim of the hole, occluding ridges) move by a fraction of a pixel, where a pixel can change from
// one surface to another or to the background.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <memory>
#include <string>

#include "ground_truth_util.h"
#include "objects/bounds.h"
#include "measure/image_diff.h"
#include "truth/micromesh.h"
#include "truth/raycast.h"
#include "texmap/gl_context.h"
#include "texmap/renderer.h"

namespace rtm {
namespace {

// Smooth hills (up to ~10 texels high) with smooth colours, and a round hole.
ReliefTexture hills(int n) {
    ReliefGeometry g;
    g.origin = {-0.32, -0.3, 0.0};
    g.a = {0.01, 0.0, 0.0015};  // not axis-aligned, not square
    g.b = {0.0, 0.009, 0.0};
    const auto height = [&](int x, int r) {
        const double u = (x + 0.5) / n, v = (r + 0.5) / n;
        return 0.05 * (std::sin(6.0 * u) * std::cos(5.0 * v) + 0.5 * std::sin(11.0 * u + 7.0 * v)) + 0.05;
    };
    const auto colour = [&](int x, int r) {
        const double u = (x + 0.5) / n, v = (r + 0.5) / n;
        return Rgba8{uint8_t(40 + 200 * u), uint8_t(128 + 100 * std::sin(9.0 * v)),
                     uint8_t(128 + 100 * std::cos(7.0 * (u + v))), 255};
    };
    const auto hole = [&](int x, int r) {
        const double dx = x - 0.7 * n, dy = r - 0.3 * n;
        return dx * dx + dy * dy < 0.01 * n * n;
    };
    return truth_test::make_relief_fn(n, n, g, height, colour, hole);
}

// Rough: per-texel noise of +-2 texels in height over steep ridges, colours with per-texel noise of +-32 levels:
// here the triangle pair and the bilinear patch differ visibly inside every cell.
ReliefTexture rough(int n) {
    ReliefGeometry g;
    g.origin = {-0.3, -0.3, 0.0};
    g.a = {0.01, 0.0, 0.0};
    g.b = {0.002, 0.01, 0.0};
    const auto noise = [](int x, int r, uint32_t salt) {
        uint32_t s = (uint32_t(x) * 73856093u) ^ (uint32_t(r) * 19349663u) ^ salt;
        s *= 2654435761u;
        s ^= s >> 15;
        return double(s % 1000u) / 999.0 * 2.0 - 1.0;
    };
    const auto height = [&](int x, int r) {
        return 0.02 * noise(x, r, 1u) + 0.08 * std::max(0.0, std::sin(0.5 * x + 0.2 * r));
    };
    const auto colour = [&](int x, int r) {
        const double u = (x + 0.5) / n, v = (r + 0.5) / n;
        const auto ch = [&](double base, uint32_t salt) {
            return uint8_t(std::clamp(base + 32.0 * noise(x, r, salt), 0.0, 255.0));
        };
        return Rgba8{ch(40 + 170 * u, 2u), ch(128 + 90 * std::sin(9.0 * v), 3u),
                     ch(128 + 90 * std::cos(7.0 * (u + v)), 4u), 255};
    };
    return truth_test::make_relief_fn(n, n, g, height, colour, [](int, int) { return false; });
}

void agree(const char* relief_name, const ReliefTexture& t, double min_iou, std::array<double, 3> min_psnr) {
    SCOPED_TRACE(relief_name);
    const Bounds b = relief_bounds(t);
    const int size = 128;
    std::unique_ptr<GlContext> ctx;
    try {
        ctx = GlContext::create_offscreen(size, size);
    } catch (const std::exception& e) {
        GTEST_SKIP() << "no OpenGL context: " << e.what();
    }
    Renderer renderer;
    const MicroMesh mesh = build_micromesh(t);

    struct View {
        const char* name;
        glm::dvec3 eye;
    };
    const glm::dvec3 c = b.centre();
    const double r = b.radius();
    const View views[] = {{"front", c + glm::dvec3(0.1, 0.2, 2.2) * r},
                          {"oblique", c + glm::dvec3(1.2, -0.8, 1.4) * r},
                          {"grazing", c + glm::dvec3(-0.4, -1.9, 0.7) * r}};
    for (const View& v : views) {
        SCOPED_TRACE(v.name);
        Camera cam;
        cam.eye = v.eye;
        cam.look_at = c;
        cam.up = {0, 1, 0};
        cam.fov_deg = 45;
        cam.width = cam.height = size;
        cam.fit_clip_planes(c, r);
        renderer.begin_frame(cam);
        draw_mesh(renderer, cam, mesh);
        renderer.finish();
        const ImageRGBA8 gl = renderer.read_pixels(size, size);
        const ImageRGBA8 rc = raycast_relief(t, cam);
        const DiffResult d = diff_images(rc, gl);
        std::printf("[ measured ] %s %s: %s\n", relief_name, v.name, d.to_string().c_str());
        if (const char* dir = std::getenv("RTM_TRUTH_DUMP")) {  // to look at a failure: both images as PPM
            for (int k = 0; k < 2; ++k) {
                const ImageRGBA8& im = k ? gl : rc;
                const std::string path = std::string(dir) + "/" + relief_name + "_" + v.name +
                                         (k ? "_gl.ppm" : "_rc.ppm");
                FILE* fp = std::fopen(path.c_str(), "wb");
                if (!fp) continue;
                std::fprintf(fp, "P6 %d %d 255\n", im.width, im.height);
                for (const Rgba8& p : im.pixels) std::fwrite(&p, 1, 3, fp);
                std::fclose(fp);
            }
        }
        EXPECT_GT(d.either, size * size / 8);  // not vacuous: the relief fills a good part of the view
        EXPECT_GT(d.iou, min_iou);
        EXPECT_GT(d.psnr, min_psnr[size_t(&v - views)]);
    }
}

// Thresholds, from measurements on Mesa 22.3.6 llvmpipe (Debian 12), 128x128, views front / oblique / grazing. For
// scale, "shift" is the PSNR of the ray-cast image against itself moved by one pixel (a small, real disagreement).
//
// hills: PSNR 64.2 / 63.0 / 61.6 dB (rmse 0.16-0.21 levels, max error 4), IoU 1 / 0.99986 / 0.99977 (one pixel on
//   the silhouette); shift 38.1 / 32.1 / 34.4 dB. Over smooth cells the triangle pair and the bilinear patch differ
//   by far less than a level; what remains is OpenGL's 8-bit rounding of the interpolated colour. Threshold 45 dB
//   (rmse below 1.44 levels): "every covered pixel agrees to about one level" whatever rounding another Mesa
//   version uses, and still 7 dB above a one-pixel shift.
// rough: PSNR 35.5 / 29.0 / 27.4 dB (rmse 4.3 / 9.1 / 10.9), IoU 0.99946 / 0.99366 / 0.98822; shift 25.8 / 24.3 /
//   20.9 dB. Inside each cell the colours differ by up to |c00 - c10 - c01 + c11|/4 (up to ~32 levels with this
//   noise) and the heights by up to |h00 - h10 - h01 + h11|/4 (up to 2 texels), so occluding ridges move by pixels
//   and the colour seen there jumps. The mesh covers slightly more (only_test ~50, only_ref ~1): the diagonal is
//   always the low-to-high one, and where that diagonal is a crease pointing out of the surface the triangle pair
//   bulges beyond the bilinear patch (where it is a valley, the silhouette is made by the cell edges, which the two
//   share). Thresholds 31 / 26 / 24 dB: between the measurement and the one-pixel shift, with at least 3 dB
//   (rmse x1.4) of room above the measurement.
// IoU > 0.98 for both: the ground truths must agree on what is covered.
TEST(GroundTruthAgreement, MicromeshMatchesRaycastOnSmoothHills) { agree("hills", hills(64), 0.98, {45, 45, 45}); }

TEST(GroundTruthAgreement, MicromeshMatchesRaycastOnRoughRelief) { agree("rough", rough(64), 0.98, {31, 26, 24}); }

}  // namespace
}  // namespace rtm
