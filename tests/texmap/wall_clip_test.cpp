// Side polygons less the quad's viewing cone (texmap/wall_clip.h): exact on a hand-made case, and a sweep over
// random quads, eyes and walls (seed printed; RTM_SEED overrides it) checking that the pieces keep every point
// whose eye ray misses the quad and drop every point whose ray meets it well inside. The cut to the margins'
// content likewise: margin_content exact on a hand-made texture and, over random ones, holding every plane point
// that bilinear filtering gives any alpha; inside_plane_rects keeping every wall point whose ray meets a rectangle
// and dropping the ones whose ray meets none.
#include "texmap/wall_clip.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <ostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/seed.h"

namespace rtm {
namespace {

TEST(ClipToHalfSpace, SquareCutThroughTheMiddleIsExact) {
    const Polygon3 square = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const Polygon3 right = clip_to_half_space(square, {1, 0, 0}, 0.5, true);
    const Polygon3 want_right = {{0.5, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0.5, 1, 1}};
    EXPECT_EQ(right, want_right);
    const Polygon3 left = clip_to_half_space(square, {1, 0, 0}, 0.5, false);
    const Polygon3 want_left = {{0, 0, 1}, {0.5, 0, 1}, {0.5, 1, 1}, {0, 1, 1}};
    EXPECT_EQ(left, want_left);
    EXPECT_TRUE(clip_to_half_space(square, {1, 0, 0}, 2.0, true).empty());  // nothing on that side
    EXPECT_EQ(clip_to_half_space(square, {1, 0, 0}, 2.0, false), square);   // all of it
    // A corner cut adds one vertex.
    EXPECT_EQ(clip_to_half_space(square, {1, 1, 0}, 0.5, false).size(), 3u);
    EXPECT_EQ(clip_to_half_space(square, {1, 1, 0}, 0.5, true).size(), 5u);
}

TEST(OutsideViewCone, EyeInThePlaneKeepsTheWallWhole) {
    const std::array<glm::dvec3, 4> quad = {glm::dvec3(1, 0, -1), {2, 0, -1}, {2, 0, 1}, {1, 0, 1}};  // plane y = 0
    const Polygon3 wall = {{1, 0, -1}, {1, 0, 1}, {1, 1, 1}, {1, 1, -1}};
    const auto pieces = outside_view_cone(wall, quad, 1e-4);
    ASSERT_EQ(pieces.size(), 1u);
    EXPECT_EQ(pieces[0], wall);
}

bool inside_convex(const Polygon3& poly, const glm::dvec3& normal, const glm::dvec3& p, double tol) {
    for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec3 e = poly[(k + 1) % poly.size()] - poly[k];
        if (glm::dot(glm::cross(e, p - poly[k]), normal) < -tol) return false;
    }
    return true;
}

// The sweep: a random relief plane and quad (a parallelogram), an eye off the plane, a wall standing on one of
// the quad's edges from displacement lo to hi. For random points of the wall: where the eye ray through the point
// meets the plane (ahead of the eye) outside the quad (the shader's test), some piece holds the point; a point
// inside the cone by twice the margin is in no piece.
TEST(OutsideViewCone, PiecesKeepWhatMissesTheQuadAndDropWhatMeetsIt) {
    const uint64_t seed = test::test_seed(20261201);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0), S(0.0, 1.0);
    int kept_checked = 0, dropped_checked = 0;
    for (int iter = 0; iter < 400; ++iter) {
        const glm::dvec3 origin{U(rng), U(rng), U(rng)};
        glm::dvec3 a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)};
        if (glm::length(glm::cross(glm::normalize(a), glm::normalize(b))) < 0.3) continue;
        const glm::dvec3 f = glm::normalize(glm::cross(a, b));
        const glm::dvec3 eye = origin + 0.5 * (a + b) + 3.0 * glm::dvec3(U(rng), U(rng), U(rng)) +
                               f * (0.2 + 2.0 * S(rng)) * (S(rng) < 0.5 ? 1.0 : -1.0);
        // Eye-relative quad and wall.
        const glm::dvec3 c = origin - eye;
        const std::array<glm::dvec3, 4> quad = {c, c + a, c + a + b, c + b};
        const int edge = int(S(rng) * 4) % 4;
        const glm::dvec3 p0 = quad[size_t(edge)], p1 = quad[size_t((edge + 1) % 4)];
        const double lo = -S(rng), hi = S(rng);
        const Polygon3 wall = {p0 + f * lo, p1 + f * lo, p1 + f * hi, p0 + f * hi};
        const double margin = 1e-4 * (glm::length(a + b) + glm::length(c + 0.5 * (a + b)));
        const auto pieces = outside_view_cone(wall, quad, margin);
        const glm::dvec3 wall_normal = glm::cross(wall[1] - wall[0], wall[3] - wall[0]);
        const double tol = 1e-9 * glm::dot(wall_normal, wall_normal);
        for (const Polygon3& piece : pieces) {
            ASSERT_GE(piece.size(), 3u);
            ASSERT_LE(piece.size(), 8u);  // the renderer's vertex budget (kMaxReliefVertices)
            for (const glm::dvec3& v : piece) ASSERT_TRUE(inside_convex(wall, wall_normal, v, tol));
        }
        ASSERT_LE(pieces.size(), 4u);
        // Dual basis for (u, v) in the plane, as the shader has it.
        const double aa = glm::dot(a, a), ab = glm::dot(a, b), bb = glm::dot(b, b), det = aa * bb - ab * ab;
        const glm::dvec3 da = (a * bb - b * ab) / det, db = (b * aa - a * ab) / det;
        const double cf = glm::dot(c, f);
        for (int k = 0; k < 50; ++k) {
            const double s = S(rng), t = S(rng);
            const glm::dvec3 p = (wall[0] * (1 - s) + wall[1] * s) * (1 - t) + (wall[3] * (1 - s) + wall[2] * s) * t;
            const double pf = glm::dot(p, f);
            if (!(std::abs(pf) > 1e-9) || cf / pf <= 0.0) continue;  // the ray does not reach the plane ahead
            const glm::dvec3 q = p * (cf / pf) - c;
            const double u = glm::dot(q, da), v = glm::dot(q, db);
            bool in_some = false;
            for (const Polygon3& piece : pieces) in_some = in_some || inside_convex(piece, wall_normal, p, tol);
            // Well inside: at least twice the margin inside each of the cone's faces (the planes through the eye
            // and the quad's edges), which the ray test below must agree is inside the quad.
            double inside_by = 1e300;
            for (size_t e = 0; e < 4; ++e) {
                glm::dvec3 n = glm::normalize(glm::cross(quad[e], quad[(e + 1) % 4]));
                if (glm::dot(n, c + 0.5 * (a + b)) < 0.0) n = -n;
                inside_by = std::min(inside_by, glm::dot(n, p));
            }
            const bool outside = u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0;
            const bool well_inside = inside_by >= 2.0 * margin;
            ASSERT_FALSE(outside && well_inside) << "iteration " << iter << ": the cone and the ray disagree";
            if (outside) {
                ++kept_checked;
                ASSERT_TRUE(in_some) << "iteration " << iter << ": a point whose ray misses the quad (u " << u << ", v "
                                     << v << ") is in no piece";
            } else if (well_inside) {
                ++dropped_checked;
                ASSERT_FALSE(in_some) << "iteration " << iter << ": a point whose ray meets the quad at (u " << u
                                      << ", v " << v << ") is in a piece";
            }
        }
    }
    EXPECT_GT(kept_checked, 1000);
    EXPECT_GT(dropped_checked, 1000);
}

}  // namespace

