#include "formats/height_map.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "formats/image_io.h"
#include "formats/manifest_json.h"
#include "formats/relief_manifest.h"
#include "warp/image_resample.h"

namespace rtm {
namespace {

std::string num(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

}  // namespace

std::string bake_height_map(const HeightBakeOptions& o, const std::string& out_dir) {
    if (o.size && (*o.size < 1 || *o.size > 16384))
        throw std::invalid_argument("--size: expected N texels along the longer side, 1..16384, found " +
                                    std::to_string(*o.size));
    ImageF height = read_gray(o.height_path);
    const int w = height.width, h = height.height;
    for (size_t p = 0; p < height.pixels.size(); ++p) {
        const float v = height.pixels[p];
        if (!(v >= 0.0f && v <= 1.0f))
            throw IoError(o.height_path + ": height " + num(v) + " at texel (" + std::to_string(p % size_t(w)) + ", " +
                          std::to_string(p / size_t(w)) + ") is outside 0..1 (a float image must be " +
                          "normalized; the world range is given by --range)");
    }
    const double texel = o.texel.value_or(1.0 / w);
    if (!(std::isfinite(texel) && texel > 0.0))
        throw std::invalid_argument("--texel: expected a finite size > 0, found " + num(texel));
    const double lo = o.range_min.value_or(0.0);
    const double hi = o.range_max.value_or(lo + 0.1 * texel * w);
    if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
        throw std::invalid_argument("--range: expected MIN,MAX finite with MIN <= MAX, found " + num(lo) + "," +
                                    num(hi));

    ImageRGBA8 color;
    if (!o.color_path.empty()) {
        color = read_rgba8(o.color_path);
        if (color.width != w || color.height != h)
            throw IoError(o.color_path + ": colour image is " + std::to_string(color.width) + "x" +
                          std::to_string(color.height) + " but height map " + o.height_path + " is " +
                          std::to_string(w) + "x" + std::to_string(h));
    }
    // The written size: --size along the longer side, the other in proportion.
    int out_w = w, out_h = h;
    if (o.size) {
        const double scale = double(*o.size) / double(std::max(w, h));
        out_w = w >= h ? *o.size : std::max(1, int(std::lround(w * scale)));
        out_h = h >= w ? *o.size : std::max(1, int(std::lround(h * scale)));
    }
    if (out_w != w || out_h != h) {
        height = resample_tent(height, out_w, out_h);
        if (!color.empty()) color = resample_tent(color, out_w, out_h);
    }
    if (color.empty()) {
        color = ImageRGBA8(out_w, out_h);
        for (size_t p = 0; p < color.pixels.size(); ++p) {
            const auto g = uint8_t(std::lround(height.pixels[p] * 255.0f));
            color.pixels[p] = Rgba8{g, g, g, 255};
        }
    }

    ReliefManifest m;
    m.name = std::filesystem::path(o.height_path).stem().string();
    m.range_min = lo;
    m.range_max = hi;
    m.geometry.origin = glm::dvec3(0.0);
    m.geometry.a = glm::dvec3(texel * w / out_w, 0.0, 0.0);  // the relief keeps its world size
    m.geometry.b = glm::dvec3(0.0, texel * h / out_h, 0.0);
    // What every reader of the manifest checks (formats/relief_manifest.cpp), refused here before anything is written:
    // texel steps whose cross product a double can hold, and displacements a float can hold.
    if (const std::string why = m.geometry.validate(); !why.empty())
        throw std::invalid_argument("--texel: " + num(texel) + " makes texel steps too small or too large for double " +
                                    "precision (" + why + ")");
    if (!std::isfinite(float(lo)) || !std::isfinite(float(hi)) ||
        std::max(std::abs(lo), std::abs(hi)) > manifest_json::kMaxCoordinate)
        throw std::invalid_argument(
            "--range: displacements " + num(lo) + " to " + num(hi) +
            " are beyond the coordinate limit +-1e30 that every reader of the manifest applies" +
            (o.range_max ? "" : "; the default range is a tenth of the width (--texel)"));
    const std::string manifest = (std::filesystem::path(out_dir.empty() ? "." : out_dir) / (m.name + ".relief.json"))
                                     .string();
    write_relief(manifest, m, color, height);
    return manifest;
}

}  // namespace rtm
