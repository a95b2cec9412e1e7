// What the coverage filter (Fant-style, PrewarpOptions::filter) costs and gains against point sampling: each
// filter pre-warps the same relief for the same views, timed, and each result is measured against the
// supersampled truth of truth/prewarp_truth.h. Used by `rtm bench-filter`; the table goes to docs/ACCURACY.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "procedural/procedural_media.h"
#include "truth/prewarp_truth.h"
#include "warp/prewarp.h"

namespace rtm {

struct FilterMeasurement {
    std::string relief, view, filter;
    double ms = 0;       // median pre-warp time (generic reference kernel, lookup tables, `threads` threads)
    double fast_ms = 0;  // median time of the fastest kernel that computes it (point: the fast kernels)
    PrewarpError error;  // against the truth
};

struct FilterMeasureOptions {
    std::vector<std::string> reliefs = procedural_names();
    int size = 256;   // procedural relief size
    int samples = 8;  // truth rays per pixel side
    int repeat = 5;   // timed pre-warps per measurement (median)
    int threads = 1;
    std::function<void(const std::string&)> progress;  // one line per step; may be empty
    // Called with every picture: (relief, view, "truth" | "point" | "coverage", image); may be empty.
    std::function<void(const std::string&, const std::string&, const std::string&, const ImageRGBA8&)> on_image;
};

std::vector<FilterMeasurement> measure_filters(const FilterMeasureOptions& options);

std::string filter_table_markdown(const std::vector<FilterMeasurement>& rows);

}  // namespace rtm