void PrintTo(const PlaneRect& r, std::ostream* os) {
    *os << "[" << r.u0 << ", " << r.u1 << "] x [" << r.v0 << ", " << r.v1 << "]";
}

namespace {

TEST(MarginContent, BoxesAreTheSampledTexelsWidenedByOne) {
    // 10x8 texture, margins left 2, right 1, bottom 2, top 1: the quad is columns 2..8, rows 1..5.
    ImageRGBA8 img(10, 8);
    for (Rgba8& p : img.pixels) p = {9, 9, 9, 0};
    auto set = [&](int x, int row, uint8_t a) { img.at(x, row) = {200, 100, 50, a}; };
    set(0, 3, 255);  // left margin: u -2 .. -1, v 2 .. 3
    set(9, 7, 10);   // right margin, bottom row: u 7 .. 8, v -2 .. -1 (any alpha > 0 counts)
    set(4, 5, 255);  // the quad's bottom row (next to the bottom band): u 2 .. 3, v 0 .. 1
    set(5, 7, 255);  // bottom margin: u 3 .. 4, v -2 .. -1
    set(5, 3, 255);  // inside the quad, away from its border: in no band
    const std::vector<PlaneRect> want = {{-3, 1, 0, 4}, {6, -3, 9, 0}, {1, -3, 5, 2}};  // left, right, bottom
    EXPECT_EQ(margin_content(img, 2, 1, 2, 1), want);
    // A band whose margin is 0 is not looked at: without a left margin the texel in column 0 is the quad's (and
    // u counts from column 0).
    const std::vector<PlaneRect> no_left = {{8, -3, 11, 0}, {3, -3, 7, 2}};
    EXPECT_EQ(margin_content(img, 0, 1, 2, 1), no_left);
    EXPECT_TRUE(margin_content(img, 0, 0, 0, 0).empty());
}

// Alpha as GL_LINEAR with GL_CLAMP_TO_EDGE filters it at plane point (u, v) (texture coordinates as the side
// polygons' shader makes them: s = (u + ml) / W, t = 1 - (v + mb) / H, row 0 at t = 0).
double filtered_alpha(const ImageRGBA8& img, int ml, int mb, double u, double v) {
    const double x = u + ml - 0.5, y = img.height - (v + mb) - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    auto a = [&](double xi, double yi) {
        const int cx = std::clamp(int(xi), 0, img.width - 1), cy = std::clamp(int(yi), 0, img.height - 1);
        return double(img.at(cx, cy).a);
    };
    return (a(x0, y0) * (1 - fx) + a(x0 + 1, y0) * fx) * (1 - fy) +
           (a(x0, y0 + 1) * (1 - fx) + a(x0 + 1, y0 + 1) * fx) * fy;
}

TEST(MarginContent, HoldsEveryPlanePointOutsideTheQuadThatFilteringGivesAlpha) {
    const uint64_t seed = test::test_seed(20261202);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> S(0.0, 1.0);
    int checked = 0;
    for (int iter = 0; iter < 300; ++iter) {
        auto margin = [&] { return S(rng) < 0.3 ? 0 : 1 + int(S(rng) * 6); };
        const int ml = margin(), mr = margin(), mb = margin(), mt = margin();
        const int w = 1 + int(S(rng) * 8), h = 1 + int(S(rng) * 8);
        ImageRGBA8 img(ml + w + mr, mb + h + mt);
        const double density = S(rng) * 0.3;
        std::vector<std::pair<int, int>> sampled;
        for (int row = 0; row < img.height; ++row)
            for (int x = 0; x < img.width; ++x) {
                const bool on = S(rng) < density;
                img.at(x, row) = {7, 7, 7, uint8_t(on ? 1 + int(S(rng) * 255) : 0)};
                if (on) sampled.emplace_back(x, row);
            }
        const std::vector<PlaneRect> rects = margin_content(img, ml, mr, mb, mt);
        ASSERT_LE(rects.size(), 4u);
        for (int k = 0; k < 200 && !sampled.empty(); ++k) {
            // Near a sampled texel's centre (within its filter footprint and a little beyond), or anywhere.
            const auto [x, row] = sampled[size_t(S(rng) * double(sampled.size())) % sampled.size()];
            double u = x - ml + 0.5 + 3.0 * (S(rng) - 0.5), v = img.height - 1 - row - mb + 0.5 + 3.0 * (S(rng) - 0.5);
            if (k % 4 == 0) u = -ml + S(rng) * img.width, v = -mb + S(rng) * img.height;
            const bool in_texture = u >= -ml && u <= w + mr && v >= -mb && v <= h + mt;
            const bool on_quad = u >= 0 && u <= w && v >= 0 && v <= h;
            if (!in_texture || on_quad || !(filtered_alpha(img, ml, mb, u, v) > 0.0)) continue;
            ++checked;
            bool held = false;
            for (const PlaneRect& r : rects) held = held || (u >= r.u0 && u <= r.u1 && v >= r.v0 && v <= r.v1);
            ASSERT_TRUE(held) << "iteration " << iter << ": plane point (" << u << ", " << v
                              << ") has alpha but lies in no rectangle";
        }
    }
    EXPECT_GT(checked, 5000);
}

TEST(InsidePlaneRects, KeepsWhatMeetsARectangleAndDropsTheRest) {
    const uint64_t seed = test::test_seed(20261203);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0), S(0.0, 1.0);
    int kept_checked = 0, dropped_checked = 0, whole = 0;
    for (int iter = 0; iter < 400; ++iter) {
        // A relief plane with texel axes a, b (a 16x16 quad), an eye off it, a wall on one edge.
        const glm::dvec3 origin{U(rng), U(rng), U(rng)};
        glm::dvec3 a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)};
        if (glm::length(glm::cross(glm::normalize(a), glm::normalize(b))) < 0.3) continue;
        a /= 16.0, b /= 16.0;
        const glm::dvec3 f = glm::normalize(glm::cross(a, b));
        const glm::dvec3 eye = origin + 8.0 * (a + b) + 3.0 * glm::dvec3(U(rng), U(rng), U(rng)) +
                               f * (0.2 + 2.0 * S(rng)) * (S(rng) < 0.5 ? 1.0 : -1.0);
        const glm::dvec3 c = origin - eye;
        const std::array<glm::dvec3, 4> quad = {c, c + 16.0 * a, c + 16.0 * (a + b), c + 16.0 * b};
        const int edge = int(S(rng) * 4) % 4;
        const glm::dvec3 p0 = quad[size_t(edge)], p1 = quad[size_t((edge + 1) % 4)];
        const double lo = -S(rng), hi = S(rng);
        const Polygon3 wall = {p0 + f * lo, p1 + f * lo, p1 + f * hi, p0 + f * hi};
        std::vector<PlaneRect> rects;
        for (int n = int(S(rng) * 5); n > 0; --n) {
            const double u0 = -8 + 32 * S(rng), v0 = -8 + 32 * S(rng);
            rects.push_back({u0, v0, u0 + 1 + 8 * S(rng), v0 + 1 + 8 * S(rng)});
        }
        const auto pieces = inside_plane_rects(wall, c, a, b, rects);
        const double cf = glm::dot(c, f);
        bool all_ahead = true;
        for (const glm::dvec3& p : wall) all_ahead = all_ahead && glm::dot(p, f) * cf > 0.0;
        if (!all_ahead) {
            ASSERT_EQ(pieces.size(), 1u);
            EXPECT_EQ(pieces[0], wall);
            ++whole;
            continue;
        }
        ASSERT_LE(pieces.size(), rects.size());
        const glm::dvec3 wall_normal = glm::cross(wall[1] - wall[0], wall[3] - wall[0]);
        const double tol = 1e-9 * glm::dot(wall_normal, wall_normal);
        for (const Polygon3& piece : pieces) {
            ASSERT_LE(piece.size(), 8u);  // 4 vertices and one per clipping plane (the renderer's budget allows 12)
            for (const glm::dvec3& v : piece) ASSERT_TRUE(inside_convex(wall, wall_normal, v, tol));
        }
        const double aa = glm::dot(a, a), ab = glm::dot(a, b), bb = glm::dot(b, b), det = aa * bb - ab * ab;
        const glm::dvec3 da = (a * bb - b * ab) / det, db = (b * aa - a * ab) / det;
        for (int k = 0; k < 50; ++k) {
            const double s = S(rng), t = S(rng);
            const glm::dvec3 p = (wall[0] * (1 - s) + wall[1] * s) * (1 - t) + (wall[3] * (1 - s) + wall[2] * s) * t;
            const glm::dvec3 q = p * (cf / glm::dot(p, f)) - c;
            const double u = glm::dot(q, da), v = glm::dot(q, db);
            // Inside a rectangle, or outside all of them, by 1e-6 texels (rounding of the cut; texels are 1/16).
            bool inside = false, near = false;
            for (const PlaneRect& r : rects) {
                inside = inside || (u > r.u0 + 1e-6 && u < r.u1 - 1e-6 && v > r.v0 + 1e-6 && v < r.v1 - 1e-6);
                near = near || (u > r.u0 - 1e-6 && u < r.u1 + 1e-6 && v > r.v0 - 1e-6 && v < r.v1 + 1e-6);
            }
            bool in_some = false;
            for (const Polygon3& piece : pieces) in_some = in_some || inside_convex(piece, wall_normal, p, tol);
            if (inside) {
                ++kept_checked;
                ASSERT_TRUE(in_some) << "iteration " << iter << ": (u " << u << ", v " << v
                                     << ") is in a rectangle but in no piece";
            } else if (!near) {
                ++dropped_checked;
                ASSERT_FALSE(in_some) << "iteration " << iter << ": (u " << u << ", v " << v
                                      << ") is in no rectangle but in a piece";
            }
        }
    }
    EXPECT_GT(kept_checked, 500);
    EXPECT_GT(dropped_checked, 1000);
    EXPECT_GT(whole, 10);
}

}  // namespace
}  // namespace rtm
