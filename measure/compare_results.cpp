#include "measure/compare_results.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rtm {

using nlohmann::json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void bad(const std::string& where, const std::string& what) {
    throw std::invalid_argument("results.json: " + where + ": " + what);
}

double number(const json& o, const char* key, const std::string& where) {
    const auto it = o.find(key);
    if (it == o.end() || it->is_null()) return kNaN;
    if (!it->is_number()) bad(where + "." + key, "expected a number or null, found " + std::string(it->type_name()));
    return it->get<double>();
}

std::string text(const json& o, const char* key, const std::string& where) {
    const auto it = o.find(key);
    if (it == o.end() || it->is_null()) return {};
    if (!it->is_string()) bad(where + "." + key, "expected a string, found " + std::string(it->type_name()));
    return it->get<std::string>();
}

const json& array(const json& o, const char* key) {
    static const json empty = json::array();
    const auto it = o.find(key);
    if (it == o.end() || it->is_null()) return empty;
    if (!it->is_array()) bad(key, "expected an array, found " + std::string(it->type_name()));
    for (size_t i = 0; i < it->size(); ++i)
        if (!(*it)[i].is_object()) bad(std::string(key) + "[" + std::to_string(i) + "]", "expected an object");
    return *it;
}

}  // namespace

double ResultView::angle_from_normal() const {
    const double rad = std::numbers::pi / 180.0;
    const double c = std::cos(azimuth * rad) * std::cos(elevation * rad);
    return std::acos(std::clamp(c, -1.0, 1.0)) / rad;
}

const ResultRow* CompareResults::row(const std::string& source, const std::string& view,
                                     const std::string& method_id) const {
    for (const ResultRow& r : rows)
        if (r.source == source && r.view == view && r.method_id == method_id) return &r;
    return nullptr;
}

std::vector<SummaryRow> CompareResults::summary_of(const std::string& source, const std::string& base) const {
    std::vector<SummaryRow> out;
    for (const SummaryRow& s : summary)
        if (s.source == source && base_name(s.base) == base) out.push_back(s);
    return out;
}

CompareResults parse_compare_results(const json& j) {
    if (!j.is_object()) bad("top level", "expected an object, found " + std::string(j.type_name()));
    CompareResults r;
    r.title = text(j, "title", "");
    r.machine = text(j, "machine", "");
    if (const auto it = j.find("image_size"); it != j.end() && it->is_array() && it->size() == 2 &&
                                              (*it)[0].is_number_integer() && (*it)[1].is_number_integer()) {
        r.image_width = (*it)[0].get<int>();
        r.image_height = (*it)[1].get<int>();
    }
    if (const auto it = j.find("threads"); it != j.end() && it->is_number_integer()) r.threads = it->get<int>();
    if (const auto it = j.find("quick"); it != j.end() && it->is_boolean()) r.quick = it->get<bool>();
    const json& sources = array(j, "sources");
    for (size_t i = 0; i < sources.size(); ++i) {
        const std::string w = "sources[" + std::to_string(i) + "]";
        const json& s = sources[i];
        const double width = number(s, "width", w), height = number(s, "height", w);
        r.sources.push_back({text(s, "name", w), text(s, "kind", w), text(s, "path", w),
                             std::isfinite(width) ? int(width) : 0, std::isfinite(height) ? int(height) : 0});
    }
    const json& views = array(j, "views");
    for (size_t i = 0; i < views.size(); ++i) {
        const std::string w = "views[" + std::to_string(i) + "]";
        r.views.push_back({text(views[i], "name", w), number(views[i], "azimuth", w), number(views[i], "elevation", w),
                           number(views[i], "distance", w)});
    }
    const json& methods = array(j, "methods");
    for (size_t i = 0; i < methods.size(); ++i) {
        const std::string w = "methods[" + std::to_string(i) + "]";
        const json& m = methods[i];
        r.methods.push_back({text(m, "id", w), text(m, "method", w), text(m, "family", w), text(m, "setting", w),
                             text(m, "base", w)});
    }
    if (const auto it = j.find("truths"); it != j.end() && it->is_object())
        for (const auto& [source, per_view] : it->items()) {
            if (!per_view.is_object()) bad("truths." + source, "expected an object");
            for (const auto& [view, images] : per_view.items()) {
                if (!images.is_object()) bad("truths." + source + "." + view, "expected an object");
                for (const auto& [name, path] : images.items())
                    if (path.is_string()) r.truths[source][view][name] = path.get<std::string>();
            }
        }
    const json& rows = array(j, "rows");
    for (size_t i = 0; i < rows.size(); ++i) {
        const std::string w = "rows[" + std::to_string(i) + "]";
        const json& o = rows[i];
        ResultRow row{text(o, "source", w),
                      text(o, "view", w),
                      text(o, "method_id", w),
                      text(o, "method", w),
                      text(o, "setting", w),
                      text(o, "family", w),
                      number(o, "ms", w),
                      number(o, "psnr", w),
                      number(o, "rmse", w),
                      number(o, "iou", w),
                      number(o, "silhouette_px", w),
                      number(o, "psnr_vs_micromesh", w),
                      number(o, "iou_vs_micromesh", w),
                      number(o, "iterations_mean", w),
                      {},
                      text(o, "image", w),
                      text(o, "heatmap", w),
                      text(o, "iterations_image", w),
                      text(o, "base", w),
                      text(o, "truth", w)};
        if (const auto st = o.find("stages"); st != o.end() && st->is_object())
            for (const auto& [name, v] : st->items())
                if (v.is_number()) row.stages[name] = v.get<double>();
        r.rows.push_back(std::move(row));
    }
    const json& summary = array(j, "summary");
    for (size_t i = 0; i < summary.size(); ++i) {
        const std::string w = "summary[" + std::to_string(i) + "]";
        const json& o = summary[i];
        SummaryRow s{text(o, "source", w), text(o, "method_id", w),
                     text(o, "method", w), text(o, "setting", w),
                     text(o, "family", w), number(o, "ms", w),
                     number(o, "psnr", w), number(o, "rmse", w),
                     number(o, "iou", w),  false,
                     text(o, "base", w),   text(o, "truth", w)};
        if (const auto p = o.find("pareto"); p != o.end() && p->is_boolean()) s.pareto = p->get<bool>();
        r.summary.push_back(std::move(s));
    }
    return r;
}

}  // namespace rtm
