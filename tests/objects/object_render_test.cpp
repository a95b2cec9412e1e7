// Six-face objects rendered by relief texture mapping (at most three quads) against their micro-polygon truth (the
// six faces' meshes), frame by frame from one-, two- and three-face views and views on region boundaries: coverage
// IoU and PSNR with stated thresholds, no cracks along the box's edges, depth correction against other geometry.
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <glm/mat4x4.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "formats/image_io.h"
#include "measure/image_diff.h"
#include "objects/relief_object.h"
#include "procedural/synthetic_object.h"
#include "texmap/gl_context.h"

namespace rtm {
namespace {

constexpr int kTexels = 64;  // per face side
constexpr int kPixels = 256;

struct Gl {
    std::unique_ptr<GlContext> ctx = GlContext::create_offscreen(kPixels, kPixels);
    Renderer renderer;
};

Camera camera(const glm::dvec3& eye) {
    Camera cam;
    cam.eye = eye;
    cam.look_at = glm::dvec3(0.0);
    cam.width = cam.height = kPixels;
    cam.fit_clip_planes(glm::dvec3(0.0), std::sqrt(3.0));
    return cam;
}

// Orbit as on the command line: azimuth about +y from +z, elevation, distance in bounding-sphere radii.
glm::dvec3 orbit(double az_deg, double el_deg, double d) {
    const double az = glm::radians(az_deg), el = glm::radians(el_deg), r = std::sqrt(3.0) * d;
    return r * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
}

struct View {
    const char* name;
    glm::dvec3 eye;
    size_t faces;  // visible faces
};

const View kViews[] = {
    {"one face +z", orbit(0, 0, 3), 1},
    {"one face -y", orbit(20, -80, 3), 1},
    {"two faces +x +z", orbit(45, 0, 3), 2},
    {"two faces -x +y", orbit(-80, 40, 2.5), 2},
    {"three faces +x +y +z", orbit(45, 35, 3), 3},
    {"three faces -x -y -z", orbit(210, -30, 2.5), 3},
    {"on the plane x = 1", {1.0, 0.3, 4.5}, 1},
    {"a hair outside x = 1", {std::nextafter(1.0, 2.0), 0.3, 4.5}, 2},
    {"on the edge x = y = 1", {1.0, 1.0, 4.5}, 1},
    {"close, three faces", orbit(130, 25, 1.6), 3},
};

void dump(const std::string& name, const ImageRGBA8& img) {
    if (const char* dir = std::getenv("RTM_DUMP")) {
        std::string file = name;
        for (char& c : file)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        write_rgba8(std::string(dir) + "/" + file + ".png", img);
    }
}

// Pixels near the projection of the box's 12 edges (within 3 pixels of a segment).
std::vector<uint8_t> near_box_edges(const Camera& cam) {
    std::vector<uint8_t> mask(size_t(kPixels) * kPixels, 0);
    const glm::dmat4 vp = cam.projection() * cam.view();
    auto project = [&](const glm::dvec3& p) {
        const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
        return glm::dvec2((c.x / c.w * 0.5 + 0.5) * kPixels, (0.5 - c.y / c.w * 0.5) * kPixels);
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int s1 = -1; s1 <= 1; s1 += 2)
            for (int s2 = -1; s2 <= 1; s2 += 2) {
                glm::dvec3 a(0.0), b(0.0);
                a[axis] = -1;
                b[axis] = 1;
                a[(axis + 1) % 3] = b[(axis + 1) % 3] = s1;
                a[(axis + 2) % 3] = b[(axis + 2) % 3] = s2;
                const glm::dvec2 pa = project(a), pb = project(b);
                for (int row = 0; row < kPixels; ++row)
                    for (int x = 0; x < kPixels; ++x) {
                        const glm::dvec2 p(x + 0.5, row + 0.5), ab = pb - pa;
                        const double t = std::clamp(glm::dot(p - pa, ab) / std::max(glm::dot(ab, ab), 1e-12), 0.0, 1.0);
                        if (glm::length(p - (pa + t * ab)) <= 3.0) mask[size_t(row) * kPixels + size_t(x)] = 1;
                    }
            }
    return mask;
}

// Background pixels of `test` inside the truth's coverage: pixels whose 5x5 neighbourhood is all covered in the
// truth (so silhouettes, where resampling differs, do not count), restricted to `mask` when given.
int holes(const ImageRGBA8& truth, const ImageRGBA8& test, const std::vector<uint8_t>* mask = nullptr) {
    int n = 0;
    for (int row = 2; row < kPixels - 2; ++row)
        for (int x = 2; x < kPixels - 2; ++x) {
            if (mask && !(*mask)[size_t(row) * kPixels + size_t(x)]) continue;
            bool interior = true;
            for (int dy = -2; dy <= 2 && interior; ++dy)
                for (int dx = -2; dx <= 2 && interior; ++dx) interior = covered(truth.at(x + dx, row + dy));
            n += interior && !covered(test.at(x, row));
        }
    return n;
}

struct Thresholds {
    double iou, psnr;
    int holes, edge_holes;
};

void compare_with_truth(SyntheticShape shape, RenderMethod method, bool depth, const Thresholds& th,
                        Filter filter = Filter::point) {
    Gl gl;
    ReliefObject object(make_synthetic_object(shape, kTexels));
    PrewarpOptions o;
    o.filter = filter;
    DrawOptions d;
    d.depth_correction = depth;
    for (const View& v : kViews) {
        SCOPED_TRACE(to_string(shape) + " " + to_string(method) + ", " + v.name);
        const Camera cam = camera(v.eye);
        StageTimes t;
        ObjectReport rep;
        const ImageRGBA8 truth = render_object_frame(object, gl.renderer, cam, RenderMethod::micromesh, o, d, t);
        const ImageRGBA8 img = render_object_frame(object, gl.renderer, cam, method, o, d, t, &rep);
        dump(to_string(shape) + "_" + to_string(method) + "_" + v.name, img);
        dump(to_string(shape) + "_truth_" + v.name, truth);
        EXPECT_EQ(rep.region.visible_faces().size(), v.faces);
        EXPECT_LE(rep.faces.size(), 3u);
        const DiffResult r = diff_images(truth, img);
        const int h = holes(truth, img);
        const std::vector<uint8_t> edges = near_box_edges(cam);
        const int eh = holes(truth, img, &edges);
        std::printf("%-14s %-10s %-24s depth %d: iou %.4f psnr %.2f holes %d near edges %d\n", to_string(shape).c_str(),
                    to_string(method).c_str(), v.name, int(depth), r.iou, r.psnr, h, eh);
        EXPECT_GE(r.iou, th.iou);
        EXPECT_GE(r.psnr, th.psnr);
        EXPECT_LE(h, th.holes);
        EXPECT_LE(eh, th.edge_holes);
    }
}

// Thresholds. The truth's micro-polygons join every 2x2 block of non-empty texels, so at the shapes' steep slopes
// and steps they stretch skins (the cross walls, the sphere's rim) that the pre-warp leaves to the adjacent faces;
// the two agree on coverage to a few percent and on colour to the resampling of 64-texel faces on 256-pixel views.
// The figures printed by the test (measured on llvmpipe) sit above the thresholds by about 2 dB and 0.02: sphere
// IoU 0.960..0.990, PSNR 26.9..34.7 dB, no interior holes; rounded cube IoU 0.979..0.997, PSNR 29.3..36.5 dB,
// at most 17 interior holes and none within 3 pixels of a projected box edge (no cracks along edges and corners).
TEST(ObjectRender, SphereTwoPassMatchesMicromesh) {
    compare_with_truth(SyntheticShape::sphere, RenderMethod::two_pass, false, {0.95, 25.0, 10, 0});
}
TEST(ObjectRender, SpherePipelinedMatchesMicromesh) {
    compare_with_truth(SyntheticShape::sphere, RenderMethod::pipelined, false, {0.95, 25.0, 10, 0});
}
TEST(ObjectRender, SphereDepthCorrection) {
    compare_with_truth(SyntheticShape::sphere, RenderMethod::two_pass, true, {0.95, 25.0, 10, 0});
}
// The coverage filter: the face's own fractional coverage meets the adjacent faces' point samples at the seams, and
// the texture-mapping stage discards what is covered less than half. Measured IoU 0.971..0.989, PSNR 23.4..30.1 dB,
// up to 430 interior holes in the close view: a known problem (docs/OBJECTS.md); the thresholds hold the figures.
TEST(ObjectRender, SphereCoverageFilter) {
    compare_with_truth(SyntheticShape::sphere, RenderMethod::two_pass, false, {0.96, 22.5, 480, 12}, Filter::coverage);
}
TEST(ObjectRender, RoundedCubeHasNoCracks) {
    compare_with_truth(SyntheticShape::rounded_cube, RenderMethod::two_pass, true, {0.96, 27.0, 25, 0});
}
// The cross-box is the hard case: every cross wall is seen only by an adjacent face, at grazing angles from close
// views, and the walls' samples are spread over many pixels. Measured: IoU 0.951..0.973, PSNR 18.5..23.2 dB, up to
// 1172 interior holes (close three-face view) and 108 near the box's edges; the thresholds hold these figures so
// that a regression shows, and the holes are a known problem (docs/OBJECTS.md, "Limitations").
TEST(ObjectRender, CrossBoxMatchesMicromesh) {
    compare_with_truth(SyntheticShape::cross_box, RenderMethod::two_pass, true, {0.94, 18.0, 1300, 120});
}

}  // namespace
}  // namespace rtm

