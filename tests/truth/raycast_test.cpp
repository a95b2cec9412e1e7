// The exact ray caster (truth/raycast.h): analytic intersections, robustness, reference agreement, threads.
//
// Tolerances. Where the intersection is known in closed form the hit distance and (u, v) are checked to 1e-9
// (relative for t, texel units for u, v) through ReliefRaycaster, which reports doubles; the per-pixel depth
// image is float, so it is checked to float precision (2e-7 relative). Colours are rounded by the caster, so they
// must lie within 0.5 (+1e-6 for the rounding of the hit position) of the unrounded analytic bilinear colour.
#include "truth/raycast.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <limits>
#include <random>
#include <thread>

#include "ground_truth_util.h"

namespace rtm {
namespace {

using truth_test::from_uvd;
using truth_test::to_uvd;

const auto kNoHoles = [](int, int) { return false; };

// A camera at `eye` looking at `at`, with an up vector that is not parallel to the view.
Camera look(const glm::dvec3& eye, const glm::dvec3& at, int size, double fov = 45.0) {
    Camera c;
    c.eye = eye;
    c.look_at = at;
    const glm::dvec3 fwd = glm::normalize(at - eye);
    c.up = std::abs(fwd.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    c.fov_deg = fov;
    c.width = c.height = size;
    return c;
}

glm::dvec3 relief_centre(const ReliefTexture& t, double d) {
    const ReliefGeometry& g = t.geometry;
    return g.origin + g.a * (t.width * 0.5) + g.b * (t.height * 0.5) + g.f() * d;
}

// Bumpy relief (smooth, with a few cliffs) for robustness and reference tests.
ReliefTexture bumpy(int w, int h, const ReliefGeometry& g, double amp, bool holes) {
    return truth_test::make_relief_fn(
        w, h, g,
        [&](int x, int r) {
            double d = amp * (std::sin(0.7 * x) * std::cos(0.9 * r) + 0.3 * std::sin(2.1 * x + 1.3 * r));
            if ((x / 3 + r / 4) % 5 == 0) d += amp;  // steps
            return d;
        },
        truth_test::hash_color, [&](int x, int r) { return holes && (x * 7 + r * 3) % 11 == 0; });
}

TEST(Raycast, FlatReliefMatchesThePlaneIntersection) {
    const uint64_t seed = truth_test::seed(71001);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    int hits = 0, misses = 0;
    for (int iter = 0; iter < 12; ++iter) {
        const ReliefGeometry g = truth_test::random_geometry(rng);
        const int w = 2 + int(rng() % 14), h = 2 + int(rng() % 14);
        const double d0 = double(float(U(rng) * 0.05));  // displacement is stored as float
        const ReliefTexture t = truth_test::make_relief_fn(
            w, h, g, [&](int, int) { return d0; }, truth_test::hash_color, kNoHoles);
        const double extent = glm::length(g.a * double(w)) + glm::length(g.b * double(h));
        const glm::dvec3 c = relief_centre(t, d0);
        // Views from the front (+f) and, for half of them, from behind: the caster is two-sided.
        const double side = iter % 2 ? -1.0 : 1.0;
        const glm::dvec3 eye = c + g.f() * (side * extent * (1.0 + std::abs(U(rng)))) + g.a * (U(rng) * w * 0.5) +
                               g.b * (U(rng) * h * 0.5);
        const Camera cam = look(eye, c, 40);
        ImageF depth;
        const ImageRGBA8 img = raycast_relief(t, cam, {}, &depth);
        const ReliefRaycaster caster(t);
        for (int py = 0; py < cam.height; ++py)
            for (int px = 0; px < cam.width; ++px) {
                glm::dvec3 o, dir;
                cam.ray(px, py, o, dir);
                // Analytic: origin + f*d0 + a*u + b*v = o + t*dir.
                const glm::dmat3 m(g.a, g.b, -dir);
                const glm::dvec3 sol = glm::inverse(m) * (o - g.origin - g.f() * d0);
                const double u = sol.x, v = sol.y, tt = sol.z;
                const double margin = 1e-6;
                const bool inside = tt > 0 && u > 0.5 + margin && u < w - 0.5 - margin && v > 0.5 + margin &&
                                    v < h - 0.5 - margin;
                const bool outside = tt < 0 || u < 0.5 - margin || u > w - 0.5 + margin || v < 0.5 - margin ||
                                     v > h - 0.5 + margin;
                const Rgba8 p = img.at(px, py);
                const ReliefRayHit hit = caster.cast(o, dir);
                SCOPED_TRACE("pixel " + std::to_string(px) + "," + std::to_string(py) + " " + t.to_string());
                if (inside) {
                    ++hits;
                    ASSERT_TRUE(hit.hit);
                    EXPECT_NEAR(hit.t, tt, 1e-9 * tt);
                    EXPECT_NEAR(hit.u, u, 1e-9);
                    EXPECT_NEAR(hit.v, v, 1e-9);
                    EXPECT_NEAR(depth.at(px, py), tt, 2e-7 * tt);
                    const uint8_t ch[3] = {p.r, p.g, p.b};
                    for (int k = 0; k < 3; ++k)
                        ASSERT_NEAR(double(ch[k]), truth_test::surface_color(t, u, v, k), 0.5 + 1e-6)
                            << "channel " << k;
                    EXPECT_EQ(p.a, 255);
                    EXPECT_EQ(p, hit.color);
                } else if (outside) {
                    ++misses;
                    ASSERT_FALSE(hit.hit);
                    ASSERT_EQ(p, (Rgba8{0, 0, 0, 255}));
                    ASSERT_TRUE(std::isinf(depth.at(px, py)));
                }
            }
    }
    EXPECT_GT(hits, 500);  // the views do show the relief (12 views of 40x40 pixels)
    EXPECT_GT(misses, 500);
}

TEST(Raycast, ImageIsNotMirrored) {
    // 2x2 relief, image rows top to bottom: red green / blue white. Seen from +f with b up, the picture looks
    // like the image file (docs/FORMATS.md). The view shows exactly the rectangle of texel centres.
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.01, 0};
    const Rgba8 cols[4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {255, 255, 255, 255}};
    const ReliefTexture t = truth_test::make_relief_fn(
        2, 2, g, [](int, int) { return 0.0; }, [&](int x, int r) { return cols[r * 2 + x]; }, kNoHoles);
    Camera cam = look({0.01, 0.01, 0.005}, {0.01, 0.01, 0}, 101, 90.0);
    cam.up = {0, 1, 0};
    const ImageRGBA8 img = raycast_relief(t, cam);
    const auto near = [](Rgba8 a, Rgba8 b) {
        return std::abs(a.r - b.r) <= 4 && std::abs(a.g - b.g) <= 4 && std::abs(a.b - b.b) <= 4;
    };
    EXPECT_TRUE(near(img.at(0, 0), cols[0])) << to_string(img.at(0, 0));
    EXPECT_TRUE(near(img.at(100, 0), cols[1])) << to_string(img.at(100, 0));
    EXPECT_TRUE(near(img.at(0, 100), cols[2])) << to_string(img.at(0, 100));
    EXPECT_TRUE(near(img.at(100, 100), cols[3])) << to_string(img.at(100, 100));
}

TEST(Raycast, SingleRaisedTexelTent) {
    // 3x3, centre texel raised to H: along v = 1.5 (the centre row, a border between cells) the surface is the
    // tent d = H*(1 - |u - 1.5|). A ray in that plane, descending with slope m per texel of u from (u0, d0), meets
    // the rising side d = H*(u - 0.5) at u* = (d0 + m*u0 + H/2) / (H + m).
    std::mt19937_64 rng(truth_test::seed(71002));
    for (int iter = 0; iter < 10; ++iter) {
        const ReliefGeometry g = truth_test::random_geometry(rng);
        const double H = 0.046875;  // exact in float (displacement is stored as float)
        const ReliefTexture t = truth_test::make_relief_fn(
            3, 3, g, [&](int x, int r) { return x == 1 && r == 1 ? H : 0.0; }, truth_test::hash_color, kNoHoles);
        const double u0 = 0.0, d0 = 2 * H, m = 0.05 + 0.04 * iter / 10.0;
        const double us = (d0 + m * u0 + 0.5 * H) / (H + m);
        ASSERT_GT(us, 0.5);
        ASSERT_LT(us, 1.5);
        const glm::dvec3 eye = from_uvd(g, {u0, 1.5, d0});
        const glm::dvec3 dir = glm::normalize(from_uvd(g, {u0 + 1, 1.5, d0 - m}) - eye);
        const glm::dvec3 expected = from_uvd(g, {us, 1.5, H * (us - 0.5)});
        const double tt = glm::length(expected - eye);
        const ReliefRaycaster caster(t);
        for (bool brute : {false, true}) {
            const ReliefRayHit hit = caster.cast(eye, dir, brute);
            ASSERT_TRUE(hit.hit) << "brute " << brute;
            EXPECT_NEAR(hit.t, tt, 1e-9 * tt);
            EXPECT_NEAR(hit.u, us, 1e-9);
            EXPECT_NEAR(hit.v, 1.5, 1e-9);
        }
    }
}

TEST(Raycast, RaisedCornerIsAQuadratic) {
    // 2x2, one cell; texel (1, row 0) -- (u, v) = (1.5, 1.5) -- raised to H: d = H*s*r. Along the diagonal
    // s = r = l with d = d0 - m*l the hit solves H*l^2 + m*l - d0 = 0.
    std::mt19937_64 rng(truth_test::seed(71003));
    for (int iter = 0; iter < 10; ++iter) {
        const ReliefGeometry g = truth_test::random_geometry(rng);
        const double H = 0.0390625, d0 = 0.03, m = 0.01 + 0.003 * iter;  // H exact in float
        const ReliefTexture t = truth_test::make_relief_fn(
            2, 2, g, [&](int x, int r) { return x == 1 && r == 0 ? H : 0.0; }, truth_test::hash_color, kNoHoles);
        const double l = (-m + std::sqrt(m * m + 4 * H * d0)) / (2 * H);
        ASSERT_GT(l, 0.0);
        ASSERT_LT(l, 1.0);
        const glm::dvec3 eye = from_uvd(g, {0.5 - 0.5, 0.5 - 0.5, d0 + 0.5 * m});  // l = -0.5, outside the cell
        const glm::dvec3 dir = glm::normalize(from_uvd(g, {1.5, 1.5, d0 - m}) - eye);
        const glm::dvec3 expected = from_uvd(g, {0.5 + l, 0.5 + l, H * l * l});
        const double tt = glm::length(expected - eye);
        const ReliefRaycaster caster(t);
        const ReliefRayHit hit = caster.cast(eye, dir);
        ASSERT_TRUE(hit.hit);
        EXPECT_NEAR(hit.t, tt, 1e-9 * tt);
        EXPECT_NEAR(hit.u, 0.5 + l, 1e-9);
        EXPECT_NEAR(hit.v, 0.5 + l, 1e-9);
        const uint8_t ch[3] = {hit.color.r, hit.color.g, hit.color.b};
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(double(ch[k]), truth_test::surface_color(t, 0.5 + l, 0.5 + l, k), 0.5 + 1e-6);
    }
}

TEST(Raycast, RampIsAPlane) {
    // Displacement linear in u: the bilinear surface is the plane d = c + k*(u - 0.5) exactly.
    std::mt19937_64 rng(truth_test::seed(71004));
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    const ReliefGeometry g = truth_test::random_geometry(rng);
    const int w = 9, h = 5;
    const double c = 0.0078125, k = 0.00390625;  // powers of two: c + k*x is exact in float
    const ReliefTexture t = truth_test::make_relief_fn(
        w, h, g, [&](int x, int) { return c + k * x; }, truth_test::hash_color, kNoHoles);
    const ReliefRaycaster caster(t);
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 eye = from_uvd(g, {U(rng) * 12, U(rng) * 8, 0.1 + 0.1 * std::abs(U(rng))});
        const glm::dvec3 target = from_uvd(g, {0.5 + (w - 1) * std::abs(U(rng)), 0.5 + (h - 1) * std::abs(U(rng)), 0});
        const glm::dvec3 dir = glm::normalize(target - eye);
        // Plane in (u, v, d): d - k*u = c - k/2. Along the ray q(t) = q0 + t*qd (linear in t).
        const glm::dvec3 q0 = to_uvd(g, eye), qd = to_uvd(g, eye + dir) - q0;
        const double tt = (c - 0.5 * k - (q0.z - k * q0.x)) / (qd.z - k * qd.x);
        const glm::dvec3 q = q0 + tt * qd;
        if (!(tt > 0 && q.x > 0.5 + 1e-6 && q.x < w - 0.5 - 1e-6 && q.y > 0.5 + 1e-6 && q.y < h - 0.5 - 1e-6)) continue;
        ++hits;
        const ReliefRayHit hit = caster.cast(eye, dir);
        ASSERT_TRUE(hit.hit) << i;
        EXPECT_NEAR(hit.t, tt, 1e-9 * tt) << i;
        EXPECT_NEAR(hit.u, q.x, 1e-9) << i;
        EXPECT_NEAR(hit.v, q.y, 1e-9) << i;
    }
    EXPECT_GT(hits, 100);
}

TEST(Raycast, CellsTouchingAnEmptyTexelAreHoles) {
    // 4x3 flat relief, texel (0, row 0) empty: cell (u, v) in [0.5,1.5] x [1.5,2.5] is a hole, the others not.
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.02, 0};
    const ReliefTexture t = truth_test::make_relief_fn(
        4, 3, g, [](int, int) { return 0.0; }, truth_test::hash_color, [](int x, int r) { return x == 0 && r == 0; });
    const ReliefRaycaster caster(t);
    const auto down_at = [&](double u, double v) { return caster.cast(from_uvd(g, {u, v, 1.0}), -g.f()); };
    EXPECT_FALSE(down_at(1.0, 2.0).hit);
    EXPECT_TRUE(down_at(2.0, 2.0).hit);
    EXPECT_TRUE(down_at(1.0, 1.0).hit);
    EXPECT_TRUE(down_at(3.0, 2.0).hit);
    EXPECT_NEAR(down_at(3.0, 2.0).t, 1.0, 1e-12);
}

