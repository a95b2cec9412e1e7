// rtm diff: error of a rendering against a reference (measure/image_diff.h). Prints one "name value" line per
// figure: psnr, rmse, iou, max_error and the coverage counts. Non-finite values print as inf / nan; JSON has no
// such numbers, so there psnr of identical images is the string "inf" and an undefined value (no pixel covered in
// both images) is null.
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli_common.h"
#include "measure/image_diff.h"
#include "formats/image_io.h"

namespace rtm::cli {

namespace {

struct DiffArgs {
    std::string ref, test, heatmap, json;
};

nlohmann::json number(double x) {
    if (std::isfinite(x)) return x;
    if (x > 0) return "inf";
    return nullptr;
}

void run_diff(const DiffArgs& a) {
    // Both outputs checked before any work: a failure leaves neither (docs/FORMATS.md, "Exit status and errors").
    if (!a.heatmap.empty()) check_output_file(a.heatmap, "--heatmap");
    if (!a.json.empty()) check_output_file(a.json, "--json");
    const ImageRGBA8 ref = read_rgba8(a.ref);  // IoError naming the file: exit 1
    const ImageRGBA8 test = read_rgba8(a.test);
    if (ref.width != test.width || ref.height != test.height)
        throw IoError(a.test + ": image is " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                      " but the reference " + a.ref + " is " + std::to_string(ref.width) + "x" +
                      std::to_string(ref.height));
    ImageRGBA8 heat;
    const DiffResult d = diff_images(ref, test, a.heatmap.empty() ? nullptr : &heat);
    if (!a.heatmap.empty()) write_rgba8(a.heatmap, heat);
    if (!a.json.empty()) {
        write_json(a.json, {
                               {"command", "diff"},
                               {"reference", a.ref},
                               {"test", a.test},
                               {"width", ref.width},
                               {"height", ref.height},
                               {"psnr", number(d.psnr)},
                               {"rmse", number(d.rmse)},
                               {"iou", number(d.iou)},
                               {"max_error", number(d.max_error)},
                               {"covered_both", d.both},
                               {"covered_either", d.either},
                               {"only_ref", d.only_ref},
                               {"only_test", d.only_test},
                           });
    }
    std::printf(
        "psnr %.6g\nrmse %.6g\niou %.6g\nmax_error %.6g\ncovered_both %lld\ncovered_either %lld\n"
        "only_ref %lld\nonly_test %lld\n",
        d.psnr, d.rmse, d.iou, d.max_error, d.both, d.either, d.only_ref, d.only_test);
}

}  // namespace

void add_diff_command(CLI::App& app) {
    auto a = std::make_shared<DiffArgs>();
    CLI::App* sub = app.add_subcommand(
        "diff", "PSNR and RMSE over pixels covered in both images, coverage IoU (background: opaque black)");
    sub->add_option("REF", a->ref, "Reference image")->required();
    sub->add_option("TEST", a->test, "Image compared with the reference")->required();
    sub->add_option("--heatmap", a->heatmap,
                    "Write a heat map: blue only in REF, red only in TEST, grey (equal) to yellow (>= 64 levels)");
    sub->add_option("--json", a->json, "Write the figures as JSON");
    sub->callback([a] { run_diff(*a); });
}

}  // namespace rtm::cli
