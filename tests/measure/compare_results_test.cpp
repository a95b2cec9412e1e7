// The comparison's result files (measure/compare.h) from a synthetic run: the summary's means, medians and Pareto
// marks, null for undefined figures, and the CSV's columns and quoting.
#include <gtest/gtest.h>

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
    const CompareEntry* ray = &sweep.back();    // "raycast"
    const CompareEntry* tp = &sweep[1];         // "two-pass:tables"
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

}  // namespace
}  // namespace rtm
