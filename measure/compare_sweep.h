// What `rtm compare` sweeps: every method at its quality settings, each one entry with a unique id
// ("method" or "method:setting"), the family it belongs to and its parameters by name. The settings and why they
// were chosen are in measure/compare_sweep.cpp and docs/COMPARE.md.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "measure/compare_base.h"
#include "objects/render_relief.h"

namespace rtm {

struct CompareEntry {
    std::string id;       // "two-pass:tables", "relief-mapping:l32-b8", "flat", "raycast", ...
    std::string method;   // the technique as results.csv names it (to_string(RenderMethod))
    std::string setting;  // "" when the method has one setting
    std::string family;   // "pre-warp", "per-pixel", "conventional" (flat) or "truth" (micromesh, raycast)
    // "flat": the relief on its quad, measured against raycast (micromesh for an object or a scene); "curved" and
    // "sphere": the relief bent over the cylinder or the sphere patch of quadric silhouettes
    // (perpixel/curved_patch.h), measured against the micro-polygon mesh of the same bent relief (reliefs only;
    // measure/compare_base.h).
    std::string base = "flat";
    nlohmann::json params;  // the setting's values by name (the papers' names for the per-pixel methods)
    RenderSettings render;  // method, pre-warp options, draw options, per-pixel settings
    int output_scale = 1;   // the pre-warp's output scale (warp/upsample.h); reliefs only
    bool counts_iterations() const { return family == "per-pixel"; }
    bool curved() const { return is_curved_base(base); }
};

// flat, the pre-warp settings, the per-pixel methods at 3-4 settings each (the papers' defaults included; one for
// the parallax pair, which has no steps), then the truths micromesh and raycast. `quick`: 2 settings per method
// (the cheapest and the default). Then the curved base: relief mapping with quadric silhouettes at relief mapping's
// steps, the same shader without the quadrics (the original relief mapping on the curved mesh) at the same steps,
// the paper's exact distance (equation 6) at the default steps, and its truths curved-micromesh and curved-raycast; the
// curved entries render the relief bent over a cylinder patch, so their errors are measured against the curved mesh,
// never against the flat truths. Then the sphere base at the default steps, with and without the quadrics
// ("sphere-l32-b8", "no-quadric-sphere-l32-b8"), and its truths sphere-micromesh and sphere-raycast.
std::vector<CompareEntry> compare_sweep(bool quick);

}  // namespace rtm
