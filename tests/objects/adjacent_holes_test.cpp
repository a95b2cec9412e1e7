// ReliefObject::prewarp_face warps the adjacent faces only where the face's own pre-warp left holes
// (AdjacentNeed, objects/face_swap.h): the face's texture is byte for byte what warping them whole gives, with the
// depth-correction levels, the pixels filled and the cracks closed, over random views of the synthetic objects, both
// reconstructions, both filters (coverage with two-pass), quantized and exact, levels 0 and 1, one and two threads.
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "common/seed.h"
#include "objects/relief_object.h"
#include "procedural/synthetic_object.h"

namespace rtm {
namespace {

// A random eye outside the box, 1.05 to 4 radii from its centre; now and then on a region boundary (level with a
// face's plane, or a hair outside it).
glm::dvec3 random_eye(std::mt19937_64& rng, const Box& box) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const glm::dvec3 c = (box.lo + box.hi) * 0.5, half = (box.hi - box.lo) * 0.5;
    const double radius = glm::length(half);
    const double az = U(rng) * 6.283185307179586, el = (U(rng) - 0.5) * 3.0, d = radius * (1.05 + U(rng) * 2.95);
    glm::dvec3 e = c + d * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
    const double pick = U(rng);
    if (pick < 0.15) {
        const int ax = int(U(rng) * 3) % 3;
        e[ax] = U(rng) < 0.5 ? box.hi[ax] + 1e-9 : box.lo[ax];
    }
    return e;
}

TEST(AdjacentHoles, ObjectFacesAreTheSameAsWithTheAdjacentFacesWhole) {
    const uint64_t seed = test::test_seed(20261203u);
    SCOPED_TRACE("RTM_SEED=" + std::to_string(seed));
    std::printf("RTM_SEED=%llu\n", (unsigned long long)seed);
    std::mt19937_64 rng(seed);
    long long faces = 0, filled = 0;
    for (SyntheticShape shape : {SyntheticShape::sphere, SyntheticShape::cross_box, SyntheticShape::rounded_cube}) {
        ReliefObject object(make_synthetic_object(shape, 48));
        for (int i = 0; i < 12; ++i) {
            const glm::dvec3 eye = random_eye(rng, object.box());
            const ObjectRegion region = object.region(eye);
            if (region.inside()) continue;
            PrewarpOptions o;
            o.method = i % 3 == 2 ? Reconstruction::pipelined : Reconstruction::two_pass;
            o.filter = i % 4 == 3 && o.method == Reconstruction::two_pass ? Filter::coverage : Filter::point;
            o.exact = i % 5 == 4;
            o.threads = 1 + i % 2;
            const int level = i % 6 == 5 ? 1 : 0;
            const bool displ = i % 2 == 0;
            for (int f : region.visible_faces()) {
                SCOPED_TRACE(to_string(shape) + " view " + std::to_string(i) + " eye " + std::to_string(eye.x) + "," +
                             std::to_string(eye.y) + "," + std::to_string(eye.z) + " face " + kFaceKeys[size_t(f)]);
                ObjectFacePrewarp holes, whole;
                object.prewarp_face(f, eye, level, o, displ, holes, true);
                object.prewarp_face(f, eye, level, o, displ, whole, false);
                ASSERT_TRUE(holes.image == whole.image);
                ASSERT_TRUE(holes.displ == whole.displ);
                EXPECT_EQ(holes.adjacent_pixels, whole.adjacent_pixels);
                EXPECT_EQ(holes.crack_pixels, whole.crack_pixels);
                EXPECT_EQ(holes.texels, whole.texels);
                ++faces;
                filled += whole.adjacent_pixels;
            }
        }
    }
    std::printf("%lld faces compared, %lld pixels filled by adjacent faces\n", faces, filled);
    EXPECT_GT(faces, 40);
    EXPECT_GT(filled, 1000);  // the adjacent faces did fill holes
}

// The composite and the crack closing run over rows in parallel: the face's texture, its depth levels and the counts
// are the same on one, two and three threads (views where cracks are closed and adjacent faces fill holes).
TEST(AdjacentHoles, CompositeAndCracksAreTheSameOnAnyNumberOfThreads) {
    const uint64_t seed = test::test_seed(20261204u);
    SCOPED_TRACE("RTM_SEED=" + std::to_string(seed));
    std::printf("RTM_SEED=%llu\n", (unsigned long long)seed);
    std::mt19937_64 rng(seed);
    long long faces = 0, cracks = 0, filled = 0;
    for (SyntheticShape shape : {SyntheticShape::sphere, SyntheticShape::cross_box}) {
        ReliefObject object(make_synthetic_object(shape, 64));
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 eye = random_eye(rng, object.box());
            const ObjectRegion region = object.region(eye);
            if (region.inside()) continue;
            PrewarpOptions o;
            o.filter = i % 4 == 3 ? Filter::coverage : Filter::point;
            const bool displ = i % 2 == 0;
            for (int f : region.visible_faces()) {
                SCOPED_TRACE(to_string(shape) + " view " + std::to_string(i) + " face " + kFaceKeys[size_t(f)]);
                ObjectFacePrewarp one;
                o.threads = 1;
                object.prewarp_face(f, eye, 0, o, displ, one);
                for (int threads : {2, 3}) {
                    ObjectFacePrewarp many;
                    o.threads = threads;
                    object.prewarp_face(f, eye, 0, o, displ, many);
                    ASSERT_TRUE(many.image == one.image) << threads << " threads";
                    ASSERT_TRUE(many.displ == one.displ) << threads << " threads";
                    EXPECT_EQ(many.adjacent_pixels, one.adjacent_pixels);
                    EXPECT_EQ(many.crack_pixels, one.crack_pixels);
                }
                ++faces;
                cracks += one.crack_pixels;
                filled += one.adjacent_pixels;
            }
        }
    }
    std::printf("%lld faces, %lld cracks closed, %lld pixels filled by adjacent faces\n", faces, cracks, filled);
    EXPECT_GT(faces, 10);
    EXPECT_GT(cracks, 0);
    EXPECT_GT(filled, 100);
}

}  // namespace
}  // namespace rtm
