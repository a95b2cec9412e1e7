// The axis swap of Figure 15 (paper section 4.1): an adjacent face's texels expressed as a relief on a visible
// face's plane and pre-warped with equations 4a/4b land exactly where the 3-D projection of each texel from the eye
// meets the visible face's plane; and warp_adjacent_face's two 1-D passes put every texel's sample at that pixel.
#include "objects/face_swap.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <vector>
#include <random>

#include "objects/object_region.h"
#include "common/seed.h"
#include "procedural/synthetic_object.h"
#include "warp/isa.h"
#include "warp/prewarp.h"

namespace rtm {
namespace {

unsigned seed() {
    const char* s = std::getenv("RTM_SEED");
    const unsigned v = s ? unsigned(std::strtoul(s, nullptr, 10)) : 20260601u;
    std::printf("RTM_SEED=%u\n", v);
    return v;
}

// A random eye from which `face` is visible: outside its plane, anywhere around.
glm::dvec3 eye_in_front(std::mt19937& rng, const Box& box, int face) {
    std::uniform_real_distribution<double> any(-3.0, 3.0), out(0.05, 3.0);
    glm::dvec3 e(any(rng), any(rng), any(rng));
    const int ax = face_axis(face);
    e[ax] = face_sign(face) > 0 ? box.hi[ax] + out(rng) : box.lo[ax] - out(rng);
    return e;
}

TEST(FaceSwap, DisplacementBecomesAColumnAndAColumnBecomesDisplacement) {
    const Box box{{-1, -2, -0.5}, {1, 2, 1.5}};
    for (int f = 0; f < kFaceCount; ++f)
        for (int g = 0; g < kFaceCount; ++g) {
            if (face_axis(f) == face_axis(g)) continue;
            SCOPED_TRACE(std::string(kFaceKeys[size_t(f)]) + " <- " + kFaceKeys[size_t(g)]);
            const FaceSwap s = make_face_swap(box_face_geometry(box, g, 8, 16), box_face_geometry(box, f, 8, 16));
            // G's displacement (source 2) feeds one of F's texel coordinates, never F's displacement ...
            const int d_to = s.source_of(0) == 2 ? 0 : s.source_of(1) == 2 ? 1 : -1;
            ASSERT_NE(d_to, -1) << s.to_string();
            // ... and F's displacement comes from one of G's texel coordinates (a column or a row).
            const int from = s.source_of(2);
            ASSERT_TRUE(from == 0 || from == 1) << s.to_string();
            // The shared axis (along the common edge) maps to itself.
            EXPECT_EQ(s.source_of(1 - d_to), 1 - from == 0 ? 0 : 1 - from) << s.to_string();
        }
}

TEST(FaceSwap, PrewarpedAdjacentTexelsLieOnTheirRaysFromTheEye) {
    std::mt19937 rng(seed());
    const SixFaceObject obj = make_synthetic_object(SyntheticShape::sphere, 16);
    double worst = 0.0;
    for (int trial = 0; trial < 40; ++trial)
        for (int f = 0; f < kFaceCount; ++f) {
            const glm::dvec3 eye = eye_in_front(rng, obj.box, f);
            const ReliefGeometry& fg = obj.faces[size_t(f)].geometry;
            const PrewarpCoefficients k = compute_coefficients(fg, eye);
            const glm::dvec3 nf = fg.f();
            for (int g = 0; g < kFaceCount; ++g) {
                if (face_axis(f) == face_axis(g)) continue;
                const ReliefTexture& gt = obj.faces[size_t(g)];
                const FaceSwap s = make_face_swap(gt.geometry, fg);
                for (int r = 0; r < gt.height; ++r)
                    for (int x = 0; x < gt.width; ++x) {
                        if (gt.empty_at(x, r)) continue;
                        const double d = gt.displ(x, r);
                        const glm::dvec3 p = s.apply(x + 0.5, (gt.height - 1 - r) + 0.5, d);
                        const double den = 1.0 + k.k3 * p.z;
                        ASSERT_GT(den, 0.0);  // every point of the box is beyond F's plane from the eye
                        const double ui = (p.x + k.k1 * p.z) / den, vi = (p.y + k.k2 * p.z) / den;
                        // The exact 3-D projection: the ray from the eye through the texel's point, cut by F's plane.
                        const glm::dvec3 X = gt.point(x, r);
                        const double t = glm::dot(fg.origin - eye, nf) / glm::dot(X - eye, nf);
                        const glm::dvec3 P = eye + t * (X - eye);
                        const double u_exact = glm::dot(P - fg.origin, fg.a) / glm::dot(fg.a, fg.a);
                        const double v_exact = glm::dot(P - fg.origin, fg.b) / glm::dot(fg.b, fg.b);
                        worst = std::max({worst, std::abs(ui - u_exact), std::abs(vi - v_exact)});
                        // Double precision on coordinates of a few texels, through a handful of operations.
                        ASSERT_NEAR(ui, u_exact, 1e-9) << kFaceKeys[size_t(f)] << " <- " << kFaceKeys[size_t(g)];
                        ASSERT_NEAR(vi, v_exact, 1e-9);
                        // And the point swapped back is the texel's 3-D point.
                        const glm::dvec3 back = fg.origin + fg.a * p.x + fg.b * p.y + nf * p.z;
                        ASSERT_NEAR(glm::length(back - X), 0.0, 1e-12);
                    }
            }
        }
    std::printf("largest difference from the exact projection: %.3g texels\n", worst);
}

// Every texel of an adjacent face, warped alone (its neighbours emptied), lands in the pixel that contains its
// projection on F: the two 1-D passes move it where equations 4a/4b say. With `exact` the displacement is the
// texel's own; quantized, it is its level's (Quantizer::decode), up to half a level away, which can move the texel
// into the next pixel (seed 3 did: u 6.997 from the exact displacement, over 7 from its level's).
TEST(FaceSwap, WarpAdjacentFacePutsEachTexelAtItsProjection) {
    std::mt19937 rng(seed());
    SixFaceObject obj = make_synthetic_object(SyntheticShape::cross_box, 12);
    int checked = 0;
    for (int trial = 0; trial < 6; ++trial)
        for (int f = 0; f < kFaceCount; ++f) {
            const glm::dvec3 eye = eye_in_front(rng, obj.box, f);
            const ReliefTexture& ft = obj.faces[size_t(f)];
            const PrewarpCoefficients k = compute_coefficients(ft.geometry, eye);
            const int g = (f + 2 + trial) % kFaceCount;
            if (face_axis(g) == face_axis(f)) continue;
            const ReliefTexture& full = obj.faces[size_t(g)];
            for (int r = 0; r < full.height; r += 3)
                for (int x = 0; x < full.width; x += 2)
                    for (const bool exact : {true, false}) {
                        if (full.empty_at(x, r)) continue;
                        SCOPED_TRACE(exact ? "exact" : "quantized");
                        ReliefTexture one = full;
                        for (ReliefTexel& t : one.texels.edit()) t.q = kEmptyIndex;
                        one.texels.edit()[size_t(r) * size_t(one.width) + size_t(x)] = full.texel(x, r);
                        AdjacentWorkspace ws;
                        AdjacentBuffer buf;
                        buf.reset(ft.width, ft.height);
                        warp_adjacent_face(one, ft.geometry, ft.width, ft.height, k, exact, ws, buf);
                        const FaceSwap s = make_face_swap(one.geometry, ft.geometry);
                        const double d = exact ? double(one.displ(x, r)) : one.quant.decode(one.texel(x, r).q);
                        const glm::dvec3 p = s.apply(x + 0.5, (one.height - 1 - r) + 0.5, d);
                        double ui, vi;
                        ASSERT_TRUE(k.warp(p.x, p.y, p.z, ui, vi));
                        const int px = int(std::floor(ui)), prow = ft.height - 1 - int(std::floor(vi));
                        int written = 0;
                        for (const Rgba8& c : buf.color.pixels) written += c.a != 0;
                        const bool inside = px >= 0 && px < ft.width && prow >= 0 && prow < ft.height;
                        ASSERT_EQ(written, inside ? 1 : 0)
                            << "texel " << x << "," << r << " of " << kFaceKeys[size_t(g)];
                        if (!inside) continue;
                        EXPECT_EQ(buf.color.at(px, prow).a, 255) << "u " << ui << " v " << vi;
                        EXPECT_FLOAT_EQ(buf.depth.at(px, prow), float(p.z));
                        ++checked;
                    }
        }
    EXPECT_GT(checked, 50);
}

// The fast schedule (per-column, per-row and per-level terms, one intermediate array, empty lines skipped) gives the
// reference's buffer value for value: every pair of perpendicular faces, random eyes in front of the visible face,
// both objects (the cross box carries discontinuity marks), quantized and exact displacement, one and two threads,
// accumulating two adjacent faces into one buffer as the object does. The fast schedule's workspace is reused over
// the whole sweep (other sizes, faces and eyes), as an object's is: each intermediate row clears only the extent the
// previous call wrote, and the column pass reads only inside the new one, so stale samples would show here.
TEST(FaceSwap, FastScheduleMatchesTheReference) {
    const uint64_t seed = test::test_seed(20261202u);
    SCOPED_TRACE("RTM_SEED=" + std::to_string(seed));
    std::printf("RTM_SEED=%llu\n", (unsigned long long)seed);
    std::mt19937 rng{static_cast<unsigned>(seed)};
    std::uniform_int_distribution<int> size(6, 40);
    long long landed = 0;
    const std::vector<Isa> isas = supported_isas();
    std::map<Isa, int> runs;
    AdjacentWorkspace ws_fast;
    for (int trial = 0; trial < 8; ++trial) {
        const SyntheticShape shape = trial % 2 ? SyntheticShape::cross_box : SyntheticShape::sphere;
        const SixFaceObject obj = make_synthetic_object(shape, size(rng));
        for (int f = 0; f < kFaceCount; ++f) {
            const glm::dvec3 eye = eye_in_front(rng, obj.box, f);
            const ReliefTexture& ft = obj.faces[size_t(f)];
            const PrewarpCoefficients k = compute_coefficients(ft.geometry, eye);
            for (bool exact : {false, true})
                for (int threads : {1, 2}) {
                    // Each instruction-set variant of the fast schedule in turn (warp/isa.h), the threads alternating.
                    const Isa isa = isas[size_t(trial * 4 + f * 2 + threads) % isas.size()];
                    SCOPED_TRACE("trial " + std::to_string(trial) + " face " + kFaceKeys[size_t(f)] +
                                 (exact ? " exact" : "") + " threads " + std::to_string(threads) + " isa " +
                                 isa_name(isa));
                    AdjacentWorkspace ws_ref;
                    AdjacentBuffer fast, ref;
                    fast.reset(ft.width, ft.height);
                    ref.reset(ft.width, ft.height);
                    for (int g = 0; g < kFaceCount; ++g) {
                        if (face_axis(g) == face_axis(f)) continue;
                        const ReliefTexture& gt = obj.faces[size_t(g)];
                        const long long a = warp_adjacent_face(gt, ft.geometry, ft.width, ft.height, k, exact, ws_fast,
                                                               fast, threads, isa);
                        const long long b = warp_adjacent_face_reference(gt, ft.geometry, ft.width, ft.height, k, exact,
                                                                         ws_ref, ref, threads);
                        ASSERT_EQ(a, b) << kFaceKeys[size_t(g)];
                        ASSERT_TRUE(fast.color == ref.color) << "colour differs after " << kFaceKeys[size_t(g)];
                        ASSERT_TRUE(fast.depth == ref.depth) << "depth differs after " << kFaceKeys[size_t(g)];
                    }
                    for (const Rgba8& c : fast.color.pixels) landed += c.a != 0;
                    ++runs[isa];
                }
        }
    }
    EXPECT_GT(landed, 1000);                                         // the comparison saw real samples
    for (Isa isa : isas) EXPECT_GT(runs[isa], 10) << isa_name(isa);  // and every variant this CPU runs
}

// A random need of F's size: scattered pixels, rectangles, or the holes of F's own pre-warp, or nothing at all.
Image2D<uint8_t> random_need(std::mt19937& rng, const ReliefTexture& ft, const PrewarpCoefficients& k, int kind) {
    Image2D<uint8_t> m(ft.width, ft.height);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    if (kind == 0) {
        const double p = U(rng) * 0.2;
        for (uint8_t& v : m.pixels) v = U(rng) < p;
    } else if (kind == 1) {
        for (int n = 0; n < 3; ++n) {
            const int x0 = int(U(rng) * ft.width), r0 = int(U(rng) * ft.height);
            const int x1 = std::min(ft.width, x0 + 1 + int(U(rng) * 6)),
                      r1 = std::min(ft.height, r0 + 1 + int(U(rng) * 6));
            for (int r = r0; r < r1; ++r)
                for (int x = x0; x < x1; ++x) m.at(x, r) = 1;
        }
    } else if (kind == 2) {
        PrewarpWorkspace pws;
        ImageRGBA8 own;
        PrewarpOptions o;
        o.keep_outliers = false;
        prewarp(ft, k, o, pws, own);
        for (size_t i = 0; i < m.pixels.size(); ++i) m.pixels[i] = own.pixels[i].a < 128;
    }
    return m;
}

// With a need, warp_adjacent_face's buffer holds at every needed pixel what the whole warp puts there, value for value
// (colour and depth, an empty pixel included), and counts the same texels that cannot be pre-warped: random needs
// (scattered pixels, small rectangles, the holes of F's own pre-warp, none), both objects, every pair of
// perpendicular faces, random eyes in front of F, quantized and exact, one and two threads, every instruction-set
// variant, two adjacent faces accumulated into one buffer as the object does, the workspace reused throughout.
TEST(FaceSwap, NeededPixelsMatchTheWholeWarp) {
    const uint64_t seed = test::test_seed(20261203u);
    SCOPED_TRACE("RTM_SEED=" + std::to_string(seed));
    std::printf("RTM_SEED=%llu\n", (unsigned long long)seed);
    std::mt19937 rng{static_cast<unsigned>(seed)};
    std::uniform_int_distribution<int> size(6, 48);
    const std::vector<Isa> isas = supported_isas();
    AdjacentWorkspace ws_need, ws_whole, ws_chunks;
    long long needed = 0, landed = 0, differ_elsewhere = 0;
    for (int trial = 0; trial < 10; ++trial) {
        const SyntheticShape shape = trial % 2 ? SyntheticShape::cross_box : SyntheticShape::sphere;
        const SixFaceObject obj = make_synthetic_object(shape, size(rng));
        for (int f = 0; f < kFaceCount; ++f) {
            const glm::dvec3 eye = eye_in_front(rng, obj.box, f);
            const ReliefTexture& ft = obj.faces[size_t(f)];
            const PrewarpCoefficients k = compute_coefficients(ft.geometry, eye);
            for (int kind = 0; kind < 4; ++kind) {
                AdjacentNeed need;
                need.assign(random_need(rng, ft, k, kind));
                const bool exact = (trial + kind) % 2 == 1;
                const int threads = 1 + (f + kind) % 2;
                const Isa isa = isas[size_t(trial * 7 + f * 3 + kind) % isas.size()];
                SCOPED_TRACE("trial " + std::to_string(trial) + " face " + kFaceKeys[size_t(f)] + " need kind " +
                             std::to_string(kind) + (exact ? " exact" : "") + " threads " + std::to_string(threads) +
                             " isa " + isa_name(isa));
                // part: the need, whole: none, chunked: the need with the adjacent face's chunks made once, which
                // must give part's buffer everywhere (the same bounds from the chunks' extremes).
                AdjacentBuffer part, whole, chunked;
                part.reset(ft.width, ft.height);
                whole.reset(ft.width, ft.height);
                chunked.reset(ft.width, ft.height);
                for (int g = 0; g < kFaceCount; ++g) {
                    if (face_axis(g) == face_axis(f)) continue;
                    const ReliefTexture& gt = obj.faces[size_t(g)];
                    const long long a = warp_adjacent_face(gt, ft.geometry, ft.width, ft.height, k, exact, ws_need,
                                                           part, threads, isa, &need);
                    const long long b = warp_adjacent_face(gt, ft.geometry, ft.width, ft.height, k, exact, ws_whole,
                                                           whole, threads, isa);
                    ASSERT_EQ(a, b) << kFaceKeys[size_t(g)];
                    const AdjacentChunks chunks = AdjacentChunks::make(gt);
                    const long long c = warp_adjacent_face(gt, ft.geometry, ft.width, ft.height, k, exact, ws_chunks,
                                                           chunked, threads, isa, &need, &chunks);
                    ASSERT_EQ(a, c) << kFaceKeys[size_t(g)];
                    ASSERT_TRUE(chunked.color.pixels == part.color.pixels) << "with chunks, " << kFaceKeys[size_t(g)];
                    ASSERT_TRUE(chunked.depth.pixels == part.depth.pixels) << "with chunks, " << kFaceKeys[size_t(g)];
                    for (int row = 0; row < ft.height; ++row)
                        for (int x = 0; x < ft.width; ++x) {
                            if (!need.needed(x, row)) {
                                differ_elsewhere += !(part.color.at(x, row) == whole.color.at(x, row));
                                continue;
                            }
                            ASSERT_TRUE(part.color.at(x, row) == whole.color.at(x, row))
                                << "pixel " << x << "," << row << " after " << kFaceKeys[size_t(g)] << ": "
                                << to_string(part.color.at(x, row)) << " against " << to_string(whole.color.at(x, row));
                            ASSERT_EQ(part.depth.at(x, row), whole.depth.at(x, row)) << "pixel " << x << "," << row;
                        }
                }
                for (int row = 0; row < ft.height; ++row)
                    for (int x = 0; x < ft.width; ++x)
                        if (need.needed(x, row)) ++needed, landed += whole.color.at(x, row).a != 0;
            }
        }
    }
    std::printf("needed pixels %lld, of which adjacent samples landed on %lld; %lld pixels not needed differ\n", needed,
                landed, differ_elsewhere);
    EXPECT_GT(landed, 500);            // the comparison saw real samples at needed pixels
    EXPECT_GT(differ_elsewhere, 100);  // and the need did leave work out
}

// A relief's chunks: per chunk of 16 texels and one neighbour on each side, the first and last non-empty texel and
// the extremes of level and displacement, against a direct count; and chunks of another relief are refused.
TEST(FaceSwap, AdjacentChunksHoldTheirTexelsExtremes) {
    const SixFaceObject obj = make_synthetic_object(SyntheticShape::sphere, 37);
    const ReliefTexture& t = obj.faces[0];
    const AdjacentChunks chunks = AdjacentChunks::make(t);
    ASSERT_EQ(chunks.per_row, 3);
    ASSERT_EQ(chunks.chunks.size(), size_t(3 * t.height));
    int empty_chunks = 0;
    for (int r = 0; r < t.height; ++r)
        for (int k = 0; k < 3; ++k) {
            const AdjacentChunks::Chunk& c = chunks.chunks[size_t(r * 3 + k)];
            int first = -1, last = -1, qmin = 255, qmax = -1;
            float dmin = 1e30f, dmax = -1e30f;
            for (int x = std::max(0, 16 * k - 1); x <= std::min(t.width - 1, 16 * k + 16); ++x) {
                const int q = t.texel(x, r).q;
                if (q == kEmptyIndex) continue;
                if (first < 0) first = x;
                last = x;
                qmin = std::min(qmin, q), qmax = std::max(qmax, q);
                dmin = std::min(dmin, t.displ(x, r)), dmax = std::max(dmax, t.displ(x, r));
            }
            if (first < 0) {
                EXPECT_GT(c.first, c.last) << r << " " << k;
                ++empty_chunks;
                continue;
            }
            EXPECT_EQ(c.first, first) << r << " " << k;
            EXPECT_EQ(c.last, last) << r << " " << k;
            EXPECT_EQ(c.qmin, qmin) << r << " " << k;
            EXPECT_EQ(c.qmax, qmax) << r << " " << k;
            EXPECT_EQ(c.dmin, dmin) << r << " " << k;
            EXPECT_EQ(c.dmax, dmax) << r << " " << k;
        }
    EXPECT_GT(empty_chunks, 0);  // the sphere's corners are empty: both kinds seen

    const ReliefTexture& f = obj.faces[2];
    const PrewarpCoefficients k = compute_coefficients(f.geometry,
                                                       (obj.box.lo + obj.box.hi) * 0.5 + glm::dvec3(0, 4, 0));
    AdjacentNeed need;
    need.assign_holes(ImageRGBA8(f.width, f.height));
    AdjacentWorkspace ws;
    AdjacentBuffer out;
    out.reset(f.width, f.height);
    const SixFaceObject other = make_synthetic_object(SyntheticShape::sphere, 20);
    const AdjacentChunks wrong = AdjacentChunks::make(other.faces[0]);
    try {
        warp_adjacent_face(t, f.geometry, f.width, f.height, k, false, ws, out, 1, Isa::automatic, &need, &wrong);
        FAIL() << "chunks of a 20x20 relief were taken for a 37x37 one";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("the chunks are of a 20x20 relief, the face is 37x37"), std::string::npos)
            << e.what();
    }
}

// A need built for one pass orientation serves the adjacent faces whose passes read it (the same buffer as with
// both built) and is refused, naming the orientation, by one whose passes read the other.
TEST(FaceSwap, AdjacentNeedBuildsOnlyTheOrientationsAskedFor) {
    const SixFaceObject obj = make_synthetic_object(SyntheticShape::cross_box, 24);
    const int f = 4;  // +z
    const ReliefTexture& ft = obj.faces[size_t(f)];
    const PrewarpCoefficients k = compute_coefficients(ft.geometry, glm::dvec3(0.3, 0.2, 4.0));
    Image2D<uint8_t> mask(ft.width, ft.height);
    for (size_t i = 0; i < mask.pixels.size(); ++i) mask.pixels[i] = uint8_t(i % 3 == 0);
    AdjacentNeed both;
    both.assign(mask, 1);
    std::array<int, 2> seen{};
    for (int g = 0; g < kFaceCount; ++g) {
        if (face_axis(g) == face_axis(f)) continue;
        const ReliefTexture& gt = obj.faces[size_t(g)];
        const int o = adjacent_pass_orientation(gt.geometry, ft.geometry);
        ASSERT_TRUE(o == 0 || o == 1) << kFaceKeys[size_t(g)];
        ++seen[size_t(o)];
        AdjacentNeed only, other;
        only.assign(mask, 1, {o == 0, o == 1});
        other.assign(mask, 1, {o == 1, o == 0});
        EXPECT_EQ(only.count, both.count);
        AdjacentWorkspace ws;
        AdjacentBuffer a, b;
        a.reset(ft.width, ft.height);
        b.reset(ft.width, ft.height);
        warp_adjacent_face(gt, ft.geometry, ft.width, ft.height, k, false, ws, a, 1, Isa::automatic, &only);
        warp_adjacent_face(gt, ft.geometry, ft.width, ft.height, k, false, ws, b, 1, Isa::automatic, &both);
        EXPECT_TRUE(a.color.pixels == b.color.pixels) << kFaceKeys[size_t(g)];
        try {
            warp_adjacent_face(gt, ft.geometry, ft.width, ft.height, k, false, ws, a, 1, Isa::automatic, &other);
            FAIL() << "a need without orientation " << o << " was taken for " << kFaceKeys[size_t(g)];
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("not indexed for pass orientation " + std::to_string(o)),
                      std::string::npos)
                << e.what();
        }
    }
    EXPECT_GT(seen[0] + seen[1], 0);
}

