// The synthetic objects' faces (procedural/synthetic_object.h), which carry discontinuity marks (paper section
// 4.1.1), on the fast two-pass kernels of every SIMD target this machine supports (warp/simd/hwy_two_pass.h)
// against the generic kernels: each face pre-warped alone from random eyes around the box,
// one and two threads, copies of still runs on and off, with and without the side polygons' margins, pixel for pixel;
// and whole faces of an object (adjacent faces warped onto the face, the face over them, composite and crack closing:
// ReliefObject::prewarp_face), the same image either way.
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "common/seed.h"
#include "objects/relief_object.h"
#include "procedural/synthetic_object.h"
#include "warp/isa.h"
#include "warp/prewarp.h"
#include "warp/simd/schedule.h"

namespace rtm {
namespace {

// The SIMD targets this machine supports (each forced in turn: warp/isa.h).
std::vector<Isa> simd_targets() {
    std::vector<Isa> v;
    for (Isa isa : supported_isas())
        if (isa != Isa::generic) v.push_back(isa);
    return v;
}

// A random eye outside the box [-1, 1]^3, 1.3 to 4 radii from its centre.
glm::dvec3 random_eye(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const double az = U(rng) * 6.283185307179586, el = (U(rng) - 0.5) * 3.0, d = std::sqrt(3.0) * (1.3 + U(rng) * 2.7);
    return d * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
}

TEST(MarkedFaces, SyntheticFacesOnTheFastKernelsMatchTheReference) {
    if (simd_targets().empty()) GTEST_SKIP() << "no SIMD target on this CPU: marked reliefs stay on the reference";
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
                for (Isa isa : simd_targets()) {
                    o.isa = isa;
                    if (k.side != ViewSide::on_plane) {
                        EXPECT_TRUE(fast_prewarp_covers(isa, t, k, o, prewarp_extent(t, k, o), nullptr));
                    }
                    for (int threads : {1, 2})
                        for (bool copy : {true, false}) {
                            o.threads = threads;
                            o.copy_still_runs = copy;
                            prewarp(t, k, o, ws_fast, fast);
                            ASSERT_TRUE(fast == ref) << isa_name(isa) << ", threads " << threads << ", copy " << copy;
                        }
                }
            }
        }
    }
}

TEST(MarkedFaces, ObjectFacesAreTheSameOnEveryTarget) {
    if (simd_targets().empty()) GTEST_SKIP() << "no SIMD target on this CPU: marked reliefs stay on the reference";
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
                for (Isa isa : simd_targets()) {
                    o.isa = isa;
                    object.prewarp_face(f, eye, 0, o, false, fast);
                    ASSERT_TRUE(fast.image == ref.image) << isa_name(isa);
                    EXPECT_EQ(fast.crack_pixels, ref.crack_pixels) << isa_name(isa);
                }
            }
        }
    }
}

}  // namespace
}  // namespace rtm
