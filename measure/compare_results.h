// The comparison's results (the results.json object, fields in docs/COMPARE.md) read into plain structs for the
// page. Missing and null numbers become NaN, missing strings empty: a page can always be written, and says which
// values are missing.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "measure/compare_base.h"

namespace rtm {

struct ResultSource {
    std::string name, kind, path;
    int width = 0, height = 0;
};

struct ResultView {
    std::string name;
    double azimuth = 0, elevation = 0, distance = 0;  // degrees; the --orbit convention
    // Angle between the view direction and the relief's normal (+z at azimuth 0, elevation 0), in degrees: 0 is
    // frontal, 90 grazing.
    double angle_from_normal() const;
};

struct ResultMethod {
    std::string id, method, family, setting;
    std::string base;  // "flat", "curved" or "sphere" (measure/compare_base.h); empty (older files): flat
};

struct ResultRow {
    std::string source, view, method_id, method, setting, family;
    double ms, psnr, rmse, iou, silhouette_px, psnr_vs_micromesh, iou_vs_micromesh, iterations_mean;
    std::map<std::string, double> stages;          // prewarp, upload, texmap, other (ms); empty for other families
    std::string image, heatmap, iterations_image;  // paths relative to the page, empty when absent
    std::string base, truth;                       // as ResultMethod's; what the errors are against
    bool curved() const { return is_curved_base(base); }
};

struct SummaryRow {
    std::string source, method_id, method, setting, family;  // source "all": over every source
    double ms, psnr, rmse, iou;
    bool pareto = false;
    std::string base, truth;  // as the rows'
    bool curved() const { return is_curved_base(base); }
};

struct CompareResults {
    std::string title, machine;
    int image_width = 0, image_height = 0, threads = 0;
    bool quick = false;
    std::vector<ResultSource> sources;
    std::vector<ResultView> views;
    std::vector<ResultMethod> methods;
    std::map<std::string, std::map<std::string, std::map<std::string, std::string>>> truths;  // source, view, name
    std::vector<ResultRow> rows;
    std::vector<SummaryRow> summary;

    const ResultRow* row(const std::string& source, const std::string& view, const std::string& method_id) const;
    // The summary rows of `source` on `base` ("flat", "curved", "sphere"; empty in the file: flat), in the file's
    // order.
    std::vector<SummaryRow> summary_of(const std::string& source, const std::string& base = "flat") const;
};

// Throws std::invalid_argument naming the field when `j` is not an object or a field has the wrong type.
CompareResults parse_compare_results(const nlohmann::json& j);

}  // namespace rtm
