// The synthetic objects' faces (procedural/synthetic_object.h), which carry discontinuity marks (paper section
// 4.1.1), on the fast AVX-512 two-pass kernels (warp/simd/avx512_two_pass.h) against the generic kernels: each face
// pre-warped alone from random eyes around the box, one and two threads, copies of still runs on and off, with and
// without the side polygons' margins, pixel for pixel; and whole faces of an object (adjacent faces warped onto the
// face, the face over them, composite and crack closing: ReliefObject::prewarp_face), the same image either way.
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "common/seed.h"
#include "objects/relief_object.h"
#include "procedural/synthetic_object.h"
#include "warp/prewarp.h"
#include "warp/simd/schedule.h"

namespace rtm {
namespace {

// A random eye outside the box [-1, 1]^3, 1.3 to 4 radii from its centre.
glm::dvec3 random_eye(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const double az = U(rng) * 6.283185307179586, el = (U(rng) - 0.5) * 3.0, d = std::sqrt(3.0) * (1.3 + U(rng) * 2.7);
    return d * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
}

TEST(MarkedFaces, SyntheticFacesOnTheFastKernelsMatchTheReference) {
    if (!fast_prewarp_available()) GTEST_SKIP() << "no AVX-512 on this CPU: marked reliefs stay on the reference";
    const uint64_t seed = test::test_seed(4301);
    std::mt19937_64 rng(seed);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    for (SyntheticShape shape : {SyntheticShape::sphere, SyntheticShape::cross_box, SyntheticShape::rounded_cube}) {
        const SixFaceObject object = make_synthetic_object(shape, 128);
        long long marked = 0;  // pairs of texels marked as not connected, both directions
        for (const ReliefTexture& t : object.faces)
            for (uint8_t b : t.breaks) marked += ((b & kBreakRight) != 0) + ((b & kBreakUp) != 0);
        EXPECT_GT(marked, 0) << to_string(shape);
        for (int f = 0; f < kFaceCount; ++f) {
            const ReliefTexture& t = object.faces[size_t(f)];
            ASSERT_FALSE(t.breaks.empty()) << to_string(shape) << " face " << kFaceKeys[size_t(f)];
            for (int i = 0; i < 6; ++i) {
                const glm::dvec3 eye = random_eye(rng);
                const PrewarpCoefficients k = compute_coefficients(t.geometry, eye);
                PrewarpOptions o;
                o.keep_outliers = i % 2 == 1;
                o.isa = Isa::generic;
                o.threads = 1;
                SCOPED_TRACE("seed " + std::to_string(seed) + " " + to_string(shape) + " face " + kFaceKeys[size_t(f)] +
                             " view " + std::to_string(i) + " " + k.to_string());
                prewarp(t, k, o, ws_ref, ref);
                o.isa = Isa::avx512;
                if (k.side != ViewSide::on_plane) {
                    EXPECT_TRUE(fast_prewarp_covers(Isa::avx512, t, k, o, prewarp_extent(t, k, o), nullptr));
                }
                for (int threads : {1, 2})
                    for (bool copy : {true, false}) {
                        o.threads = threads;
                        o.copy_still_runs = copy;
                        prewarp(t, k, o, ws_fast, fast);
                        ASSERT_TRUE(fast == ref) << "threads " << threads << ", copy " << copy;
                    }
            }
        }
    }
}

TEST(MarkedFaces, ObjectFacesAreTheSameOnEveryTarget) {
    if (!fast_prewarp_available()) GTEST_SKIP() << "no AVX-512 on this CPU: marked reliefs stay on the reference";
    const uint64_t seed = test::test_seed(4302);
    std::mt19937_64 rng(seed);
    for (SyntheticShape shape : {SyntheticShape::sphere, SyntheticShape::cross_box}) {
        ReliefObject object(make_synthetic_object(shape, 96));
        for (int i = 0; i < 4; ++i) {
            const glm::dvec3 eye = random_eye(rng);
            const ObjectRegion region = object.region(eye);
            if (region.inside()) continue;
            for (int f : region.visible_faces()) {
                SCOPED_TRACE("seed " + std::to_string(seed) + " " + to_string(shape) + " view " + std::to_string(i) +
                             " face " + kFaceKeys[size_t(f)]);
                PrewarpOptions o;
                o.isa = Isa::generic;
                ObjectFacePrewarp ref, fast;
                object.prewarp_face(f, eye, 0, o, false, ref);
                o.isa = Isa::avx512;
                object.prewarp_face(f, eye, 0, o, false, fast);
                ASSERT_TRUE(fast.image == ref.image);
                EXPECT_EQ(fast.crack_pixels, ref.crack_pixels);
            }
        }
    }
}

}  // namespace
}  // namespace rtm
