// A relief texture from a height map (rtm bake --height): what game and scan assets usually ship. The height
// image's normalized value 0..1 (any single-channel or grey image OpenImageIO reads; the first channel of a
// colour one) maps linearly onto [range_min, range_max] world units along +f; the relief lies in the z = 0 plane
// with origin (0, 0, 0), a = (texel, 0, 0), b = (0, texel, 0), so the image looked at as a picture is the relief
// seen from +z (shared conventions: row 0 is the top, v = h).
#pragma once

#include <optional>
#include <string>

namespace rtm {

struct HeightBakeOptions {
    std::string height_path;
    std::string color_path;           // empty: grey levels from the height
    std::optional<double> range_min;  // default 0
    std::optional<double> range_max;  // default a tenth of the relief's width (texel * width / 10)
    std::optional<double> texel;      // world units per texel of the height image; default 1 / width (one unit wide)
    // Texels along the longer side of the written relief (the other side in proportion, rounded, at least 1): the
    // height map and the colour are resampled with a tent filter (warp/image_resample.h) and the relief keeps its
    // world size (each written texel is `texel * image width / written width` wide). Default: the image's size.
    std::optional<int> size;
};

// Writes DIR/NAME.relief.json with NAME_color.png and NAME_disp.png beside it (NAME: the height image's stem) and
// returns the manifest's path. Throws IoError naming the file and what is wrong (unreadable image, sizes that
// differ, a float image with values outside 0..1), std::invalid_argument for a bad range, texel size or size.
std::string bake_height_map(const HeightBakeOptions& options, const std::string& out_dir);

}  // namespace rtm