// Checks a reported hit: finite, inside the rectangle, on the surface, and the same as the reference.
void check_hit(const ReliefTexture& t, const ReliefRaycaster& caster, const glm::dvec3& o, const glm::dvec3& dir,
               const std::string& what) {
    SCOPED_TRACE(what);
    const ReliefRayHit hit = caster.cast(o, dir);
    const ReliefRayHit ref = caster.cast(o, dir, true);
    ASSERT_EQ(hit.hit, ref.hit);
    if (!hit.hit) {
        EXPECT_TRUE(std::isinf(hit.t));
        return;
    }
    ASSERT_TRUE(std::isfinite(hit.t) && std::isfinite(hit.u) && std::isfinite(hit.v));
    EXPECT_GE(hit.t, 0.0);
    EXPECT_NEAR(hit.t, ref.t, 1e-9 * std::max(1.0, ref.t));
    EXPECT_EQ(hit.color, ref.color);
    EXPECT_GE(hit.u, 0.5);
    EXPECT_LE(hit.u, t.width - 0.5);
    EXPECT_GE(hit.v, 0.5);
    EXPECT_LE(hit.v, t.height - 0.5);
    const glm::dvec3 q = to_uvd(t.geometry, o + hit.t * dir);
    EXPECT_NEAR(q.x, hit.u, 1e-7);
    EXPECT_NEAR(q.y, hit.v, 1e-7);
    EXPECT_NEAR(q.z, truth_test::surface_height(t, hit.u, hit.v), 1e-9);
}

