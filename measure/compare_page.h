// The comparison's web page: DIR/index.html, one self-contained page (no network; the pictures beside it) built
// from the comparison's results (the same object `rtm compare` writes as DIR/results.json), and the step-by-step
// pictures of the pre-warp for one view (the paper's Figures 5-11). See docs/COMPARE.md for the page and the
// results.json fields.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "objects/relief_quad.h"
#include "texmap/camera.h"

namespace rtm {

struct ComparePageInput {
    std::string out_dir;     // index.html is written here; image paths in `results` are relative to it
    nlohmann::json results;  // the results.json object (fields in docs/COMPARE.md)
    // The relief and the camera of the step-by-step section (a relief quad of the run, an oblique view); when
    // absent the page has no such section.
    ReliefQuad* steps_relief = nullptr;
    std::optional<Camera> steps_camera;
};

// Writes out_dir/index.html (and the step-by-step pictures under out_dir/steps/). Throws IoError naming the file
// that cannot be written.
void write_compare_page(const ComparePageInput& input);

}  // namespace rtm
