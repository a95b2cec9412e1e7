#include "test_util.h"

#include <cstdlib>

namespace rtm::test {

ReliefGeometry random_geometry(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::uniform_real_distribution<double> S(0.2, 3.0);
    for (;;) {
        glm::dvec3 a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)};
        if (glm::length(glm::cross(glm::normalize(a), glm::normalize(b))) < 0.2) continue;
        ReliefGeometry g;
        g.origin = {U(rng) * 2, U(rng) * 2, U(rng) * 2};
        g.a = glm::normalize(a) * (S(rng) * 0.01);
        // b orthogonal to a is not required by the conventions, but the relief's "parallel camera" uses f
        // perpendicular to both; keep b general (not orthogonal) to exercise the dual basis.
        g.b = glm::normalize(b) * (S(rng) * 0.01);
        return g;
    }
}

}  // namespace rtm::test
