#include "perpixel/relief_map.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace rtm {

ImageRGBA8 perpixel_color_texture(const ReliefTexture& t) {
    ImageRGBA8 img(t.width, t.height);
    for (size_t i = 0; i < t.texels.size(); ++i) {
        const ReliefTexel& x = t.texels[i];
        img.pixels[i] = x.q == kEmptyIndex ? Rgba8{} : Rgba8{x.r, x.g, x.b, 255};
    }
    return img;
}

ImageRGBA8 perpixel_relief_map(const ReliefTexture& t) {
    ImageRGBA8 img(t.width, t.height);
    const double sa = glm::length(t.geometry.a), sb = glm::length(t.geometry.b);
    auto usable = [&](int x, int row) {
        return x >= 0 && x < t.width && row >= 0 && row < t.height && !t.empty_at(x, row);
    };
    // Derivative of displacement along one axis: central where both neighbours exist, else one-sided, else 0.
    auto slope = [&](int x, int row, int dx, int drow, double spacing) {
        const bool p = usable(x + dx, row + drow), m = usable(x - dx, row - drow);
        const double c = t.displ(x, row);
        if (p && m) return (t.displ(x + dx, row + drow) - t.displ(x - dx, row - drow)) / (2.0 * spacing);
        if (p) return (t.displ(x + dx, row + drow) - c) / spacing;
        if (m) return (c - t.displ(x - dx, row - drow)) / spacing;
        return 0.0;
    };
    for (int row = 0; row < t.height; ++row)
        for (int x = 0; x < t.width; ++x) {
            Rgba8& out = img.at(x, row);
            const ReliefTexel& tx = t.texel(x, row);
            if (tx.q == kEmptyIndex) {
                out = {128, 128, 255, 254};
                continue;
            }
            // v grows upwards: the texel above (v + 1) is row - 1.
            const double gu = slope(x, row, 1, 0, sa), gv = slope(x, row, 0, -1, sb);
            const glm::dvec3 n = glm::normalize(glm::dvec3(-gu, -gv, 1.0));
            auto enc = [](double c) { return uint8_t(std::lround((c * 0.5 + 0.5) * 255.0)); };
            out = {enc(n.x), enc(n.y), enc(n.z), uint8_t(254 - tx.q)};
        }
    return img;
}

ImageF perpixel_depth_map(const ReliefTexture& t) {
    ImageF img(t.width, t.height);
    const double range = t.quant.max - t.quant.min;
    for (int row = 0; row < t.height; ++row)
        for (int x = 0; x < t.width; ++x) {
            const double d = t.empty_at(x, row) || !(range > 0.0) ? 1.0 : (t.quant.max - t.displ(x, row)) / range;
            img.at(x, row) = float(std::clamp(d, 0.0, 1.0));
        }
    return img;
}

}  // namespace rtm
