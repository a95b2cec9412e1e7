// Error of a rendering against a reference (rtm diff): PSNR and RMSE over the pixels covered in both images
// (a pixel is covered when it is not the opaque-black background, and not fully transparent), coverage IoU (do the
// silhouettes agree?), and a heat map of the per-pixel error (scale and colours: measure/image_diff.cpp).
#pragma once

#include <string>

#include "warp/image.h"

namespace rtm {

struct DiffResult {
    double rmse = 0.0;  // over RGB, 0..255 scale, pixels covered in both; NaN if none (but some in either)
    double psnr = 0.0;  // 20*log10(255/rmse); +infinity when rmse == 0; NaN when rmse is
    double iou = 1.0;   // |covered in both| / |covered in either|; 1 when both are empty
    long long both = 0, either = 0, only_ref = 0, only_test = 0;
    double max_error = 0.0;  // largest per-pixel RGB distance among pixels covered in both
    std::string to_string() const;
};

bool covered(const Rgba8& p);  // not the opaque-black background (0,0,0,255) and alpha != 0
// Throws std::invalid_argument when sizes differ (naming both sizes). `heatmap`, if given, is resized to the size
// of the inputs.
DiffResult diff_images(const ImageRGBA8& ref, const ImageRGBA8& test, ImageRGBA8* heatmap = nullptr);

}  // namespace rtm
