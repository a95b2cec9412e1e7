#include "measure/compare_page_fixture.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "formats/image_io.h"
#include "measure/compare_page.h"
#include "objects/bounds.h"
#include "procedural/procedural_media.h"
#include "texmap/camera_rig.h"

namespace rtm::test {

using nlohmann::json;

namespace {

// A 32x32 picture of its own (a gradient whose hue depends on `seed`).
void picture(const std::string& path, int seed) {
    ImageRGBA8 img(32, 32);
    for (int r = 0; r < 32; ++r)
        for (int x = 0; x < 32; ++x)
            img.at(x, r) = {uint8_t(8 * x + 37 * seed), uint8_t(8 * r + 11 * seed), uint8_t(97 * seed), 255};
    write_rgba8(path, img);
}

}  // namespace

json write_compare_fixture(const std::string& dir) {
    const char* sources[] = {"bumps", "steps"};
    struct V {
        const char* name;
        double az, el;
    };
    const V views[] = {{"az00_el00", 0, 0}, {"az45_el20", 45, 20}, {"az80_el05", 80, 5}};
    struct M {
        const char* id;
        const char* method;
        const char* family;
        const char* setting;
        double ms, rmse;  // at the frontal view of "bumps"
        bool iterations;
        const char* base = "flat";  // "curved", "sphere": measured against that base's curved mesh
        bool curved() const { return base != std::string("flat"); }
    };
    const M methods[] = {{"flat", "flat", "conventional", "", 0.8, 30.0, false},
                         {"two-pass", "two-pass", "pre-warp", "", 7.0, 6.0, false},
                         {"parallax", "parallax", "per-pixel", "", 1.0, 20.0, false},
                         {"relief-mapping:16-6", "relief-mapping", "per-pixel", "16-6", 6.0, 4.0, true},
                         {"interval-mapping:8-2", "interval-mapping", "per-pixel", "8-2", 7.0, 4.2, true},
                         {"quadric-silhouettes:l8-b2", "quadric-silhouettes", "per-pixel", "l8-b2", 5.0, 5.0, true,
                          "curved"},
                         {"quadric-silhouettes:no-quadric-l8-b2", "quadric-silhouettes", "per-pixel",
                          "no-quadric-l8-b2", 4.0, 8.0, true, "curved"},
                         {"quadric-silhouettes:sphere-l8-b2", "quadric-silhouettes", "per-pixel", "sphere-l8-b2", 6.0,
                          6.0, true, "sphere"},
                         {"quadric-silhouettes:no-quadric-sphere-l8-b2", "quadric-silhouettes", "per-pixel",
                          "no-quadric-sphere-l8-b2", 5.5, 9.0, true, "sphere"}};
    json j;
    j["title"] = "fixture (2 sources, 3 views, 5 flat methods, 2 on the cylinder, 2 on the sphere)";
    j["image_size"] = {32, 32};
    j["machine"] = "test machine";
    j["threads"] = 2;
    j["quick"] = true;
    for (const char* s : sources)
        j["sources"].push_back({{"name", s},
                                {"kind", "relief"},
                                {"path", std::string(s) + ".relief.json"},
                                {"width", 64},
                                {"height", 64}});
    for (const V& v : views)
        j["views"].push_back({{"name", v.name}, {"azimuth", v.az}, {"elevation", v.el}, {"distance", 2.2}});
    for (const M& m : methods)
        j["methods"].push_back({{"id", m.id},
                                {"method", m.method},
                                {"family", m.family},
                                {"setting", m.setting},
                                {"base", m.base},
                                {"params", json::object()}});
    int seed = 0;
    struct Acc {
        std::vector<double> ms, psnr, rmse, iou;
    };
    std::map<std::string, std::map<std::string, Acc>> acc;  // source ("all" too), method id (ids are unique)
    for (int si = 0; si < 2; ++si) {
        const std::string src = sources[si];
        for (int vi = 0; vi < 3; ++vi) {
            const std::string view = views[vi].name, folder = "img/" + src + "/" + view;
            std::filesystem::create_directories(dir + "/" + folder);
            for (const char* truth : {"raycast", "micromesh", "curved-micromesh", "sphere-micromesh"}) {
                picture(dir + "/" + folder + "/" + truth + ".png", ++seed);
                j["truths"][src][view][truth] = folder + "/" + truth + ".png";
            }
            for (const M& m : methods) {
                const std::string base = folder + "/" + std::string(m.method) +
                                         (m.setting[0] ? std::string("_") + m.setting : "");
                picture(dir + "/" + base + ".png", ++seed);
                picture(dir + "/" + base + "_heat.png", ++seed);
                if (m.iterations) picture(dir + "/" + base + "_iter.png", ++seed);
                // The error grows towards grazing views and on the second source; times do not depend on the view.
                const double rmse = m.rmse * (1 + 0.5 * vi) * (1 + 0.25 * si);
                const double ms = m.ms * (1 + 0.1 * si);
                json row = {{"source", src},
                            {"view", view},
                            {"method_id", m.id},
                            {"method", m.method},
                            {"setting", m.setting},
                            {"family", m.family},
                            {"base", m.base},
                            {"truth", m.curved() ? std::string(m.base) + "-micromesh" : "raycast"},
                            {"ms", ms},
                            {"stages", json::object()},
                            {"psnr", 20 * std::log10(255.0 / rmse)},
                            {"rmse", rmse},
                            {"iou", 1.0 - 0.02 * vi * (m.family == std::string("per-pixel") ? 2 : 1) -
                                        (m.curved() && m.setting[0] == 'n' ? 0.05 : 0.0)},
                            {"silhouette_px", 0.5 + vi * (m.family == std::string("per-pixel") ? 2.0 : 0.7)},
                            {"psnr_vs_micromesh", 20 * std::log10(255.0 / rmse) - 1},
                            {"iou_vs_micromesh", 0.99},
                            {"iterations_mean", m.iterations ? json(m.ms * 3 - vi) : json(nullptr)},
                            {"image", base + ".png"},
                            {"heatmap", base + "_heat.png"},
                            {"iterations_image", m.iterations ? json(base + "_iter.png") : json(nullptr)}};
                if (m.family == std::string("pre-warp"))
                    row["stages"] = {{"prewarp", 0.6 * ms},
                                     {"upload", 0.1 * ms},
                                     {"texmap", 0.2 * ms},
                                     {"other", 0.1 * ms}};
                // Missing values the page must survive: an image identical to the truth has no PSNR; an IoU not
                // measured.
                if (si == 1 && vi == 0 && m.method == std::string("two-pass")) row["psnr"] = nullptr;
                if (si == 1 && vi == 2 && m.method == std::string("parallax")) row.erase("iou");
                for (const std::string& key : {src, std::string("all")}) {
                    Acc& a = acc[key][m.id];
                    a.ms.push_back(ms);
                    a.rmse.push_back(rmse);
                    if (row["psnr"].is_number()) a.psnr.push_back(row["psnr"].get<double>());
                    if (row.contains("iou")) a.iou.push_back(row["iou"].get<double>());
                }
                j["rows"].push_back(row);
            }
        }
    }
    auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (double x : v) s += x;
        return v.empty() ? NAN : s / double(v.size());
    };
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    };
    for (const std::string key : {"bumps", "steps", "all"})
        for (const std::string base : {"flat", "curved", "sphere"}) {  // each base has a Pareto front of its own
            std::vector<json> rows;
            for (const M& m : methods) {
                if (m.base != base) continue;
                const Acc& a = acc[key][m.id];
                rows.push_back({{"source", key},
                                {"method_id", m.id},
                                {"method", m.method},
                                {"setting", m.setting},
                                {"family", m.family},
                                {"base", m.base},
                                {"truth", m.curved() ? std::string(m.base) + "-micromesh" : "raycast"},
                                {"ms", median(a.ms)},
                                {"psnr", mean(a.psnr)},
                                {"rmse", mean(a.rmse)},
                                {"iou", mean(a.iou)}});
            }
            for (json& r : rows) {
                bool dominated = false;
                for (const json& o : rows)
                    dominated |= &o != &r && o["ms"] <= r["ms"] && o["rmse"] <= r["rmse"] &&
                                 (o["ms"] < r["ms"] || o["rmse"] < r["rmse"]);
                r["pareto"] = !dominated;
                j["summary"].push_back(r);
            }
        }
    return j;
}

void write_compare_fixture_page(const std::string& dir) {
    ComparePageInput in;
    in.out_dir = dir;
    in.results = write_compare_fixture(dir);
    std::ofstream(dir + "/results.json") << in.results.dump(1) << "\n";
    ReliefQuad quad(to_relief(make_bumps(64)));
    const Bounds b = relief_bounds(quad.relief());
    in.steps_relief = &quad;
    in.steps_camera = orbit_camera(b.centre(), b.radius(), {10, 8, 1.6}, 128, 128);
    write_compare_page(in);
}

}  // namespace rtm::test