TEST(Raycast, GrazingRaysAndRaysFromInsideTheSlab) {
    const uint64_t seed = truth_test::seed(71005);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0), P(0.0, 1.0);
    int grazing_hits = 0, inside_hits = 0;
    for (int iter = 0; iter < 6; ++iter) {
        const ReliefGeometry g = truth_test::random_geometry(rng);
        const int w = 8 + int(rng() % 40), h = 8 + int(rng() % 40);
        const double amp = 0.01;
        const ReliefTexture t = bumpy(w, h, g, amp, false);
        const ReliefRaycaster caster(t);
        const glm::dvec3 f = g.f();
        const glm::dvec3 ea = glm::normalize(g.a), eb = glm::normalize(g.b - glm::dot(g.b, ea) * ea);
        for (int i = 0; i < 150; ++i) {
            // Grazing: 0.1 degrees above (or below) the base plane, from outside, through a point of the slab.
            const glm::dvec3 target = from_uvd(g, {0.5 + (w - 1) * P(rng), 0.5 + (h - 1) * P(rng), amp * U(rng)});
            const double az = 2 * M_PI * P(rng), el = glm::radians(i % 2 ? 0.1 : -0.1);
            const glm::dvec3 in_plane = std::cos(az) * ea + std::sin(az) * eb;
            const glm::dvec3 dir = glm::normalize(std::cos(el) * in_plane - std::sin(el) * f);
            const double back = 2.0 * (glm::length(g.a) * w + glm::length(g.b) * h);
            check_hit(t, caster, target - back * dir, dir, "grazing " + std::to_string(i));
            grazing_hits += caster.cast(target - back * dir, dir).hit;
            // Eye inside the slab (above or below the surface), any direction.
            const glm::dvec3 eye = from_uvd(g, {0.5 + (w - 1) * P(rng), 0.5 + (h - 1) * P(rng), 1.5 * amp * U(rng)});
            const glm::dvec3 d2 = glm::normalize(glm::dvec3(U(rng), U(rng), U(rng)));
            check_hit(t, caster, eye, d2, "inside " + std::to_string(i));
            inside_hits += caster.cast(eye, d2).hit;
            // Exactly parallel to the base plane, and straight along -f and +f.
            check_hit(t, caster, eye, in_plane, "parallel " + std::to_string(i));
            check_hit(t, caster, eye, f, "+f " + std::to_string(i));
            check_hit(t, caster, eye, -f, "-f " + std::to_string(i));
        }
        // Whole images from inside the slab: no NaN in the depth (infinity or a finite distance).
        const Camera cam = look(from_uvd(g, {w * 0.3, h * 0.4, 0.5 * amp}), relief_centre(t, 0), 24, 100.0);
        ImageF depth;
        raycast_relief(t, cam, {}, &depth);
        for (float d : depth.pixels) ASSERT_FALSE(std::isnan(d));
    }
    EXPECT_GT(grazing_hits, 100);
    EXPECT_GT(inside_hits, 100);
}

