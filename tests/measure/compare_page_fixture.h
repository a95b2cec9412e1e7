// A small synthetic comparison for the page's tests (tests/measure/compare_page_test.cpp) and for the headless
// browser test (tests/cli/compare_page.sh, through the compare_page_fixture program): 2 sources, 3 views from
// frontal to grazing, 5 methods of four families on the flat base and 2 on the curved base (quadric silhouettes with
// and without the quadrics, measured against curved-micromesh), with the pictures (small PNGs) the rows name, a
// missing PSNR, a missing IoU, and the Pareto flags computed by a naive O(n^2) dominance test per source and base.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace rtm::test {

// Writes the pictures under dir/img/ and returns the results.json object (not written) naming them.
nlohmann::json write_compare_fixture(const std::string& dir);

// Writes the fixture, dir/results.json and dir/index.html with a step-by-step section (a 64x64 procedural relief
// seen obliquely; its final frame rendered through OSMesa).
void write_compare_fixture_page(const std::string& dir);

}  // namespace rtm::test
