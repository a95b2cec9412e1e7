// Helpers shared by the warp tests: random reliefs and views with a printed seed.
#pragma once

#include <glm/geometric.hpp>

#include <cstdint>
#include <random>
#include <string>

#include "common/seed.h"
#include "warp/relief_texture.h"

namespace rtm::test {

// test_seed: RTM_SEED if set, else a fixed default (common/seed.h); tests print it on failure via SCOPED_TRACE.

// A w x h relief with displacement from `fn(x, row)` (world units) in [lo, hi], colours from a hash.
template <class Fn>
ReliefTexture make_test_relief(int w, int h, double lo, double hi, Fn fn, ReliefGeometry g = {}) {
    ImageRGBA8 c(w, h);
    ImageF d(w, h);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) {
            uint32_t s = uint32_t(x) * 73856093u ^ uint32_t(r) * 19349663u;
            s = s * 2654435761u;
            c.at(x, r) = {uint8_t(s >> 24), uint8_t(s >> 16), uint8_t(s >> 8), 255};
            d.at(x, r) = float(fn(x, r));
        }
    return make_relief(c, d, lo, hi, g);
}

// Random unit-ish geometry: origin, a, b not axis-aligned, non-square texels.
ReliefGeometry random_geometry(std::mt19937_64& rng);

}  // namespace rtm::test