TEST(Raycast, MatchesTheBruteForceReference) {
    // The quadtree walk against every-cell intersection, on random reliefs with holes and random views.
    const uint64_t seed = truth_test::seed(71006);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int iter = 0; iter < 10; ++iter) {
        const ReliefGeometry g = truth_test::random_geometry(rng);
        const int w = 2 + int(rng() % 20), h = 2 + int(rng() % 20);
        const ReliefTexture t = bumpy(w, h, g, 0.02, iter % 2 == 0);
        const double extent = glm::length(g.a * double(w)) + glm::length(g.b * double(h));
        const glm::dvec3 c = relief_centre(t, 0);
        const glm::dvec3 eye = c + glm::dvec3(U(rng), U(rng), U(rng)) * extent + g.f() * (0.5 * extent);
        const Camera cam = look(eye, c, 28, 60.0);
        ImageF d1, d2;
        RaycastOptions fast, brute;
        brute.brute_force = true;
        const ImageRGBA8 a = raycast_relief(t, cam, fast, &d1), b = raycast_relief(t, cam, brute, &d2);
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            ASSERT_EQ(a.pixels[i], b.pixels[i]) << "iteration " << iter << " pixel " << i << " " << t.to_string();
            ASSERT_EQ(std::isinf(d1.pixels[i]), std::isinf(d2.pixels[i]));
            if (!std::isinf(d1.pixels[i])) {
                ASSERT_NEAR(d1.pixels[i], d2.pixels[i], 1e-6 * d2.pixels[i]);
            }
        }
    }
}