namespace rtm {
namespace {

// Depth correction (section 4.2) lets the object occlude and be occluded by other geometry: a square through the
// sphere's centre (z = 0) cuts it in half. With the perceived depth the object's pixels and the square's agree with
// the micro-polygon truth drawn with the same square; without it the box faces' own depths hide the square.
// The per-face plans carried out (objects/object_plan.h): the same eye again reuses every face's pre-warp and uploads
// nothing, and draws the same image; a moved eye pre-warps again and draws what a fresh object draws. Skips off
// pre-warps every frame.
TEST(ObjectRender, ReusedFacesDrawTheSameImage) {
    Gl gl;
    ReliefObject object(make_synthetic_object(SyntheticShape::sphere, kTexels));
    const Camera cam = camera(orbit(45, 35, 3));
    PrewarpOptions o;
    DrawOptions d;
    d.depth_correction = true;
    StageTimes t;
    ObjectReport first, again;
    const ImageRGBA8 a = render_object_frame(object, gl.renderer, cam, RenderMethod::two_pass, o, d, t, &first);
    const ImageRGBA8 b = render_object_frame(object, gl.renderer, cam, RenderMethod::two_pass, o, d, t, &again);
    ASSERT_EQ(first.faces.size(), 3u);
    ASSERT_EQ(again.faces.size(), 3u);
    for (const ObjectFaceReport& f : again.faces) {
        EXPECT_EQ(f.skips, (std::vector<std::string>{kSkipReuse, kSkipPartialUpload})) << kFaceKeys[size_t(f.face)];
        EXPECT_EQ(f.prewarp_ms, 0.0);
        EXPECT_EQ(f.adjacent.size(), 2u);
    }
    EXPECT_TRUE(a == b) << "a reused frame differs";

    const Camera moved = camera(orbit(50, 30, 3));
    ObjectReport rep;
    const ImageRGBA8 c = render_object_frame(object, gl.renderer, moved, RenderMethod::two_pass, o, d, t, &rep);
    for (const ObjectFaceReport& f : rep.faces) EXPECT_TRUE(f.skips.empty()) << kFaceKeys[size_t(f.face)];
    ReliefObject fresh(make_synthetic_object(SyntheticShape::sphere, kTexels));
    const ImageRGBA8 e = render_object_frame(fresh, gl.renderer, moved, RenderMethod::two_pass, o, d, t);
    EXPECT_TRUE(c == e) << "a pre-warp after a reuse differs from a fresh object's";

    DrawOptions off = d;
    off.skips = false;
    render_object_frame(object, gl.renderer, moved, RenderMethod::two_pass, o, off, t, &rep);
    for (const ObjectFaceReport& f : rep.faces) EXPECT_TRUE(f.skips.empty()) << kFaceKeys[size_t(f.face)];
}

TEST(ObjectRender, DepthCorrectionOccludesOtherGeometry) {
    Gl gl;
    ReliefObject object(make_synthetic_object(SyntheticShape::sphere, kTexels));
    const glm::u8vec4 magenta(255, 0, 255, 255);
    const std::vector<MeshVertex> square = {{{-1.6f, -1.6f, 0.0f}, magenta},
                                            {{1.6f, -1.6f, 0.0f}, magenta},
                                            {{1.6f, 1.6f, 0.0f}, magenta},
                                            {{-1.6f, 1.6f, 0.0f}, magenta}};
    const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
    for (const View& v : kViews) {
        if (v.faces < 2) continue;  // the square is seen edge-on or not at all from the one-face views
        SCOPED_TRACE(v.name);
        const Camera cam = camera(v.eye);
        gl.renderer.begin_frame(cam);
        object.draw_micromesh(gl.renderer, cam);
        gl.renderer.draw_mesh(cam, square, idx);
        const ImageRGBA8 truth = gl.renderer.read_pixels(kPixels, kPixels);
        auto draw = [&](bool depth) {
            DrawOptions d;
            d.depth_correction = depth;
            StageTimes t;
            gl.renderer.begin_frame(cam);
            object.draw(gl.renderer, cam, RenderMethod::two_pass, {}, t, d);
            gl.renderer.draw_mesh(cam, square, idx);
            return gl.renderer.read_pixels(kPixels, kPixels);
        };
        const ImageRGBA8 with = draw(true), without = draw(false);
        dump(std::string("occlusion_") + v.name, with);
        // Pixels whose "is it the square" answer differs from the truth's.
        auto wrong = [&](const ImageRGBA8& img) {
            int n = 0;
            for (size_t i = 0; i < img.pixels.size(); ++i) {
                const bool a = truth.pixels[i].r == 255 && truth.pixels[i].g == 0 && truth.pixels[i].b == 255;
                const bool b = img.pixels[i].r == 255 && img.pixels[i].g == 0 && img.pixels[i].b == 255;
                n += a != b;
            }
            return n;
        };
        const int w_with = wrong(with), w_without = wrong(without);
        std::printf("%-24s square pixels differing from the truth: %d with depth correction, %d without\n", v.name,
                    w_with, w_without);
        // The intersection curve is resampled differently (8-bit depth over the box's 2 units, 64-texel faces):
        // a band of pixels along it: measured 22 to 423 pixels (0.6% of the image); the threshold is 1.7%.
        EXPECT_LE(w_with, kPixels * kPixels / 60);
        // Without depth correction the box faces hide the square wherever it passes in front of the sphere's far
        // half; that discriminates only when the square is seen at an angle (the eye 20 degrees or more off its
        // normal: from near the z axis the sphere's near half hides it either way).
        if (std::abs(v.eye.z) < std::cos(glm::radians(20.0)) * glm::length(v.eye)) {
            EXPECT_LT(w_with * 3, w_without);
        }
    }
}

}  // namespace
}  // namespace rtm
