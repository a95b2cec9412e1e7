// The occlusion-compatible quadrants drawn about the epipole: they tile the picture, and the epipole is clamped.
#include <gtest/gtest.h>

#include "warp/quadrants.h"

namespace rtm {
namespace {

double area(const QuadrantOverlay::Box& b) { return (b.p1.x - b.p0.x) * (b.p1.y - b.p0.y); }

TEST(Quadrants, TileThePictureAboutAnInsideEpipole) {
    const QuadrantOverlay o = quadrant_overlay({10, 20}, {110, 70}, {40, 30});
    EXPECT_TRUE(o.inside);
    EXPECT_EQ(o.epipole, glm::dvec2(40, 30));
    EXPECT_EQ(o.quadrants[0].p0, glm::dvec2(10, 20));
    EXPECT_EQ(o.quadrants[0].p1, glm::dvec2(40, 30));
    EXPECT_EQ(o.quadrants[3].p0, glm::dvec2(40, 30));
    EXPECT_EQ(o.quadrants[3].p1, glm::dvec2(110, 70));
    double sum = 0;
    for (const auto& b : o.quadrants) sum += area(b);
    EXPECT_DOUBLE_EQ(sum, 100.0 * 50.0);  // exact: small integers
}

TEST(Quadrants, EpipoleBeyondThePictureIsClampedAndTwoQuadrantsAreEmpty) {
    const QuadrantOverlay o = quadrant_overlay({0, 0}, {64, 32}, {100, 10});
    EXPECT_FALSE(o.inside);
    EXPECT_EQ(o.epipole, glm::dvec2(64, 10));
    EXPECT_EQ(area(o.quadrants[1]), 0.0);  // right of the epipole: nothing left of the picture
    EXPECT_EQ(area(o.quadrants[3]), 0.0);
    EXPECT_EQ(area(o.quadrants[0]) + area(o.quadrants[2]), 64.0 * 32.0);
}

TEST(Quadrants, EpipoleOnTheBorderCountsAsInside) {
    EXPECT_TRUE(quadrant_overlay({0, 0}, {8, 8}, {8, 0}).inside);
    EXPECT_FALSE(quadrant_overlay({0, 0}, {8, 8}, {8.001, 0}).inside);
}

}  // namespace
}  // namespace rtm