TEST(Raycast, DegenerateSizesHaveNoSurface) {
    // The surface runs through the texel centres: a 1xN or Nx1 relief is a line, a 1x1 relief a point.
    for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{7, 1}}) {
        const ReliefTexture t = truth_test::make_relief_fn(
            w, h, ReliefGeometry{}, [](int x, int) { return 0.1 * x; }, truth_test::hash_color, kNoHoles);
        const ReliefRaycaster caster(t);
        EXPECT_FALSE(caster.has_surface());
        ImageF depth;
        const ImageRGBA8 img = raycast_relief(t, look({0.5, 0.5, 5}, {0.5, 0.5, 0}, 16), {}, &depth);
        for (size_t i = 0; i < img.pixels.size(); ++i) {
            ASSERT_EQ(img.pixels[i], (Rgba8{0, 0, 0, 255}));
            ASSERT_TRUE(std::isinf(depth.pixels[i]));
        }
    }
    // 2x2 is one cell: hit.
    const ReliefTexture t = truth_test::make_relief_fn(
        2, 2, ReliefGeometry{}, [](int, int) { return 0.0; }, truth_test::hash_color, kNoHoles);
    EXPECT_TRUE(ReliefRaycaster(t).cast({1, 1, 5}, {0, 0, -1}).hit);
    // All texels empty: nothing.
    const ReliefTexture e = truth_test::make_relief_fn(
        5, 5, ReliefGeometry{}, [](int, int) { return 0.0; }, truth_test::hash_color, [](int, int) { return true; });
    EXPECT_FALSE(ReliefRaycaster(e).has_surface());
    EXPECT_FALSE(ReliefRaycaster(e).cast({2, 2, 5}, {0, 0, -1}).hit);
    Camera bad = look({1, 1, 5}, {1, 1, 0}, 8);
    bad.width = 0;
    EXPECT_THROW(raycast_relief(t, bad), std::invalid_argument);
    // Degenerate rays are misses, not NaN.
    const ReliefRaycaster c(t);
    EXPECT_FALSE(c.cast({1, 1, 5}, {0, 0, 0}).hit);
    EXPECT_FALSE(c.cast({1, 1, 5}, {0, 0, std::nan("")}).hit);
    EXPECT_FALSE(c.cast({1, std::numeric_limits<double>::infinity(), 5}, {0, 0, -1}).hit);
}

