// The comparison of methods on one relief: each method renders the same views, and each picture is measured
// against the ray-cast truth (run time next to error). Used by `rtm compare` and by the accuracy tests.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "measure/image_diff.h"
#include "objects/relief_quad.h"
#include "texmap/camera.h"

namespace rtm {

struct CompareView {
    std::string name;                                   // e.g. "az45_el20"
    double azimuth = 0, elevation = 0, distance = 2.2;  // the --orbit convention
};

// A view of the --orbit convention named from its angles, as the reports name views: "az30_el20" (whole degrees).
CompareView orbit_view(double azimuth, double elevation, double distance = 2.2);

// Eight views from frontal to grazing (azimuth 85 degrees: 5 degrees above the relief plane).
std::vector<CompareView> default_compare_views();

struct CompareMethod {
    std::string name;  // "two-pass", "two-pass-exact", ...
    RenderMethod method = RenderMethod::two_pass;
    PrewarpOptions prewarp;
};

// flat, two-pass without and with side polygons, two-pass-exact, pipelined (with side polygons), micromesh.
std::vector<CompareMethod> default_compare_methods();

struct CompareRow {
    std::string view, method;
    double ms = 0;  // median total frame time (raycast: one run)
    double prewarp_ms = 0;
    DiffResult error;         // against raycast
    DiffResult vs_micromesh;  // against the micro-polygon mesh
};

struct CompareOptions {
    int width = 512, height = 512;
    int repeat = 5;  // frames timed per method and view (median)
    int threads = 0;
    std::vector<CompareView> views = default_compare_views();
    std::vector<CompareMethod> methods = default_compare_methods();
    // Called with each picture (view, method name, image) so the caller can save it; may be empty.
    std::function<void(const std::string&, const std::string&, const ImageRGBA8&)> on_image;
    std::function<void(const std::string&)> on_progress;  // one line per finished step
};

// Camera for a view of `quad` (orbit about the relief's bounding sphere, 45 degree field of view).
Camera compare_camera(const ReliefQuad& quad, const CompareView& v, int width, int height);

// Needs no current GL context: creates an offscreen one.
std::vector<CompareRow> run_comparison(ReliefQuad& quad, const CompareOptions& options);

// A Markdown table of the rows, and a per-method summary (mean PSNR, mean IoU, median time over the views).
std::string comparison_markdown(const std::string& title, const std::vector<CompareRow>& rows);

}  // namespace rtm
