// What `rtm compare` sweeps: every method at its quality settings, each one entry with a unique id
// ("method" or "method:setting"), the family it belongs to and its parameters by name. The settings and why they
// were chosen are in measure/compare_sweep.cpp and docs/COMPARE.md.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "objects/render_relief.h"

namespace rtm {

struct CompareEntry {
    std::string id;         // "two-pass:tables", "relief-mapping:l32-b8", "flat", "raycast", ...
    std::string method;     // the technique as results.csv names it (to_string(RenderMethod))
    std::string setting;    // "" when the method has one setting
    std::string family;     // "pre-warp", "per-pixel", "conventional" (flat) or "truth" (micromesh, raycast)
    nlohmann::json params;  // the setting's values by name (the papers' names for the per-pixel methods)
    RenderSettings render;  // method, pre-warp options, draw options, per-pixel settings
    int output_scale = 1;   // the pre-warp's output scale (warp/upsample.h); reliefs only
    bool counts_iterations() const { return family == "per-pixel"; }
};

// flat, the pre-warp settings, the per-pixel methods at 3-4 settings each (the papers' defaults included; one for
// the parallax pair, which has no steps), then the truths micromesh and raycast. `quick`: 2 settings per method
// (the cheapest and the default). The relief mapping with quadric silhouettes is left out: it renders the relief
// bent over a cylinder, not the surface the truths render.
std::vector<CompareEntry> compare_sweep(bool quick);

}  // namespace rtm
