// The page's short reading of the figures, written from the measured values only: which methods are on the
// run-time-against-error front, what the pre-warp costs beside the per-pixel methods, how the error grows from the
// frontal to the most grazing view, where coverage and silhouettes go wrong, and the search iterations of relief
// and interval mapping. Every sentence names its numbers; a value that is missing (NaN) is left out and counted.
#pragma once

#include <string>
#include <vector>

#include "measure/compare_results.h"

namespace rtm {

// Paragraphs of plain text (not HTML-escaped).
std::vector<std::string> compare_reading(const CompareResults& results);

}  // namespace rtm
