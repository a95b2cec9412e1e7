#include "objects/bounds.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace rtm {

void Bounds::extend(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
}

void Bounds::extend(const Bounds& b) {
    if (b.empty()) return;
    extend(b.lo);
    extend(b.hi);
}

double Bounds::radius() const { return empty() ? 0.0 : 0.5 * glm::length(hi - lo); }

Bounds relief_bounds(const ReliefTexture& t) {
    const ReliefGeometry& g = t.geometry;
    const glm::dvec3 f = g.f();
    Bounds b;
    for (double d : {t.quant.min, t.quant.max})
        for (int cu = 0; cu <= 1; ++cu)
            for (int cv = 0; cv <= 1; ++cv)
                b.extend(g.origin + g.a * double(cu * t.width) + g.b * double(cv * t.height) + f * d);
    return b;
}

}  // namespace rtm