TEST(Raycast, SameOutputForOneAndTwoThreadsAndProgressFromTheCaller) {
    std::mt19937_64 rng(truth_test::seed(71007));
    const ReliefGeometry g = truth_test::random_geometry(rng);
    const ReliefTexture t = bumpy(48, 40, g, 0.03, true);
    const glm::dvec3 c = relief_centre(t, 0);
    const double extent = glm::length(g.a * 48.0) + glm::length(g.b * 40.0);
    const Camera cam = look(c + g.f() * (0.7 * extent) + g.a * 10.0, c, 80);
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<double> fractions;
    bool other_thread = false;
    RaycastOptions o1, o2;
    o1.threads = 1;
    o2.threads = 2;
    o2.progress = [&](double f) {
        fractions.push_back(f);
        other_thread |= std::this_thread::get_id() != caller;
    };
    ImageF d1, d2;
    const ImageRGBA8 a = raycast_relief(t, cam, o1, &d1);
    const ImageRGBA8 b = raycast_relief(t, cam, o2, &d2);
    EXPECT_EQ(a, b);
    EXPECT_EQ(d1, d2);
    EXPECT_FALSE(other_thread);
    ASSERT_FALSE(fractions.empty());
    EXPECT_EQ(fractions.back(), 1.0);
    for (size_t i = 1; i < fractions.size(); ++i) EXPECT_GE(fractions[i], fractions[i - 1]);
    long long covered = 0;
    for (const Rgba8& p : a.pixels) covered += !(p == Rgba8{0, 0, 0, 255});
    EXPECT_GT(covered, 200);  // not vacuous: the view shows the relief (a parallelogram with holes)
}

}  // namespace
}  // namespace rtm
