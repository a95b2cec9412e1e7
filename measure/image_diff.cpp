// Error of a rendering against a reference.
//
// Coverage: a pixel is covered unless it is the background, i.e. opaque black (0, 0, 0, 255); a fully transparent
// pixel (alpha 0, e.g. an empty texel of a pre-warped texture) is not covered either. A surface that is truly
// black is therefore counted as background: renders and references share that blind spot, so it cancels.
//
// Per-pixel error e = |rgb_ref - rgb_test| (Euclidean distance over R, G, B in 0..255 levels, alpha ignored);
// rmse = sqrt(sum(e^2) / (3 * both)), i.e. the root mean square over channels; max_error = max(e).
// With nothing covered in either image the images agree: rmse 0, psnr +inf, iou 1. With something covered but
// no pixel covered in both, there is nothing to compare colours over: rmse and psnr are NaN (and iou is 0), so a
// check like "psnr > 30" fails instead of passing.
//
// Heat map (same size as the inputs, opaque):
//   neither covered          black   (0, 0, 0)
//   only the reference       blue    (0, 0, 255)     the test misses surface
//   only the test            red     (255, 0, 0)     the test has surface the reference does not
//   both covered             grey-to-yellow ramp of e: e = 0 is dark grey (64, 64, 64), e >= 64 levels is bright
//                            yellow (255, 255, 0), linear in between, rounded to the nearest level.
#include "measure/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace rtm {

namespace {

constexpr double kHeatFull = 64.0;  // error (levels) mapped to full yellow

Rgba8 heat(double e) {
    const double t = std::min(e / kHeatFull, 1.0);
    const auto mix = [t](double lo, double hi) { return uint8_t(std::lround(lo + (hi - lo) * t)); };
    return {mix(64, 255), mix(64, 255), mix(64, 0), 255};
}

std::string size_str(const ImageRGBA8& img) { return std::to_string(img.width) + "x" + std::to_string(img.height); }

}  // namespace

bool covered(const Rgba8& p) { return p.a != 0 && !(p.r == 0 && p.g == 0 && p.b == 0 && p.a == 255); }

std::string DiffResult::to_string() const {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "DiffResult{psnr=%.6g, rmse=%.6g, iou=%.6g, both=%lld, either=%lld, only_ref=%lld, only_test=%lld, "
                  "max_error=%.6g}",
                  psnr, rmse, iou, both, either, only_ref, only_test, max_error);
    return buf;
}

DiffResult diff_images(const ImageRGBA8& ref, const ImageRGBA8& test, ImageRGBA8* heatmap) {
    if (ref.width != test.width || ref.height != test.height)
        throw std::invalid_argument("image sizes differ: reference is " + size_str(ref) + ", test is " +
                                    size_str(test));
    if (heatmap) heatmap->resize(ref.width, ref.height, Rgba8{0, 0, 0, 255});
    DiffResult d;
    // Integer sum of squares: exact (at most 3 * 255^2 per pixel, far below 2^63 for any image we accept).
    long long sum_sq = 0;
    long long max_sq = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i) {
        const Rgba8 p = ref.pixels[i], q = test.pixels[i];
        const bool cr = covered(p), ct = covered(q);
        if (cr && ct) {
            const int dr = int(p.r) - int(q.r), dg = int(p.g) - int(q.g), db = int(p.b) - int(q.b);
            const long long sq = dr * dr + dg * dg + db * db;
            sum_sq += sq;
            max_sq = std::max(max_sq, sq);
            ++d.both;
            if (heatmap) heatmap->pixels[i] = heat(std::sqrt(double(sq)));
        } else if (cr) {
            ++d.only_ref;
            if (heatmap) heatmap->pixels[i] = {0, 0, 255, 255};
        } else if (ct) {
            ++d.only_test;
            if (heatmap) heatmap->pixels[i] = {255, 0, 0, 255};
        }
    }
    d.either = d.both + d.only_ref + d.only_test;
    d.iou = d.either == 0 ? 1.0 : double(d.both) / double(d.either);
    d.max_error = std::sqrt(double(max_sq));
    if (d.both > 0) {
        d.rmse = std::sqrt(double(sum_sq) / (3.0 * double(d.both)));
        d.psnr = d.rmse == 0.0 ? std::numeric_limits<double>::infinity() : 20.0 * std::log10(255.0 / d.rmse);
    } else if (d.either == 0) {
        d.rmse = 0.0;
        d.psnr = std::numeric_limits<double>::infinity();
    } else {
        d.rmse = d.psnr = std::numeric_limits<double>::quiet_NaN();
    }
    return d;
}

}  // namespace rtm