// The need from a face's pre-warp: every pixel whose alpha is under 128 (empty, or covered less than half), every
// alpha value in every channel mix, on one and two threads.
TEST(FaceSwap, AdjacentNeedHolesAreThePixelsUnderHalfAlpha) {
    std::mt19937 rng(11);
    ImageRGBA8 img(37, 29);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = {uint8_t(rng()), uint8_t(rng()), uint8_t(rng()), uint8_t(i < 256 ? i : rng())};
    for (int threads : {1, 2}) {
        AdjacentNeed need;
        need.assign_holes(img, threads);
        long long n = 0;
        for (int row = 0; row < img.height; ++row)
            for (int x = 0; x < img.width; ++x) {
                ASSERT_EQ(need.needed(x, row), img.at(x, row).a < 128) << x << "," << row << " " << threads;
                n += img.at(x, row).a < 128;
            }
        EXPECT_EQ(need.count, n);
    }
}

TEST(FaceSwap, AdjacentNeedLinesMatchTheMask) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    Image2D<uint8_t> m(13, 7);
    for (uint8_t& v : m.pixels) v = U(rng) < 0.3;
    AdjacentNeed need;
    need.assign(m);
    long long n = 0;
    for (int row = 0; row < m.height; ++row)
        for (int x = 0; x < m.width; ++x) {
            ASSERT_EQ(need.needed(x, row), m.at(x, row) != 0);
            ASSERT_EQ(need.lines[0].needed(x, m.height - 1 - row), m.at(x, row) != 0);
            ASSERT_EQ(need.lines[1].needed(m.height - 1 - row, x), m.at(x, row) != 0);
            n += m.at(x, row);
        }
    EXPECT_EQ(need.count, n);
    // Per line: the extent and the counts over every range of positions (clamped to the line), both orientations.
    for (const AdjacentNeed::Lines& l : need.lines)
        for (int c = 0; c < l.n1; ++c) {
            int lo = l.n2, hi = -1;
            for (int k = 0; k < l.n2; ++k)
                if (l.needed(c, k)) lo = std::min(lo, k), hi = k;
            ASSERT_EQ(l.lo[size_t(c)], lo) << "line " << c;
            ASSERT_EQ(l.hi[size_t(c)], hi) << "line " << c;
            for (int k0 = -2; k0 < l.n2 + 2; ++k0)
                for (int k1 = k0 - 1; k1 < l.n2 + 2; ++k1) {
                    bool any = false;
                    for (int k = std::max(k0, 0); k <= std::min(k1, l.n2 - 1); ++k) any |= l.needed(c, k);
                    ASSERT_EQ(l.any(c, k0, k1), any) << "line " << c << " " << k0 << ".." << k1;
                }
        }
}

}  // namespace
}  // namespace rtm
