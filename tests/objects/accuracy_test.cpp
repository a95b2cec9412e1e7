// Guards the accuracy table of docs/ACCURACY.md: each shipped relief, eight views from frontal to grazing,
// every method against the ray-cast truth at 256x256. The expected figures were measured with this test
// (RTM_PRINT_ACCURACY=1 prints them); a regression of more than the margins below fails CI.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>

#include "measure/compare.h"
#include "formats/relief_manifest.h"

namespace rtm {
namespace {

struct Expect {
    double psnr, iou;  // mean over the eight views, against raycast
};

// Margins: PSNR 0.5 dB and IoU 0.01 below the measured means. Means over 8 views of 65536 pixels move by a
// few hundredths when rasterization changes in the last bit (Mesa version); a real regression (a lost span,
// a wrong order, a missing side polygon) costs whole decibels or several hundredths of IoU.
constexpr double kPsnrMargin = 0.5, kIouMargin = 0.01;

struct ExpectRow {
    const char* media;
    const char* method;
    Expect e;
};
const ExpectRow kRows[] = {
#include "accuracy_expected.inc"
};

std::map<std::string, Expect> expected_for(const std::string& media) {
    std::map<std::string, Expect> m;
    for (const ExpectRow& r : kRows)
        if (media == r.media) m[r.method] = r.e;
    return m;
}

class Accuracy : public ::testing::TestWithParam<std::string> {};

// The method names of accuracy_expected.inc and the sweep entries (measure/compare_sweep.h) they stand for.
const std::map<std::string, std::string> kSweepIds = {
    {"flat", "flat"},
    {"two-pass-no-sidewalls", "two-pass:no-sides"},
    {"two-pass", "two-pass:tables"},
    {"two-pass-exact", "two-pass:exact"},
    {"pipelined", "pipelined:tables"},
    {"micromesh", "micromesh"},
};

TEST_P(Accuracy, MethodsAgainstRaycastTruth) {
    const std::string name = GetParam();
    const auto source = load_relief_source(std::string(RTM_SOURCE_DIR) + "/media/" + name + ".relief.json");
    CompareOptions o;
    o.width = o.height = 256;
    o.repeat = 1;
    std::map<std::string, std::string> name_of;  // sweep id -> table name
    for (const auto& [table, id] : kSweepIds) name_of[id] = table;
    o.methods.clear();
    for (const CompareEntry& e : compare_sweep(false))
        if (name_of.count(e.id)) o.methods.push_back(e);
    ASSERT_EQ(o.methods.size(), kSweepIds.size());
    const CompareRun run = run_comparison({source.get()}, o);
    std::map<std::string, Expect> got;
    std::map<std::string, int> n;
    for (const CompareRow& r : run.rows) {
        const std::string m = name_of.at(r.method_id);
        got[m].psnr += r.error.psnr;
        got[m].iou += r.error.iou;
        ++n[m];
    }
    const bool print = std::getenv("RTM_PRINT_ACCURACY") != nullptr;
    for (auto& [m, e] : got) {
        e.psnr /= n[m];
        e.iou /= n[m];
        if (print) std::printf("{\"%s\", \"%s\", {%.2f, %.4f}},\n", name.c_str(), m.c_str(), e.psnr, e.iou);
    }
    if (print) return;
    const auto want = expected_for(name);
    ASSERT_FALSE(want.empty()) << "no expected figures for " << name << " in accuracy_expected.inc";
    for (const auto& [m, w] : want) {
        ASSERT_TRUE(got.count(m)) << m;
        EXPECT_GE(got[m].psnr, w.psnr - kPsnrMargin) << name << " " << m;
        EXPECT_GE(got[m].iou, w.iou - kIouMargin) << name << " " << m;
    }
    // The claims the table supports: relief texture mapping is far closer to the truth than flat texture
    // mapping, and the side polygons raise coverage.
    EXPECT_GT(got["two-pass"].psnr, got["flat"].psnr + 5) << name;
    EXPECT_GT(got["two-pass"].iou, got["two-pass-no-sidewalls"].iou) << name;
}

INSTANTIATE_TEST_SUITE_P(Media, Accuracy, ::testing::Values("bricks", "facade", "bumps", "ridges"));

}  // namespace
}  // namespace rtm
