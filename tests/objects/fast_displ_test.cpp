// Depth correction's displacement image by the fast kernels (objects/fast_displ.h) against the reference kernels'
// (prewarp with displ_out): over random views of the town's reliefs and of bumps, both reconstructions, with and
// without the side polygons' margins, the colour is the same bit for bit, the empty pixels are the same, and every
// index is within one level of the reference's.
#include "objects/fast_displ.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "common/seed.h"
#include "formats/relief_manifest.h"
#include "objects/bounds.h"
#include "procedural/procedural_media.h"

namespace rtm {
namespace {

TEST(FastDispl, ColourExactAndIndicesWithinOneLevelOfTheReference) {
    std::vector<std::pair<std::string, ReliefTexture>> reliefs;
    for (const char* name : {"town_facade0", "town_roof", "town_side", "town_garden"})
        reliefs.emplace_back(name, load_relief(std::string(RTM_SOURCE_DIR) + "/media/" + name + ".relief.json"));
    reliefs.emplace_back("bumps", to_relief(make_bumps(96)));
    const uint64_t seed = test::test_seed(4220);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int cases = test::sweep_cases(60);
    long long pixels = 0, differ = 0;
    int covered = 0;
    for (int c = 0; c < cases; ++c) {
        const auto& [name, t] = reliefs[size_t(c) % reliefs.size()];
        const ReliefTexture index = index_relief(t);
        const Bounds b = relief_bounds(t);
        // An eye in front of the quad (+f side), 1 to 4 radii from its centre, head-on to grazing.
        const glm::dvec3 ua = glm::normalize(t.geometry.a), ub = glm::normalize(t.geometry.b);
        glm::dvec3 dir = t.geometry.f() * (0.3 + std::abs(u(rng))) + ua * (1.5 * u(rng)) + ub * u(rng);
        dir = glm::normalize(dir);
        const glm::dvec3 eye = b.centre() + dir * (b.radius() * (1.0 + 3.0 * std::abs(u(rng))));
        const PrewarpCoefficients k = compute_coefficients(t.geometry, eye);
        PrewarpOptions o;
        o.method = c % 2 ? Reconstruction::pipelined : Reconstruction::two_pass;
        o.keep_outliers = (c / 2) % 2 == 0;
        o.threads = 1 + c % 3;
        if (!fast_displ_covers(t, k, o)) continue;
        ++covered;
        PrewarpWorkspace ws_ref, ws_fast;
        ImageRGBA8 ref, fast, scratch;
        Image2D<uint8_t> ref_displ, fast_displ;
        prewarp(t, k, o, ws_ref, ref, &ref_displ);
        prewarp_fast_displ(t, index, k, o, ws_fast, fast, fast_displ, scratch);
        ASSERT_EQ(ref.width, fast.width) << name << " case " << c;
        ASSERT_EQ(ref.height, fast.height) << name << " case " << c;
        ASSERT_EQ(ref.pixels, fast.pixels) << name << " case " << c;
        ASSERT_EQ(ref_displ.width, fast_displ.width);
        ASSERT_EQ(ref_displ.height, fast_displ.height);
        for (size_t i = 0; i < ref_displ.pixels.size(); ++i) {
            const int a = ref_displ.pixels[i], f = fast_displ.pixels[i];
            ASSERT_EQ(a == kEmptyIndex, f == kEmptyIndex) << name << " case " << c << " pixel " << i;
            if (a == kEmptyIndex) continue;
            ++pixels;
            differ += a != f;
            ASSERT_LE(std::abs(a - f), 1) << name << " case " << c << " pixel " << i;
        }
    }
    std::printf("%d views on the fast kernels: %lld of %lld covered pixels' indices differ by one level\n", covered,
                differ, pixels);
    EXPECT_GE(covered, cases / 2);
}

}  // namespace
}  // namespace rtm
