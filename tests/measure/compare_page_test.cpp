// The comparison's page from a synthetic results.json (tests/measure/compare_page_fixture.h): well-formed (a strict
// XML check here, and xmllint when installed), every picture it names exists, one plot point per method id with the
// front's points exactly the `pareto` rows, the reading's numbers, and missing values shown as missing.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include "common/temp_dir.h"
#include "measure/compare_page.h"
#include "measure/compare_page_fixture.h"
#include "measure/compare_reading.h"
#include "measure/compare_results.h"
#include "measure/time_error_plot.h"

namespace rtm {
namespace {

using objects_testing::read_file;
using objects_testing::TempDir;

// Strict well-formedness: every element closed and properly nested (HTML's void elements must be written <x/>),
// attribute values quoted, no '<' in text or attribute values, '&' only as a character reference, CDATA sections
// closed, ids unique. Returns an empty string when the page passes, else the first problem with its offset.
std::string check_well_formed(const std::string& s) {
    std::vector<std::string> open;
    std::set<std::string> ids;
    size_t i = 0;
    auto fail = [&](const std::string& what) { return what + " at offset " + std::to_string(i); };
    auto check_text = [&](size_t from, size_t to) -> std::string {
        for (size_t k = from; k < to; ++k) {
            if (s[k] == '<') return "'<' in text at offset " + std::to_string(k);
            if (s[k] == '&' && !std::regex_search(s.substr(k, 12), std::regex("^&(#[0-9]+|#x[0-9a-fA-F]+|[a-z]+);")))
                return "bare '&' at offset " + std::to_string(k);
        }
        return {};
    };
    while (i < s.size()) {
        const size_t lt = s.find('<', i);
        if (const std::string e = check_text(i, lt == std::string::npos ? s.size() : lt); !e.empty()) return e;
        if (lt == std::string::npos) break;
        i = lt;
        if (s.compare(i, 9, "<!DOCTYPE") == 0) {
            i = s.find('>', i) + 1;
        } else if (s.compare(i, 4, "<!--") == 0) {
            const size_t e = s.find("-->", i);
            if (e == std::string::npos) return fail("unclosed comment");
            i = e + 3;
        } else if (s.compare(i, 9, "<![CDATA[") == 0) {
            const size_t e = s.find("]]>", i);
            if (e == std::string::npos) return fail("unclosed CDATA");
            i = e + 3;
        } else if (s.compare(i, 2, "</") == 0) {
            const size_t e = s.find('>', i);
            const std::string name = s.substr(i + 2, e - i - 2);
            if (open.empty() || open.back() != name)
                return fail("</" + name + "> closes <" + (open.empty() ? "nothing" : open.back()) + ">");
            open.pop_back();
            i = e + 1;
        } else {
            static const std::regex tag(
                R"(^<([a-zA-Z][a-zA-Z0-9]*)((\s+[a-zA-Z_:][-a-zA-Z0-9_:.]*="[^"<]*")*)\s*(/?)>)");
            std::smatch m;
            const std::string rest = s.substr(i, std::min<size_t>(s.size() - i, 20000));
            if (!std::regex_search(rest, m, tag)) return fail("malformed tag '" + rest.substr(0, 40) + "'");
            if (const std::string e = check_text(i + 1, i + m.length(0) - 1); !e.empty() && e[1] == '&') return e;
            static const std::regex id_attr(R"(\sid="([^"]*)\")");
            std::smatch idm;
            const std::string attrs = m[2].str();
            if (std::regex_search(attrs, idm, id_attr) && !ids.insert(idm[1].str()).second)
                return fail("duplicate id '" + idm[1].str() + "'");
            if (m[4].str().empty()) open.push_back(m[1].str());
            i += m.length(0);
        }
    }
    if (!open.empty()) return "unclosed <" + open.back() + ">";
    return {};
}

TEST(ComparePageChecker, CatchesWhatItShould) {
    EXPECT_EQ(check_well_formed("<!DOCTYPE html>\n<html><body><p>a &amp; b<br/></p></body></html>"), "");
    EXPECT_NE(check_well_formed("<html><body><p>a</body></html>"), "");
    EXPECT_NE(check_well_formed("<html><body><img src=x></body></html>"), "");
    EXPECT_NE(check_well_formed("<html><p>a & b</p></html>"), "");
    EXPECT_NE(check_well_formed("<html><p id=\"a\"></p><p id=\"a\"></p></html>"), "");
    EXPECT_NE(check_well_formed("<html><p>1 < 2</p></html>"), "");
    EXPECT_EQ(check_well_formed("<script>//<![CDATA[\nif (a < b && c) {}\n//]]></script>"), "");
}

struct PlotPoint {
    std::string id;
    bool pareto, ringed;
};

// The points of the plot of `source` on `base` ("flat", "curved", "sphere") in the page: <g class="pt" data-id=...
// data-pareto=...> and whether the point carries the front's ring.
std::vector<PlotPoint> plot_points(const std::string& html, const std::string& source,
                                   const std::string& base = "flat") {
    const size_t block = html.find("<div class=\"plot-block\" data-source=\"" + source + "\"" +
                                   (base != "flat" ? " data-base=\"" + base + "\">" : ">"));
    if (block == std::string::npos) return {};
    const std::string svg = html.substr(block, html.find("</svg>", block) - block);
    std::vector<PlotPoint> out;
    static const std::regex pt(R"re(<g class="pt" data-id="([^"]*)" data-pareto="(true|false)"[^>]*>(.*?)</g>)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), pt); it != std::sregex_iterator(); ++it)
        out.push_back({(*it)[1].str(), (*it)[2].str() == "true",
                       (*it)[3].str().find("class=\"front-mark\"") != std::string::npos});
    return out;
}

class ComparePage : public ::testing::Test {
protected:
    void SetUp() override {
        test::write_compare_fixture_page(dir.path().string());
        html = read_file(dir.file("index.html"));
        results = nlohmann::json::parse(read_file(dir.file("results.json")));
    }
    TempDir dir;
    std::string html;
    nlohmann::json results;
};

TEST_F(ComparePage, IsWellFormed) {
    ASSERT_FALSE(html.empty());
    EXPECT_EQ(check_well_formed(html), "");
    if (std::filesystem::exists("/usr/bin/xmllint")) {
        // XML mode: stricter than xmllint --html, whose HTML 4 parser rejects HTML5 and SVG elements.
        const std::string cmd = "/usr/bin/xmllint --noout '" + dir.file("index.html") + "' 2>&1";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }
}

TEST_F(ComparePage, EveryPictureItNamesExists) {
    static const std::regex src(R"re(<img src="([^"]*)")re");
    int n = 0;
    for (auto it = std::sregex_iterator(html.begin(), html.end(), src); it != std::sregex_iterator(); ++it, ++n)
        EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / (*it)[1].str())) << (*it)[1].str();
    // 2 sources x 3 views x (2 truths + 5 methods x 2 pictures + 2 iteration maps, and on each curved base its truth
    // and 2 methods x 3 pictures), and 5 step-by-step pictures.
    EXPECT_EQ(n, 2 * 3 * (2 + 5 * 2 + 2 + 2 * (1 + 2 * 3)) + 5);
    for (const char* f : {"source", "displacement", "horizontal", "prewarped", "frame"})
        EXPECT_NE(html.find(std::string("src=\"steps/") + f + ".png\""), std::string::npos) << f;
}

TEST_F(ComparePage, PlotsHaveOnePointPerMethodIdAndTheFrontIsTheParetoRows) {
    for (const std::string base : {"flat", "curved", "sphere"})
        for (const char* source : {"all", "bumps", "steps"}) {
            SCOPED_TRACE(std::string(source) + " " + base);
            const bool curved = base != "flat";
            std::map<std::string, bool> want;
            for (const auto& s : results["summary"])
                if (s["source"] == source && s["base"] == base)
                    want[s["method_id"].get<std::string>()] = s["pareto"].get<bool>();
            // The flat plot: the 5 flat methods; each curved base's: its 2, kept out of the other plots.
            ASSERT_EQ(want.size(), curved ? 2u : 5u);
            std::map<std::string, bool> got;
            int front = 0;
            for (const PlotPoint& p : plot_points(html, source, base)) {
                EXPECT_TRUE(got.emplace(p.id, p.pareto).second) << "two points for " << p.id;
                EXPECT_EQ(p.ringed, p.pareto) << p.id;
                front += p.pareto;
            }
            EXPECT_EQ(got, want);
            EXPECT_GE(front, 1);
            // The fixture's fronts: flat, parallax, relief-mapping (two-pass and interval lose); on each curved base
            // both (without the quadrics: faster, larger RMSE).
            EXPECT_EQ(front, curved ? 2 : 3);
        }
}

// The per-view grids are collapsible: one <details> per source and view of each base, the first view of each source
// open; each curved base's grids come after its own heading and hold its own truth, never another base's.
TEST_F(ComparePage, ViewGridsCollapseWithTheFirstViewOpen) {
    static const std::regex details(R"re(<details class="view"( open="open")?><summary>([a-z0-9_]+) )re");
    std::vector<std::pair<std::string, bool>> got;
    for (auto it = std::sregex_iterator(html.begin(), html.end(), details); it != std::sregex_iterator(); ++it)
        got.push_back({(*it)[2].str(), (*it)[1].matched});
    const std::vector<std::string> views = {"az00_el00", "az45_el20", "az80_el05"};
    ASSERT_EQ(got.size(), 3u * 2u * 3u);  // 3 bases x 2 sources x 3 views
    for (size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(got[i].first, views[i % 3]) << i;
        EXPECT_EQ(got[i].second, i % 3 == 0) << i;
    }
    const size_t curved = html.find("<section id=\"curved\">");
    ASSERT_NE(curved, std::string::npos);
    const std::string flat_part = html.substr(0, curved), curved_part = html.substr(curved);
    EXPECT_EQ(flat_part.find("curved-micromesh.png"), std::string::npos);
    EXPECT_EQ(flat_part.find("quadric-silhouettes_l8-b2.png"), std::string::npos);
    EXPECT_NE(curved_part.find("curved-micromesh.png"), std::string::npos);
    EXPECT_NE(curved_part.find("quadric-silhouettes_no-quadric-l8-b2_heat.png"), std::string::npos);
    EXPECT_EQ(curved_part.find("/raycast.png"), std::string::npos);
    const size_t cylinder = html.find("<h3 id=\"curved-base\">"), sphere = html.find("<h3 id=\"sphere-base\">");
    ASSERT_NE(cylinder, std::string::npos);
    ASSERT_NE(sphere, std::string::npos);
    ASSERT_LT(cylinder, sphere);
    const std::string cylinder_part = html.substr(cylinder, sphere - cylinder), sphere_part = html.substr(sphere);
    EXPECT_EQ(cylinder_part.find("sphere-micromesh.png"), std::string::npos);
    EXPECT_EQ(cylinder_part.find("sphere-l8-b2"), std::string::npos);
    EXPECT_NE(sphere_part.find("sphere-micromesh.png"), std::string::npos);
    EXPECT_NE(sphere_part.find("quadric-silhouettes_no-quadric-sphere-l8-b2_heat.png"), std::string::npos);
    EXPECT_EQ(sphere_part.find("curved-micromesh.png"), std::string::npos);
}

TEST_F(ComparePage, TheReadingQuotesTheMeasuredValues) {
    const CompareResults r = parse_compare_results(results);
    const std::vector<std::string> reading = compare_reading(r);
    std::string all;
    for (const std::string& p : reading) all += p + "\n";
    SCOPED_TRACE(all);
    // The fixture's front over all sources, fastest first.
    EXPECT_NE(all.find("3 of 5 methods"), std::string::npos);
    EXPECT_NE(all.find("flat (0.840 ms"), std::string::npos);
    // two-pass: the pre-warp stage is 60% of every frame.
    EXPECT_NE(all.find("took a median 60% of the frame time"), std::string::npos);
    // From frontal (0 degrees) to grazing (az80_el05): every method's PSNR falls.
    EXPECT_NE(all.find("az80_el05"), std::string::npos);
    EXPECT_NE(all.find("falls for 5 of 5 methods"), std::string::npos);
    // The missing PSNR and IoU are counted, and never printed as nan.
    EXPECT_NE(all.find("1 without a PSNR"), std::string::npos);
    EXPECT_NE(all.find("1 without an IoU"), std::string::npos);
    // The curved base: the quadrics against the same search without them, from the fixture's IoU (lower by 0.05
    // without the quadrics) and RMSE (5 against 8 at the frontal view, the same factors elsewhere).
    EXPECT_NE(all.find("On the cylinder patch"), std::string::npos);
    EXPECT_NE(all.find("quadric-silhouettes:l8-b2 IoU 0.9600 against 0.9100"), std::string::npos);
    EXPECT_NE(all.find("raised the coverage IoU at 1 of 1 settings"), std::string::npos);
    EXPECT_NE(all.find("the IoU: quadric-silhouettes:l8-b2 0.9200 against 0.8700"), std::string::npos);
    // And the sphere patch, a sentence of its own against its own mesh (the fixture's sphere rows: the same IoU).
    EXPECT_NE(all.find("On the sphere patch (the relief bent over a sphere, every row measured against its curved "
                       "micro-polygon mesh, sphere-micromesh)"),
              std::string::npos);
    EXPECT_NE(all.find("quadric-silhouettes:sphere-l8-b2 IoU 0.9600 against 0.9100"), std::string::npos);
    EXPECT_EQ(all.find("nan"), std::string::npos);
    EXPECT_EQ(html.find(">nan"), std::string::npos);
    EXPECT_EQ(html.find(">-nan"), std::string::npos);
}

TEST(TimeErrorPlot, LeavesOutPointsWithoutTimeOrErrorAndStepsThroughTheFront) {
    std::vector<SummaryRow> rows = {
        {"s", "a", "a", "", "per-pixel", 1.0, 30, 5.0, 1, true, "flat", "raycast"},
        {"s", "b", "b", "", "pre-warp", 4.0, 35, 2.0, 1, true, "flat", "raycast"},
        {"s", "c", "c", "", "per-pixel", 8.0, 32, 3.0, 1, false, "flat", "raycast"},
        {"s", "d", "d", "", "per-pixel", NAN, 32, 3.0, 1, false, "flat", "raycast"},
        {"s", "e", "e", "", "per-pixel", 2.0, NAN, NAN, 1, false, "flat", "raycast"},
    };
    const TimeErrorPlot p = time_error_plot(rows, "p");
    EXPECT_EQ(p.left_out, (std::vector<std::string>{"d", "e"}));
    // The front a (1 ms) then b (4 ms): one step, across then down.
    static const std::regex path(R"re(<path class="front" d="M([0-9.]+) ([0-9.]+) H([0-9.]+) V([0-9.]+)")re");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(p.svg, m, path)) << p.svg;
    EXPECT_LT(std::stod(m[1]), std::stod(m[3]));  // b is right of a (slower)
    EXPECT_GT(std::stod(m[4]), std::stod(m[2]));  // and lower on the page (smaller RMSE)
    EXPECT_EQ(std::count(p.svg.begin(), p.svg.end(), '\n') > 0, true);
    size_t n = 0;
    for (size_t k = p.svg.find("class=\"pt\""); k != std::string::npos; k = p.svg.find("class=\"pt\"", k + 1)) ++n;
    EXPECT_EQ(n, 3u);
}

TEST(CompareResults, AFieldOfTheWrongTypeIsNamed) {
    nlohmann::json j = {{"rows", {{{"source", "s"}, {"ms", "fast"}}}}};
    try {
        parse_compare_results(j);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("rows[0].ms"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parse_compare_results(nlohmann::json::array()), std::invalid_argument);
    EXPECT_THROW(parse_compare_results({{"summary", 3}}), std::invalid_argument);
}

TEST(ComparePageHtml, AnEmptyRunStillGivesAWellFormedPage) {
    const std::string html = compare_page_html(nlohmann::json::object(), "");
    EXPECT_EQ(check_well_formed(html), "");
    EXPECT_NE(html.find("no summary rows"), std::string::npos);
}

}  // namespace
}  // namespace rtm
