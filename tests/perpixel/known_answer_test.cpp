// The per-pixel methods (perpixel/) through llvmpipe on the known-answer reliefs (procedural/known_answer.h),
// measured against the exact ray caster (truth/raycast.h) at frontal and oblique views: error over the pixels
// both cover (PSNR) and coverage (IoU).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "measure/compare.h"
#include "measure/curved_raycast.h"
#include "measure/image_diff.h"
#include "objects/render_relief.h"
#include "perpixel/curved_patch.h"
#include "procedural/known_answer.h"
#include "texmap/gl_context.h"
#include "truth/micromesh.h"
#include "formats/image_io.h"

namespace rtm {
namespace {

constexpr int kReliefSize = 64;
constexpr int kImage = 128;

struct Gl {
    std::unique_ptr<GlContext> ctx = GlContext::create_offscreen(kImage, kImage);
    std::unique_ptr<Renderer> renderer = std::make_unique<Renderer>();
};

ImageRGBA8 render(Gl& gl, ReliefQuad& quad, const Camera& cam, RenderMethod m, const PerPixelSettings& pp = {}) {
    RenderSettings s;
    s.method = m;
    s.perpixel = pp;
    StageTimes t;
    return render_relief_frame(quad, gl.renderer.get(), cam, s, t);
}

// The truth of a curved base: the relief displaced over `patch` as micro-polygons (curved_micromesh), built once and
// drawn through the same GL path for each camera.
struct CurvedTruth {
    std::vector<MeshVertex> vertices;
    std::vector<uint32_t> indices;
    CurvedTruth(const ReliefTexture& t, const CurvedPatch& patch) { curved_micromesh(t, patch, vertices, indices); }
    ImageRGBA8 draw(Gl& gl, const Camera& cam) const {
        gl.renderer->begin_frame(cam);
        gl.renderer->draw_mesh(cam, vertices, indices);
        return gl.renderer->read_pixels(cam.width, cam.height);
    }
};

const std::vector<CompareView>& views() {
    static const std::vector<CompareView> v = {{"frontal", 0, 0, 2.2},
                                               {"oblique", 35, 25, 2.2},
                                               {"grazing", 60, 15, 2.2}};
    return v;
}

TEST(PerPixel, EveryShaderVariantCompilesOnThisGl) {
    Gl gl;
    PerPixelQuad q;
    for (PerPixelMethod m : all_perpixel_methods())
        for (int bits = 0; bits < 32; ++bits) {
            PerPixelCommon c;
            c.depth_correction = bits & 1;
            c.shading = bits & 2;
            c.self_shadowing = bits & 4;
            c.iteration_counts = bits & 8;
            c.float_textures = bits & 16;
            EXPECT_NO_THROW(q.prepare(m, c)) << to_string(m) << " variant " << bits;
            if (m == PerPixelMethod::quadric_silhouettes) {
                EXPECT_NO_THROW(q.prepare(m, c, true)) << "the exact distance, variant " << bits;
            }
            if (m == PerPixelMethod::protruded_displacement) {
                EXPECT_NO_THROW(q.prepare(m, c, false, true)) << "the steep texture, variant " << bits;
            }
        }
}

TEST(PerPixel, MethodNamesRoundTrip) {
    for (PerPixelMethod m : all_perpixel_methods()) {
        const RenderMethod r = parse_render_method(to_string(m));
        EXPECT_EQ(to_string(r), to_string(m));
        ASSERT_TRUE(perpixel_method(r).has_value());
        EXPECT_EQ(*perpixel_method(r), m);
    }
    EXPECT_FALSE(perpixel_method(RenderMethod::two_pass).has_value());
    EXPECT_THROW(parse_render_method("relief-maping"), std::invalid_argument);
}

TEST(PerPixel, BadSettingsAreRejectedNamingTheValue) {
    PerPixelSettings s;
    s.relief_mapping.linear_search_steps = 0;
    try {
        s.validate();
        FAIL() << "linear_search_steps 0 accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("linear_search_steps"), std::string::npos) << e.what();
    }
    PerPixelSettings t;
    t.interval_mapping.convergence_threshold = -1;
    EXPECT_THROW(t.validate(), std::invalid_argument);
    for (float bad : {-0.1f, std::nanf("")}) {
        PerPixelSettings u;
        u.protruded_displacement.steep_threshold = bad;
        try {
            u.validate();
            FAIL() << "steep_threshold " << bad << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("steep_threshold"), std::string::npos) << e.what();
        }
    }
    PerPixelSettings w;
    w.protruded_displacement.steep_scale_x = INFINITY;
    EXPECT_THROW(w.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace rtm

namespace rtm {
namespace {

// Every method at its default settings, every known-answer relief, every view: PSNR over the pixels both cover
// and coverage IoU against the ray caster. Bounds per method (min PSNR dB, min IoU) in kBounds below.
struct Bound {
    double psnr, iou;
};

// Measured at 128x128 (llvmpipe, Mesa 22, the default float textures): the lowest over the three reliefs, less
// about 1.5 dB (PSNR) and 0.01 (IoU) so a different rasterizer's rounding does not fail them, and at most 70 dB
// (the searches' frontal figures are 75.6 to 83 dB or inf: there a few pixels one level off decide); a method
// that finds the wrong point loses far more (parallax, which reads one depth, is 15-30 dB below the searches at oblique
// views). IoU below 1 at oblique views is the top polygon: rays that enter the relief's slab through its sides never
// reach a fragment (protruded displacement mapping's side faces are what recovers them), and Welsh's offset limiting
// shifts less than the true parallax, so near the border its points fall outside the footprint. Per method: {frontal,
// oblique (az 35 el 25), grazing (az 60 el 15)} x {psnr, iou}.
const std::map<std::string, std::array<Bound, 3>> kBounds = {
    {"parallax", {{{31.0, 0.99}, {14.0, 0.80}, {10.0, 0.45}}}},
    {"parallax-offset-limiting", {{{30.0, 0.94}, {13.0, 0.74}, {10.0, 0.39}}}},
    {"steep-parallax", {{{45.5, 0.99}, {28.0, 0.83}, {21.5, 0.48}}}},
    {"parallax-occlusion", {{{70.0, 0.99}, {35.5, 0.83}, {29.5, 0.48}}}},
    {"relief-mapping", {{{70.0, 0.99}, {45.5, 0.83}, {41.5, 0.48}}}},
    {"interval-mapping", {{{70.0, 0.99}, {45.5, 0.83}, {41.5, 0.48}}}},
    // The side faces recover the rays through the slab's sides: coverage as the ray caster's.
    {"protruded-displacement", {{{70.0, 0.99}, {46.0, 0.99}, {44.5, 0.99}}}},
};

TEST(PerPixel, KnownAnswersAgainstTheRayCaster) {
    Gl gl;
    std::printf("%-12s %-8s %-26s %8s %7s\n", "relief", "view", "method", "psnr", "iou");
    for (const std::string& name : known_answer_names()) {
        ReliefQuad quad(to_relief(make_known_answer(name, kReliefSize)));
        for (size_t vi = 0; vi < views().size(); ++vi) {
            const CompareView& v = views()[vi];
            const Camera cam = compare_camera(quad, v, kImage, kImage);
            const ImageRGBA8 truth = render(gl, quad, cam, RenderMethod::raycast);
            // RTM_PERPIXEL_DUMP=DIR writes every image (to look at the errors).
            const char* dump = std::getenv("RTM_PERPIXEL_DUMP");
            const std::string stem = dump ? std::string(dump) + "/" + name + "_" + v.name + "_" : "";
            if (dump) write_rgba8(stem + "raycast.png", truth);
            for (PerPixelMethod m : all_perpixel_methods()) {
                if (m == PerPixelMethod::quadric_silhouettes) continue;  // a curved relief: its own test below
                const ImageRGBA8 img = render(gl, quad, cam, parse_render_method(to_string(m)));
                if (dump) write_rgba8(stem + to_string(m) + ".png", img);
                const DiffResult d = diff_images(truth, img);
                std::printf("%-12s %-8s %-26s %8.2f %7.4f\n", name.c_str(), v.name.c_str(), to_string(m).c_str(),
                            d.psnr, d.iou);
                const Bound& b = kBounds.at(to_string(m))[vi];
                EXPECT_GE(d.psnr, b.psnr) << name << " " << v.name << " " << to_string(m);
                EXPECT_GE(d.iou, b.iou) << name << " " << v.name << " " << to_string(m);
            }
            const DiffResult mm = diff_images(truth, render(gl, quad, cam, RenderMethod::micromesh));
            std::printf("%-12s %-8s %-26s %8.2f %7.4f\n", name.c_str(), v.name.c_str(), "micromesh", mm.psnr, mm.iou);
        }
    }
}

}  // namespace
}  // namespace rtm

namespace rtm {
namespace {

// `img` with every pixel `coverage` does not cover made background: an image's error over another one's pixels.
ImageRGBA8 restricted_to(ImageRGBA8 img, const ImageRGBA8& coverage) {
    for (size_t i = 0; i < img.pixels.size(); ++i)
        if (!covered(coverage.pixels[i])) img.pixels[i] = Rgba8{0, 0, 0, 255};
    return img;
}

// Relief mapping and interval mapping at their top settings (256 linear steps; 16 bisections / secant steps to
// 1e-4), against the micro-polygon truth, beside the exact ray caster's PSNR against it over the same pixels. The
// issue asks for "within 1 dB of the ray caster".
//
// Over the same pixels, not over all the ray caster covers: PSNR is taken over the pixels both images cover, and the
// top polygon covers about half of what the ray caster does at grazing views (IoU 0.50 to 0.53: rays entering the
// slab through its sides). Compared over their own pixels, the searches seemed 2.6 dB short of the ray caster at
// grazing on the step (42.80 against 45.42) and the pyramid (60.76 against 63.35), yet they return the ray caster's
// colour at every pixel they cover but one (the step's: a pixel at the block's edge): the same few wrong pixels at the
// edges (on the step one pixel of 3,016 holds 96% of the squared error, where the micro-polygons and the ray caster
// disagree about the block's corner) divided by half as many pixels, 10*log10(5720/3016) = 2.8 dB on the step.
//
// Measured here (128x128, llvmpipe), with the default float textures (colour and exact depth filtered in float):
// within 0.01 dB of the ray caster over the same pixels at every view of every relief; asserted: within 1 dB.
// With the papers' 8-bit textures (float_textures = false) the smooth reliefs fall 4.4 to 8.5 dB short (53.7 to
// 61 dB): llvmpipe filters RGBA8 in 8 bits and the depth has 254 levels. Asserted there what holds: the step
// within 1 dB of the ray caster (capped at 62 dB) at every view (63.34, 46.26, 42.72), the smooth reliefs
// >= 52.5 dB (53.69 the least).
TEST(PerPixel, TopSettingsWithinOneDecibelOfTheRayCaster) {
    Gl gl;
    PerPixelSettings top;
    top.relief_mapping.linear_search_steps = 256;
    top.relief_mapping.binary_search_steps = 16;
    top.interval_mapping.linear_search_steps = 256;
    top.interval_mapping.convergence_threshold = 1e-4f;
    top.interval_mapping.max_iterations = 32;
    for (const std::string& name : known_answer_names()) {
        ReliefQuad quad(to_relief(make_known_answer(name, kReliefSize)));
        quad.micromesh();
        for (const CompareView& v : views()) {
            const Camera cam = compare_camera(quad, v, kImage, kImage);
            const ImageRGBA8 mesh = render(gl, quad, cam, RenderMethod::micromesh);
            const ImageRGBA8 raycast = render(gl, quad, cam, RenderMethod::raycast);
            const double ray_all = diff_images(mesh, raycast).psnr;
            for (bool float_textures : {true, false})
                for (RenderMethod m : {RenderMethod::relief_mapping, RenderMethod::interval_mapping}) {
                    PerPixelSettings s = top;
                    s.common.float_textures = float_textures;
                    const ImageRGBA8 img = render(gl, quad, cam, m, s);
                    const double p = diff_images(mesh, img).psnr;
                    const double ray = diff_images(mesh, restricted_to(raycast, img)).psnr;
                    const char* depth = float_textures ? "float" : "8-bit";
                    if (const char* dump = std::getenv("RTM_PERPIXEL_DUMP")) {
                        const std::string stem = std::string(dump) + "/top_" + name + "_" + v.name + "_";
                        write_rgba8(stem + to_string(m) + "_" + depth + ".png", img);
                        write_rgba8(stem + "micromesh.png", mesh);
                        write_rgba8(stem + "raycast.png", raycast);
                    }
                    std::printf(
                        "%-10s %-8s %-16s %s depth %.2f dB (ray caster %.2f dB over the same pixels, %.2f dB "
                        "over its own) against the micro-polygons\n",
                        name.c_str(), v.name.c_str(), to_string(m).c_str(), depth, p, ray, ray_all);
                    const double bound = float_textures ? ray - 1.0 : name != "step" ? 52.5 : std::min(ray, 62.0) - 1.0;
                    EXPECT_GE(p, bound) << name << " " << v.name << " " << to_string(m) << " " << depth;
                }
        }
    }
}

struct IterationStats {
    double mean = 0;
    int min = 0, max = 0;
    long long pixels = 0;
};

IterationStats iteration_stats(const ImageRGBA8& counts) {
    IterationStats s;
    s.min = 1 << 30;
    double sum = 0;
    for (const Rgba8& p : counts.pixels) {
        if (p.r == 0) continue;  // background (a count is at least 1)
        sum += p.r;
        s.min = std::min(s.min, int(p.r));
        s.max = std::max(s.max, int(p.r));
        ++s.pixels;
    }
    s.mean = s.pixels ? sum / double(s.pixels) : 0.0;
    return s;
}

// Interval mapping's claim (its Figure 5): at the same linear search and the same stopping rule (|surface depth -
// ray depth| < 0.01, at most 10 iterations), its refinement needs fewer iterations than relief mapping's
// bisection. Measured and printed at 5 linear steps (the paper's) and 32; what is asserted is only that the
// counts are well formed (1..10 over exactly the pixels the colour image covers).
TEST(PerPixel, IterationCountsOfIntervalAndReliefMapping) {
    Gl gl;
    for (int linear : {5, 32}) {
        PerPixelSettings s;
        s.relief_mapping.linear_search_steps = linear;
        s.relief_mapping.convergence_threshold = 0.01f;
        s.relief_mapping.max_iterations = 10;
        s.interval_mapping.linear_search_steps = linear;
        s.interval_mapping.convergence_threshold = 0.01f;
        s.interval_mapping.max_iterations = 10;
        for (const std::string& name : known_answer_names()) {
            ReliefQuad quad(to_relief(make_known_answer(name, kReliefSize)));
            for (const CompareView& v : views()) {
                const Camera cam = compare_camera(quad, v, kImage, kImage);
                const ImageRGBA8 truth = render(gl, quad, cam, RenderMethod::raycast);
                for (RenderMethod m : {RenderMethod::relief_mapping, RenderMethod::interval_mapping}) {
                    PerPixelSettings c = s;
                    const ImageRGBA8 colour = render(gl, quad, cam, m, c);
                    c.common.iteration_counts = true;
                    const ImageRGBA8 counts = render(gl, quad, cam, m, c);
                    const IterationStats st = iteration_stats(counts);
                    const DiffResult d = diff_images(truth, colour);
                    std::printf("linear %2d %-10s %-8s %-16s iterations mean %.3f (%d..%d), psnr %.2f dB\n", linear,
                                name.c_str(), v.name.c_str(), to_string(m).c_str(), st.mean, st.min, st.max, d.psnr);
                    EXPECT_GE(st.min, 1);
                    EXPECT_LE(st.max, 10);
                    long long covered_colour = 0;
                    for (const Rgba8& p : colour.pixels) covered_colour += covered(p);
                    EXPECT_EQ(st.pixels, covered_colour) << name << " " << v.name << " " << to_string(m);
                }
            }
        }
    }
}

}  // namespace
}  // namespace rtm

namespace rtm {
namespace {

// Relief mapping with quadric silhouettes on the cylinder patch (bent through 1.2 radians: depth range / radius =
// 0.3), against the truth for that curved surface: the relief displaced radially on the patch, one vertex a texel
// (curved_micromesh), through the same GL path; beside it the original relief mapping on the same mesh (quadric
// coefficients zero). Measured (128x128, llvmpipe): IoU 0.79-0.91 with the quadrics against 0.71-0.88 without
// (gains 0.025 to 0.079); PSNR 16.5-21.1 dB, 0.3-0.6 dB better than without. The colour error is the method's
// model, not the search: it maps depth along the fragment's normal with texture coordinates that do not shrink
// with depth, while radially the ground (depth 1) has 30% less arc length than the top. Bounds: the lowest
// measured less 0.02 IoU and 1.5 dB, and the quadrics must gain coverage at every view, by 0.005 at least (their
// purpose: silhouettes where the ray leaves the surface).
TEST(PerPixel, QuadricSilhouettesAgainstTheCurvedMicroPolygons) {
    Gl gl;
    for (const std::string& name : known_answer_names()) {
        ReliefQuad quad(to_relief(make_known_answer(name, kReliefSize)));
        const PerPixelSettings s;
        const CurvedPatch patch = curved_patch_for(quad.relief(), CurvedShape::cylinder, s.quadric_silhouettes.angle);
        const CurvedTruth curved(quad.relief(), patch);
        for (const CompareView& v : views()) {
            const Camera cam = compare_camera(quad, v, kImage, kImage);
            const ImageRGBA8 truth = curved.draw(gl, cam);
            const ImageRGBA8 img = render(gl, quad, cam, RenderMethod::quadric_silhouettes, s);
            const DiffResult d = diff_images(truth, img);
            PerPixelSettings plain = s;
            plain.quadric_silhouettes.quadric = false;
            const DiffResult dp = diff_images(truth, render(gl, quad, cam, RenderMethod::quadric_silhouettes, plain));
            PerPixelSettings exact = s;
            exact.quadric_silhouettes.exact_distance = true;
            const ImageRGBA8 img_exact = render(gl, quad, cam, RenderMethod::quadric_silhouettes, exact);
            const DiffResult de = diff_images(truth, img_exact), dx = diff_images(img, img_exact);
            std::printf(
                "%-10s %-8s quadric-silhouettes psnr %.2f iou %.4f; without the quadrics psnr %.2f iou %.4f; "
                "exact distance psnr %.2f iou %.4f (against the approximate: psnr %.2f iou %.4f)\n",
                name.c_str(), v.name.c_str(), d.psnr, d.iou, dp.psnr, dp.iou, de.psnr, de.iou, dx.psnr, dx.iou);
            EXPECT_GE(d.psnr, 15.0) << name << " " << v.name;
            EXPECT_GE(d.iou, 0.77) << name << " " << v.name;
            EXPECT_GT(d.iou, dp.iou + 0.005) << name << " " << v.name;
            if (const char* dump = std::getenv("RTM_PERPIXEL_DUMP")) {
                const std::string stem = std::string(dump) + "/quadric_" + name + "_" + v.name + "_";
                write_rgba8(stem + "truth.png", truth);
                write_rgba8(stem + "quadric-silhouettes.png", img);
                write_rgba8(stem + "quadric-silhouettes-exact.png", img_exact);
            }
        }
    }
}

// Quadric silhouettes on a sphere patch (both principal curvatures: the paper's paraboloid, Figure 7 (a)), 32 x 32
// quads, against the curved micro-polygons of the same sphere, with and without the quadrics and with the exact
// distance; and the two truths against each other (the CPU ray caster of the bent relief against the micro-polygons).
// Measured (128x128, llvmpipe): PSNR 15.4 to 18.4 dB, IoU 0.73 to 0.89 with the quadrics, which gain 0.034 to 0.112
// IoU and 0.5 to 0.7 dB over the same search without them at every view (the cylinder's gains: 0.025 to 0.079); the
// exact distance loses coverage as on the cylinder (IoU 0.22 to 0.66). The truths agree: 32.2 to 62.6 dB, IoU
// 0.9975 or more (the step the lowest: its walls lie between texel centres, where the mesh's flat triangles and the
// ray caster's bilinear patches differ). Bounds: the lowest measured less 1.5 dB and 0.02 IoU (the truths: 30.5 dB
// and 0.99); the quadrics ahead of the search without them in PSNR and by 0.02 IoU at every view, and of the exact
// distance in IoU.
TEST(PerPixel, QuadricSilhouettesOnASphere) {
    Gl gl;
    for (const std::string& name : known_answer_names()) {
        ReliefQuad quad(to_relief(make_known_answer(name, kReliefSize)));
        PerPixelSettings s;
        s.quadric_silhouettes.base = CurvedShape::sphere;
        s.quadric_silhouettes.rows = 32;
        PerPixelSettings plain = s, exact = s;
        plain.quadric_silhouettes.quadric = false;
        exact.quadric_silhouettes.exact_distance = true;
        const CurvedPatch patch = curved_patch_for(quad.relief(), CurvedShape::sphere, s.quadric_silhouettes.angle);
        const CurvedTruth curved(quad.relief(), patch);
        for (const CompareView& v : views()) {
            const Camera cam = compare_camera(quad, v, kImage, kImage);
            const ImageRGBA8 truth = curved.draw(gl, cam);
            const ImageRGBA8 img = render(gl, quad, cam, RenderMethod::quadric_silhouettes, s);
            const DiffResult d = diff_images(truth, img);
            const DiffResult dp = diff_images(truth, render(gl, quad, cam, RenderMethod::quadric_silhouettes, plain));
            const DiffResult de = diff_images(truth, render(gl, quad, cam, RenderMethod::quadric_silhouettes, exact));
            const DiffResult dr = diff_images(truth, raycast_curved_relief(quad.relief(), patch, cam));
            std::printf(
                "sphere %-10s %-8s quadrics psnr %.2f iou %.4f; without psnr %.2f iou %.4f; exact distance "
                "psnr %.2f iou %.4f; curved ray caster against the micro-polygons psnr %.2f iou %.4f\n",
                name.c_str(), v.name.c_str(), d.psnr, d.iou, dp.psnr, dp.iou, de.psnr, de.iou, dr.psnr, dr.iou);
            const std::string where = name + " " + v.name;
            EXPECT_GE(d.psnr, 13.8) << where;
            EXPECT_GE(d.iou, 0.71) << where;
            EXPECT_GT(d.psnr, dp.psnr) << where;
            EXPECT_GT(d.iou, dp.iou + 0.02) << where;
            EXPECT_GT(d.iou, de.iou) << where;
            EXPECT_GE(dr.psnr, 30.5) << where;
            EXPECT_GE(dr.iou, 0.99) << where;
            if (const char* dump = std::getenv("RTM_PERPIXEL_DUMP")) {
                const std::string stem = std::string(dump) + "/sphere_" + name + "_" + v.name + "_";
                write_rgba8(stem + "truth.png", truth);
                write_rgba8(stem + "quadric-silhouettes.png", img);
            }
        }
    }
}

// The paper's exact ray-quadric distance (equation 6) against its approximate one (equation 7), on patches bent
// through 1.2, 0.3 and 0.02 radians (nearly flat), each against the curved micro-polygons of its own patch.
// Equation 6 measures along U, perpendicular to the ray: on a flat base that is depth / sin(angle from the normal),
// so a ray counts as deeper than it is and meets the relief too soon (in the frontal view, where the angle is under
// 13 degrees, the whole relief is drawn about flat at the top of its range); on the bent patch it is also shorter
// than the depth where U runs along the curve, so rays that equation 7 takes to the bottom come back out first and
// are discarded as silhouettes (the ground beside the bulge goes missing). Equation 7 is exact on a flat base.
// Measured (128x128, llvmpipe): the approximate distance ahead in PSNR by 1.65 dB at least (1.2 rad, grazing; 2.3 to
// 5.5 dB at its other views, 5 to 19 dB at 0.3 rad, 18 to 42 dB at 0.02 rad) and in IoU at every angle and view;
// nearly flat, the approximate distance is relief mapping on the plane (33.2 to 59.8 dB), the exact one 9.5 to 16.9
// dB. Bounds: the approximate ahead by 1 dB and in IoU everywhere; nearly flat, the approximate >= 31.5 dB and the
// exact <= 18.5 dB (each 1.5 dB from what was measured).
TEST(PerPixel, QuadricExactDistanceAgainstTheApproximate) {
    Gl gl;
    for (double angle : {1.2, 0.3, 0.02})
        for (const std::string& name : known_answer_names()) {
            ReliefQuad quad(to_relief(make_known_answer(name, kReliefSize)));
            PerPixelSettings approx;
            approx.quadric_silhouettes.angle = angle;
            PerPixelSettings exact = approx;
            exact.quadric_silhouettes.exact_distance = true;
            const CurvedTruth curved(quad.relief(), curved_patch_for(quad.relief(), CurvedShape::cylinder, angle));
            for (const CompareView& v : views()) {
                const Camera cam = compare_camera(quad, v, kImage, kImage);
                const ImageRGBA8 truth = curved.draw(gl, cam);
                const DiffResult da = diff_images(truth,
                                                  render(gl, quad, cam, RenderMethod::quadric_silhouettes, approx));
                const DiffResult de = diff_images(truth,
                                                  render(gl, quad, cam, RenderMethod::quadric_silhouettes, exact));
                if (const char* dump = std::getenv("RTM_PERPIXEL_DUMP")) {
                    const std::string stem = std::string(dump) + "/quadric_angle" + std::to_string(angle).substr(0, 4) +
                                             "_" + name + "_" + v.name + "_";
                    write_rgba8(stem + "truth.png", truth);
                    write_rgba8(stem + "approximate.png",
                                render(gl, quad, cam, RenderMethod::quadric_silhouettes, approx));
                    write_rgba8(stem + "exact.png", render(gl, quad, cam, RenderMethod::quadric_silhouettes, exact));
                }
                std::printf("angle %.2f %-10s %-8s approximate psnr %.2f iou %.4f, exact psnr %.2f iou %.4f\n", angle,
                            name.c_str(), v.name.c_str(), da.psnr, da.iou, de.psnr, de.iou);
                const std::string where = name + " " + v.name + " at " + std::to_string(angle) + " rad";
                EXPECT_GT(da.psnr, de.psnr + 1.0) << where;
                EXPECT_GT(da.iou, de.iou) << where;
                if (angle < 0.05) {
                    EXPECT_GE(da.psnr, 31.5) << where;
                    EXPECT_LE(de.psnr, 18.5) << where;
                }
            }
        }
}

}  // namespace
}  // namespace rtm

namespace rtm {
namespace {

// Depth correction (gl_FragDepth at the point found): the step relief seen frontally with a magenta polygon
// through the middle of its slab (displacement 0.125 of 0 .. 0.25) drawn in the same frame. With correction the
// block (displacement 0.25) hides the polygon and the ground (0) is hidden by it: magenta covers the ground, 84% of
// the quad's area (the block is [0.3, 0.7]^2), a little less on screen since the block's top is nearer (measured
// 0.809 for both methods). Without,
// every fragment has its polygon's depth: the top polygon is in front everywhere (no magenta), protruded
// displacement's base polygon behind everywhere (all magenta but the block's side faces). The polygon spans the
// surface (the texel centres).
// Far from the world's origin the curved base mesh and its truth keep their digits: positions are taken relative to
// the eye (the base mesh) and to the relief's origin (the curved micro-polygons) in double before they become floats.
// A stress audit found quadric silhouettes at 24 dB against themselves at 1e6 and a sliver (IoU 0.10) at 1e8.
TEST(PerPixel, QuadricSilhouettesFarFromTheOriginDrawAsNearIt) {
    Gl gl;
    const PerPixelSettings s;
    ImageRGBA8 near_method, near_truth;
    for (double x : {0.0, 1e6, 1e8}) {
        ReliefTexture t = to_relief(make_known_answer("sphere-cap", kReliefSize));
        t.geometry.origin += glm::dvec3(x, 0.5 * x, -x);
        ReliefQuad quad(std::move(t));
        const Camera cam = compare_camera(quad, views()[1], kImage, kImage);
        const ImageRGBA8 img = render(gl, quad, cam, RenderMethod::quadric_silhouettes, s);
        std::vector<MeshVertex> vertices;
        std::vector<uint32_t> indices;
        const glm::dvec3 origin = quad.relief().geometry.origin;
        curved_micromesh(quad.relief(),
                         curved_patch_for(quad.relief(), CurvedShape::cylinder, s.quadric_silhouettes.angle), vertices,
                         indices, origin);
        gl.renderer->begin_frame(cam);
        gl.renderer->draw_mesh(cam, vertices, indices, origin);
        const ImageRGBA8 truth = gl.renderer->read_pixels(kImage, kImage);
        if (x == 0.0) {
            near_method = img;
            near_truth = truth;
            continue;
        }
        const DiffResult dm = diff_images(near_method, img), dt = diff_images(near_truth, truth);
        std::printf("at %g: quadric silhouettes psnr %.2f iou %.4f, curved micro-polygons psnr %.2f iou %.4f\n", x,
                    dm.psnr, dm.iou, dt.psnr, dt.iou);
        // Not bit for bit in general: the matrices round to float differently there (measured: the same images at
        // 1e6; at 1e8 the method the same, the truth 89.4 dB).
        EXPECT_GT(dm.iou, 0.999) << x;
        EXPECT_GT(dm.psnr, 60.0) << x;
        EXPECT_GT(dt.iou, 0.999) << x;
        EXPECT_GT(dt.psnr, 60.0) << x;
    }
}

TEST(PerPixel, DepthCorrectionPutsTheFoundPointInTheDepthBuffer) {
    Gl gl;
    ReliefQuad quad(to_relief(make_step(kReliefSize)));
    const Camera cam = compare_camera(quad, {"frontal", 0, 0, 2.2}, kImage, kImage);
    const glm::u8vec4 magenta(255, 0, 255, 255);
    const float z = 0.125f, lo = 0.5f / kReliefSize, hi = 1.0f - lo;  // over the surface: the texel centres
    const std::vector<MeshVertex> plane = {{{lo, lo, z}, magenta},
                                           {{hi, lo, z}, magenta},
                                           {{hi, hi, z}, magenta},
                                           {{lo, hi, z}, magenta}};
    const std::vector<uint32_t> tris = {0, 1, 2, 0, 2, 3};
    for (RenderMethod m : {RenderMethod::relief_mapping, RenderMethod::protruded_displacement}) {
        for (bool correct : {true, false}) {
            PerPixelSettings s;
            s.common.depth_correction = correct;
            RenderSettings rs;
            rs.method = m;
            rs.perpixel = s;
            StageTimes t;
            (void)render_relief_frame(quad, gl.renderer.get(), cam, rs, t);  // begin_frame, the relief
            gl.renderer->draw_mesh(cam, plane, tris);  // same frame: begin_frame's state, the relief's depths
            const ImageRGBA8 img = gl.renderer->read_pixels(kImage, kImage);
            // What render_relief_frame read back is the relief alone; the second read has the plane on it.
            long long magenta_px = 0, relief_px = 0;
            for (const Rgba8& p : img.pixels) {
                if (p.r == 255 && p.g == 0 && p.b == 255)
                    ++magenta_px;
                else if (covered(p))
                    ++relief_px;
            }
            const double frac = double(magenta_px) / double(magenta_px + relief_px);
            std::printf("%s, depth correction %s: magenta %.3f of the covered pixels\n", to_string(m).c_str(),
                        correct ? "on" : "off", frac);
            if (correct) {
                EXPECT_GT(frac, 0.70) << to_string(m);
                EXPECT_LT(frac, 0.84) << to_string(m);
            } else if (m == RenderMethod::relief_mapping) {
                // Measured 0.121: along the border, where the top polygon's rays leave the footprint before they reach
                // the ground and are discarded, the polygon shows; everywhere else the top polygon is in front.
                EXPECT_LT(frac, 0.15) << to_string(m);
            } else {
                EXPECT_GT(frac, 0.95) << to_string(m);
            }
        }
    }
}

}  // namespace
}  // namespace rtm

namespace rtm {
namespace {

// Shading and relief mapping's self-shadowing on the step seen frontally, the light from +x at 26.6 degrees above
// the plane (direction (1, 0, 0.5)): the lit ground and the block's top get ambient + (1 - ambient) N.L = 0.25 +
// 0.75 * 0.447 = 0.585 of the unlit colour; the block's shadow (0.25 / 0.5 = 0.5 long in x, cut off by the quad's
// border at x = 0: [0, 0.3] x [0.3, 0.7], 12% of the quad) only the ambient 0.25. Measured fractions of the
// covered pixels darkened below 0.4 of the unlit colour: 0.132 with shadows, 0.021 without (the wall facing away
// from the light, border pixels); 0.857 and 0.968 lit as expected. Bounds leave room for rasterization.
// Protruded displacement mapping's texture for steep slopes (its section 4) on the step: the relief's colour encodes
// its texture coordinates (red s, green t, blue 0), the steep texture is plain magenta. A pixel turned magenta was
// found steep; the same pixel without the steep texture tells where its point lies (the search is the same). Steep
// pixels must lie on the block's walls, which span one texel between texel centres at the block's edges, and most
// points found on the walls must be steep. The test reads the height map at the linear search's last sample
// outside, so a wall point whose sample fell on the wall itself, or near the wall's bottom or top, is missed: the
// paper's detection, patchy on the wall. Measured (128x128, llvmpipe, threshold 0.1, 32 linear steps): no steep pixel
// in the frontal view (no wall seen), none more than 1.5 texels from a wall, 50% (oblique) and 68% (grazing) of the
// points found on the walls steep. Bounds: none off the walls; 40% on them at the oblique and grazing views; with
// the threshold at 1 (no depth difference exceeds it) none at all.
TEST(PerPixel, ProtrudedDisplacementSteepSlopesTakeTheWallTexture) {
    Gl gl;
    ProceduralRelief pr = make_step(kReliefSize);
    const int n = kReliefSize;
    for (int row = 0; row < n; ++row)
        for (int i = 0; i < n; ++i)
            pr.color.at(i, row) = Rgba8{uint8_t(std::lround(255.0 * (i + 0.5) / n)),
                                        uint8_t(std::lround(255.0 * (n - 1 - row + 0.5) / n)), 0, 255};
    ReliefQuad quad(to_relief(pr));
    quad.perpixel().set_steep_texture(ImageRGBA8(1, 1, Rgba8{255, 0, 255, 255}));
    // The walls' bands in texture coordinates: between the texel centres on either side of the block's edges.
    const ReliefTexture& t = quad.relief();
    std::vector<double> edges;  // in texels, where the displacement changes between neighbouring centres
    for (int i = 0; i + 1 < n; ++i)
        if (t.displ(i, n / 2) != t.displ(i + 1, n / 2)) edges.push_back(i + 1.0);  // between centres i+0.5, i+1.5
    ASSERT_EQ(edges.size(), 2u);
    auto from_edge = [&](double texels) {  // distance in texels to the nearest wall band's middle
        double d = 1e9;
        for (double e : edges) d = std::min(d, std::abs(texels - e));
        return d;
    };
    // Distance in texels from (ts, tt) to the nearest wall: to the block's outline (the band's middles), a square.
    auto from_wall = [&](double ts, double tt) {
        const double lo = edges[0], hi = edges[1];
        const double ds = std::max({lo - ts, ts - hi, 0.0}), dt = std::max({lo - tt, tt - hi, 0.0});
        if (ds > 0 || dt > 0) return std::hypot(ds, dt);  // outside the block
        return std::min(from_edge(ts), from_edge(tt));    // inside: to the nearest side
    };
    for (const CompareView& v : views()) {
        const Camera cam = compare_camera(quad, v, kImage, kImage);
        PerPixelSettings plain;
        const ImageRGBA8 where = render(gl, quad, cam, RenderMethod::protruded_displacement, plain);
        PerPixelSettings steep = plain;
        steep.protruded_displacement.steep_texture = true;
        const ImageRGBA8 img = render(gl, quad, cam, RenderMethod::protruded_displacement, steep);
        long long on_wall = 0, on_wall_steep = 0, steep_n = 0, steep_off_wall = 0, covered_n = 0;
        for (size_t k = 0; k < img.pixels.size(); ++k) {
            const Rgba8& w = where.pixels[k];
            if (!covered(w)) continue;
            ++covered_n;
            // The point's texel coordinates (8-bit: a quarter texel at 64 texels).
            const double ts = w.r / 255.0 * n, tt = n - w.g / 255.0 * n;  // tt: rows from the top
            const double d = from_wall(ts, tt);
            const bool wall = d < 0.5;
            const bool is_steep = img.pixels[k].b > 128;
            on_wall += wall;
            on_wall_steep += wall && is_steep;
            steep_n += is_steep;
            if (is_steep && d > 1.5) ++steep_off_wall;
        }
        if (const char* dump = std::getenv("RTM_PERPIXEL_DUMP")) {
            write_rgba8(std::string(dump) + "/steep_" + v.name + "_plain.png", where);
            write_rgba8(std::string(dump) + "/steep_" + v.name + "_steep.png", img);
        }
        std::printf(
            "%-8s steep pixels %lld of %lld covered; on the walls %lld, of which steep %lld; steep more than "
            "1.5 texels from a wall %lld\n",
            v.name.c_str(), steep_n, covered_n, on_wall, on_wall_steep, steep_off_wall);
        EXPECT_EQ(steep_off_wall, 0) << v.name;
        if (v.name != "frontal") {
            ASSERT_GT(on_wall, 100) << v.name;  // the walls are in view
            EXPECT_GE(double(on_wall_steep) / double(on_wall), 0.4) << v.name;
        }
        PerPixelSettings never = steep;
        never.protruded_displacement.steep_threshold = 1.0f;
        const ImageRGBA8 none = render(gl, quad, cam, RenderMethod::protruded_displacement, never);
        EXPECT_EQ(none.pixels, where.pixels) << v.name;
    }
}

TEST(PerPixel, ShadingAndSelfShadowing) {
    Gl gl;
    ReliefQuad quad(to_relief(make_step(kReliefSize)));
    const Camera cam = compare_camera(quad, {"frontal", 0, 0, 2.2}, kImage, kImage);
    PerPixelSettings unlit;
    const ImageRGBA8 base = render(gl, quad, cam, RenderMethod::relief_mapping, unlit);
    for (bool shadows : {false, true}) {
        PerPixelSettings s;
        s.common.shading = true;
        s.common.self_shadowing = shadows;
        s.common.light_dir = {1.0, 0.0, 0.5};
        const ImageRGBA8 img = render(gl, quad, cam, RenderMethod::relief_mapping, s);
        long long dark = 0, lit = 0, n = 0;
        for (size_t i = 0; i < img.pixels.size(); ++i) {
            const Rgba8& b = base.pixels[i];
            const int sum_b = b.r + b.g + b.b;
            if (!covered(b) || sum_b < 150) continue;  // ratios need colour to be measured on
            const Rgba8& p = img.pixels[i];
            const double ratio = double(p.r + p.g + p.b) / sum_b;
            ++n;
            if (ratio < 0.4) ++dark;
            if (std::abs(ratio - 0.585) < 0.03) ++lit;
        }
        const double fd = double(dark) / n, fl = double(lit) / n;
        std::printf("self-shadowing %s: %.3f of the pixels in shadow, %.3f lit at N.L = 0.447\n",
                    shadows ? "on" : "off", fd, fl);
        if (shadows) {
            EXPECT_GT(fd, 0.08);
            EXPECT_LT(fd, 0.15);
        } else {
            EXPECT_LT(fd, 0.03);
        }
        EXPECT_GT(fl, 0.75);  // the flat parts in the light: the right darkening, within 8-bit normal rounding
    }
}

// Quadric silhouettes' shading and self-shadowing on the curved bases: the share of the pixels in shadow (the colour
// at the ambient level: lit = 0, cast or attached) against the CPU truth of the same bent relief
// (curved_relief_shadows: a ray from the point seen towards the light). The method's point and the truth's differ
// (the model error of the tables above), so the shares are compared, not pixels. The light is not parallel to any
// wall of the step (a wall at N.L = 0 is lit or not by rounding). Measured (128x128, llvmpipe, light (1, 0.7, 0.6),
// ambient 0.25, frontal and oblique views, both bases): with the shadow test the share within 0.061 of the truth's
// (0.007 to 0.407); without it, the attached shadows alone (N.L <= 0), 0.094 to 0.179 under the truth's where that
// is over 0.1. Bounds: within 0.075 with the test; without it 0.07 under the truth's where that is over 0.1; the
// test only darkens.
TEST(PerPixel, QuadricSilhouettesShadingAndShadows) {
    Gl gl;
    const glm::dvec3 light(1.0, 0.7, 0.6);
    for (CurvedShape shape : {CurvedShape::cylinder, CurvedShape::sphere})
        for (const std::string& name : known_answer_names()) {
            ReliefQuad quad(to_relief(make_known_answer(name, kReliefSize)));
            PerPixelSettings unlit;
            unlit.quadric_silhouettes.base = shape;
            unlit.quadric_silhouettes.rows = shape == CurvedShape::sphere ? 32 : 4;
            const CurvedPatch patch = curved_patch_for(quad.relief(), shape, unlit.quadric_silhouettes.angle);
            for (const CompareView& v : views()) {
                if (v.name == "grazing") continue;
                const Camera cam = compare_camera(quad, v, kImage, kImage);
                const ImageRGBA8 base = render(gl, quad, cam, RenderMethod::quadric_silhouettes, unlit);
                const std::vector<uint8_t> truth = curved_relief_shadows(quad.relief(), patch, cam, light);
                long long truth_n = 0, truth_dark = 0;
                for (uint8_t m : truth) {
                    truth_n += m != 0;
                    truth_dark += m == 2;
                }
                double share_off = 0;
                for (bool shadows : {false, true}) {
                    PerPixelSettings s = unlit;
                    s.common.shading = true;
                    s.common.self_shadowing = shadows;
                    s.common.light_dir = light;
                    const ImageRGBA8 img = render(gl, quad, cam, RenderMethod::quadric_silhouettes, s);
                    long long n = 0, dark = 0;
                    for (size_t k = 0; k < img.pixels.size(); ++k) {
                        const Rgba8& b = base.pixels[k];
                        const int sum_b = b.r + b.g + b.b;
                        if (!covered(b) || sum_b < 150) continue;  // ratios need colour to be measured on
                        const Rgba8& px = img.pixels[k];
                        ++n;
                        dark += double(px.r + px.g + px.b) / sum_b < 0.27;  // ambient 0.25, 8-bit rounding
                    }
                    if (const char* dump = std::getenv("RTM_PERPIXEL_DUMP")) {
                        const std::string stem = std::string(dump) + "/shadow_" + to_string(shape) + "_" + name + "_" +
                                                 v.name + "_";
                        ImageRGBA8 mask(kImage, kImage, Rgba8{0, 0, 0, 255});
                        for (size_t k = 0; k < truth.size(); ++k)
                            if (truth[k])
                                mask.pixels[k] = truth[k] == 2 ? Rgba8{60, 60, 60, 255} : Rgba8{220, 220, 220, 255};
                        write_rgba8(stem + "truth.png", mask);
                        write_rgba8(stem + (shadows ? "shadows.png" : "shaded.png"), img);
                    }
                    const double share = double(dark) / n, want = double(truth_dark) / truth_n;
                    std::printf(
                        "%-8s %-10s %-8s shadows %-3s: %.3f of the pixels at the ambient level; the truth %.3f\n",
                        to_string(shape).c_str(), name.c_str(), v.name.c_str(), shadows ? "on" : "off", share, want);
                    const std::string where = to_string(shape) + " " + name + " " + v.name;
                    if (shadows) {
                        EXPECT_NEAR(share, want, 0.075) << where;
                        EXPECT_GE(share, share_off) << where;
                    } else {
                        share_off = share;
                        if (want > 0.1) {
                            EXPECT_LT(share, want - 0.07) << where;
                        }
                    }
                }
            }
        }
}

}  // namespace
}  // namespace rtm
