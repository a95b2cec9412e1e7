// The comparison engine of `rtm compare` (docs/COMPARE.md): every method of the sweep (measure/compare_sweep.h) at
// every setting renders each source (measure/compare_source.h) from a set of views from frontal to grazing; each
// frame is timed (median over repeats, the pre-warp's stages split) and measured against the truths (PSNR, RMSE over
// common pixels, coverage IoU, silhouette error). The results become results.json / results.csv / compare.md here;
// the web page is measure/compare_page.h's.
#pragma once

#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "measure/compare_source.h"
#include "measure/compare_sweep.h"
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
// Three of them for --quick: frontal, oblique, grazing.
std::vector<CompareView> quick_compare_views();

// Camera for a view of what `bounds` encloses (orbit about its bounding sphere, 45 degree field of view).
Camera compare_camera(const Bounds& bounds, const CompareView& v, int width, int height);
Camera compare_camera(const ReliefQuad& quad, const CompareView& v, int width, int height);

struct CompareOptions {
    int width = 512, height = 512;
    int repeat = 5;  // frames timed per method and view after one warm-up (median); raycast: one frame
    int threads = 0;
    std::vector<CompareView> views = default_compare_views();
    std::vector<CompareEntry> methods = compare_sweep(false);
    // Where the pictures go (DIR/images/...); empty: none are written and the rows' paths stay empty.
    std::string out_dir;
    // Called after each step (one source, view and method): steps done, steps in all, what was done.
    std::function<void(size_t, size_t, const std::string&)> on_progress;
};

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

struct CompareRow {
    std::string source, view, method_id, method, setting, family;
    std::string base = "flat";  // the entry's base: "flat", "curved" or "sphere" (CompareEntry::base)
    // What `error` is measured against: "raycast", "micromesh", or the curved base's mesh, "curved-micromesh" or
    // "sphere-micromesh".
    std::string truth;
    double ms = 0;      // median frame time
    StageTimes stages;  // medians per stage (pre-warp family only; `other` = total - the three)
    bool has_stages = false;
    DiffResult error;                   // against `truth`
    DiffResult vs_micromesh;            // against the micro-polygon mesh (a curved base's own for a curved base)
    double silhouette_px = kNoValue;    // silhouette error against the reference truth
    double iterations_mean = kNoValue;  // per-pixel search iterations over the covered pixels
    std::string image, heatmap, iterations_image;  // relative to out_dir; empty = none
};

struct CompareRun {
    std::vector<CompareView> views;
    std::vector<const CompareEntry*> methods;  // the entries that rendered at least one source
    std::vector<CompareRow> rows;              // per source, view, method in that order
    // truths[source][view]["raycast" | "micromesh" | "curved-micromesh" | "sphere-micromesh"] = image path ("" when
    // not rendered or not written; a curved base's mesh only where that base was rendered)
    std::map<std::string, std::map<std::string, std::map<std::string, std::string>>> truths;
};

// Needs no current GL context: creates an offscreen one. Throws IoError when a picture cannot be written.
CompareRun run_comparison(const std::vector<CompareSource*>& sources, const CompareOptions& options);

// The results.json object (fields: docs/COMPARE.md) of a run; `meta` holds title, machine, threads, quick,
// image_size (copied in).
nlohmann::json comparison_json(const std::vector<CompareSource*>& sources, const CompareOptions& options,
                               const CompareRun& run, const nlohmann::json& meta);
// results.csv from the results.json object: a header row, then one row per element of "rows", the columns being
// the rows' fields (stages as stage_prewarp, stage_upload, stage_texmap, stage_other); null is an empty cell.
std::string comparison_csv(const nlohmann::json& results);
// A Markdown table of the summary rows (per source, base and method id).
std::string comparison_markdown(const nlohmann::json& results);

}  // namespace rtm
