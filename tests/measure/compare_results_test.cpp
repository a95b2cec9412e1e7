// The comparison's result files (measure/compare.h) from a synthetic run: the summary's means, medians and Pareto
// marks, null for undefined figures, and the CSV's columns and quoting.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "measure/compare.h"

namespace rtm {
namespace {

class FakeSource final : public CompareSource {
public:
    explicit FakeSource(const std::string& n) {
        name = n;
        kind = "relief";
        path = n + ".relief.json";
        width = height = 4;
    }
    Bounds bounds() const override { return {}; }
    bool renders(const CompareEntry&) const override { return true; }
    ImageRGBA8 render(Renderer&, const Camera&, const RenderSettings&, int, StageTimes&) override { return {}; }
};

CompareRow row(const std::string& source, const std::string& view, const CompareEntry& e, double ms, double rmse) {
    CompareRow r;
    r.source = source;
    r.view = view;
    r.method_id = e.id;
    r.method = e.method;
    r.setting = e.setting;
    r.family = e.family;
    r.ms = ms;
    r.error.rmse = rmse;
    r.error.psnr = rmse > 0 ? 20 * std::log10(255 / rmse) : INFINITY;
    r.error.iou = 0.5;
    r.image = "images/" + source + "/" + view + "/x.png";
    return r;
}

TEST(CompareResults, SummaryParetoAndCsv) {
    const std::vector<CompareEntry> sweep = compare_sweep(true);
    const CompareEntry* flat = &sweep.front();  // "flat"
    const CompareEntry* ray = &*std::find_if(sweep.begin(), sweep.end(), [](const CompareEntry& e) {
        return e.id == "raycast";  // the last flat entry; the curved base follows
    });
    const CompareEntry* tp = &sweep[1];  // "two-pass:tables"
    ASSERT_EQ(flat->id, "flat");
    ASSERT_EQ(ray->id, "raycast");
    ASSERT_EQ(tp->id, "two-pass:tables");
    FakeSource a("a"), b("b,\"quoted\"");
    CompareOptions o;
    o.width = 8;
    o.height = 6;
    CompareRun run;
    run.views = {orbit_view(0, 0), orbit_view(45, 20)};
    run.methods = {flat, tp, ray};
    // Source a: flat is fast and wrong, two-pass slower and better, raycast slowest and exact (psnr +inf -> null).
    run.rows = {row("a", "az00_el00", *flat, 1, 20), row("a", "az00_el00", *tp, 2, 10),
                row("a", "az00_el00", *ray, 30, 0),  row("a", "az45_el20", *flat, 3, 22),
                row("a", "az45_el20", *tp, 4, 12),   row("a", "az45_el20", *ray, 50, 0)};
    // Source b: two-pass is both faster and better than flat, so flat is off b's front.
    run.rows.push_back(row(b.name, "az00_el00", *flat, 5, 30));
    run.rows.push_back(row(b.name, "az00_el00", *tp, 1, 5));
    run.rows.back().has_stages = true;
    run.rows.back().stages = {0.25, 0.125, 0.5, 1.0};
    run.rows.push_back(row(b.name, "az00_el00", *ray, 40, 0));
    const nlohmann::json j = comparison_json({&a, &b}, o, run, {{"title", "t"}});
    EXPECT_EQ(j["image_size"], nlohmann::json::array({8, 6}));
    ASSERT_EQ(j["rows"].size(), 9u);
    EXPECT_TRUE(j["rows"][2]["psnr"].is_null());  // identical to the truth: +inf is not JSON
    EXPECT_EQ(j["rows"][7]["stages"]["other"].get<double>(), 0.125);
    EXPECT_TRUE(j["rows"][0]["stages"].empty());
    ASSERT_EQ(j["summary"].size(), 9u);  // 3 methods x (a, b, all)
    const auto& s = j["summary"];
    EXPECT_EQ(s[0]["source"], "a");
    EXPECT_EQ(s[0]["method_id"], "flat");
    EXPECT_DOUBLE_EQ(s[0]["rmse"].get<double>(), 21.0);  // mean over the views
    EXPECT_DOUBLE_EQ(s[0]["ms"].get<double>(), 2.0);     // median of {1, 3}: the mean of the middle two
    EXPECT_TRUE(s[2]["psnr"].is_null());                 // raycast: no finite PSNR
    EXPECT_TRUE(s[0]["pareto"] && s[1]["pareto"] && s[2]["pareto"]);
    EXPECT_EQ(s[3]["source"], b.name);
    EXPECT_FALSE(s[3]["pareto"]);  // flat on b: beaten by two-pass
    EXPECT_TRUE(s[4]["pareto"] && s[5]["pareto"]);
    EXPECT_EQ(s[6]["source"], "all");

    const std::string csv = comparison_csv(j);
    std::istringstream in(csv);
    std::string header, first;
    std::getline(in, header);
    std::getline(in, first);
    EXPECT_EQ(header.rfind("source,view,method_id,method,setting,family,ms,stage_prewarp,", 0), 0u) << header;
    EXPECT_EQ(first.rfind("a,az00_el00,flat,flat,,conventional,1,,,,,", 0), 0u) << first;
    EXPECT_NE(csv.find("\"b,\"\"quoted\"\"\",az00_el00,two-pass:tables"), std::string::npos) << csv;
    size_t lines = 0;
    for (char c : csv) lines += c == '\n';
    EXPECT_EQ(lines, 10u);  // header + 9 rows
}

// The curved bases in the sweep: on the cylinder patch quadric silhouettes at relief mapping's steps, each beside
// the same steps without the quadrics, and its truths, the curved mesh and the curved ray caster (--quick keeps 2
// steps of each); on the sphere patch the default steps with and without the quadrics, and its two truths. Each
// entry's patch is its base's, in its settings and its params.
TEST(CompareSweep, TheCurvedBasePairsEachQuadricSettingWithTheSameStepsWithout) {
    for (bool quick : {false, true}) {
        std::vector<std::string> with, without, truths, relief_mapping, exact, sphere;
        for (const CompareEntry& e : compare_sweep(quick)) {
            if (e.method == "relief-mapping") relief_mapping.push_back(e.setting);
            if (!e.curved()) continue;
            const auto& q = e.render.perpixel.quadric_silhouettes;
            EXPECT_EQ(q.base, e.base == "sphere" ? CurvedShape::sphere : CurvedShape::cylinder) << e.id;
            EXPECT_EQ(e.params.at("patch").at("shape"), e.base == "sphere" ? "sphere" : "cylinder") << e.id;
            EXPECT_EQ(q.rows, e.base == "sphere" ? q.segments : 4) << e.id;  // as rtm render draws each patch
            if (e.family == "truth") {
                truths.push_back(e.id);
                EXPECT_EQ(e.id, e.base + "-" + to_string(e.render.method));
            } else if (e.base == "sphere") {
                EXPECT_EQ(e.render.method, RenderMethod::quadric_silhouettes) << e.id;
                EXPECT_EQ(q.quadric, e.params.at("quadric").get<bool>()) << e.id;
                sphere.push_back(e.setting);
            } else {
                EXPECT_EQ(e.render.method, RenderMethod::quadric_silhouettes) << e.id;
                EXPECT_EQ(e.family, "per-pixel") << e.id;  // iteration counts, as the other searches
                EXPECT_EQ(q.quadric, e.params.at("quadric").get<bool>()) << e.id;
                EXPECT_EQ(q.linear_search_steps, e.params.at("linear_search_steps").get<int>()) << e.id;
                EXPECT_EQ(q.binary_search_steps, e.params.at("binary_search_steps").get<int>()) << e.id;
                EXPECT_EQ(q.exact_distance, e.params.value("exact_distance", false)) << e.id;
                (q.exact_distance ? exact : q.quadric ? with : without).push_back(e.setting);
            }
        }
        EXPECT_EQ(truths, (std::vector<std::string>{"curved-micromesh", "curved-raycast", "sphere-micromesh",
                                                    "sphere-raycast"}));
        EXPECT_EQ(sphere, (std::vector<std::string>{"sphere-l32-b8", "no-quadric-sphere-l32-b8"}));
        EXPECT_EQ(with, relief_mapping);
        ASSERT_EQ(without.size(), with.size());
        for (size_t i = 0; i < with.size(); ++i) EXPECT_EQ(without[i], "no-quadric-" + with[i]);
        EXPECT_EQ(with.size(), quick ? 2u : 4u);
        // The paper's exact distance at the default steps, beside the approximate one at the same steps.
        EXPECT_EQ(exact, (std::vector<std::string>{"exact-l32-b8"}));
        EXPECT_NE(std::find(with.begin(), with.end(), "l32-b8"), with.end());
    }
}

// The curved base is summarized apart: its Pareto front is its own (a different truth), and each row says what it
// is measured against, in results.json and in results.csv's last columns.
TEST(CompareResults, TheCurvedBaseHasAFrontOfItsOwnAndEachRowNamesItsTruth) {
    const std::vector<CompareEntry> sweep = compare_sweep(true);
    auto find = [&](const std::string& id) {
        for (const CompareEntry& e : sweep)
            if (e.id == id) return &e;
        ADD_FAILURE() << "no " << id;
        return &sweep.front();
    };
    const CompareEntry *flat = find("flat"), *ray = find("raycast"), *q = find("quadric-silhouettes:l8-b2"),
                       *nq = find("quadric-silhouettes:no-quadric-l8-b2"), *cm = find("curved-micromesh");
    FakeSource a("a");
    CompareOptions o;
    CompareRun run;
    run.views = {orbit_view(0, 0)};
    run.methods = {flat, ray, q, nq, cm};
    auto add = [&](const CompareEntry* e, double ms, double rmse) {
        run.rows.push_back(row("a", "az00_el00", *e, ms, rmse));
        run.rows.back().base = e->base;
        run.rows.back().truth = e->curved() ? "curved-micromesh" : "raycast";
    };
    // Flat: flat (1 ms, 20) and raycast (30 ms, 0). Curved: quadric (10 ms, 25), without (20 ms, 30), the curved mesh
    // (40 ms, 0). Over one front flat would dominate both quadric rows; on its own the curved base's front is the
    // quadric row and its mesh.
    add(flat, 1, 20);
    add(ray, 30, 0);
    add(q, 10, 25);
    add(nq, 20, 30);
    add(cm, 40, 0);
    const nlohmann::json j = comparison_json({&a}, o, run, {{"title", "t"}});
    ASSERT_EQ(j["summary"].size(), 10u);  // (a, all) x (2 flat + 3 curved)
    const auto& s = j["summary"];
    const char* order[] = {"flat", "raycast", "quadric-silhouettes:l8-b2", "quadric-silhouettes:no-quadric-l8-b2",
                           "curved-micromesh"};
    for (size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(s[i]["source"], "a");
        EXPECT_EQ(s[i]["method_id"], order[i]);
        EXPECT_EQ(s[i]["base"], i < 2 ? "flat" : "curved");
        EXPECT_EQ(s[i]["truth"], i < 2 ? "raycast" : "curved-micromesh");
    }
    EXPECT_TRUE(s[0]["pareto"] && s[1]["pareto"]);  // the flat front: flat, raycast
    EXPECT_TRUE(s[2]["pareto"]);                    // the curved front: quadric (10 ms) and the mesh (40 ms, exact)
    EXPECT_FALSE(s[3]["pareto"]);                   // without the quadrics: slower and worse here
    EXPECT_TRUE(s[4]["pareto"]);
    EXPECT_EQ(j["methods"][2]["base"], "curved");
    EXPECT_EQ(j["rows"][2]["truth"], "curved-micromesh");
    EXPECT_EQ(j["rows"][0]["truth"], "raycast");

    const std::string csv = comparison_csv(j);
    std::istringstream in(csv);
    std::string header, line;
    std::getline(in, header);
    EXPECT_NE(header.find(",iterations_image,base,truth"), std::string::npos) << header;
    std::vector<std::string> lines;
    while (std::getline(in, line)) lines.push_back(line);
    ASSERT_EQ(lines.size(), 5u);
    EXPECT_TRUE(lines[0].ends_with(",flat,raycast")) << lines[0];
    EXPECT_TRUE(lines[3].ends_with(",curved,curved-micromesh")) << lines[3];
}

}  // namespace
}  // namespace rtm
