#include "warp/relief_texture.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace rtm {

Quantizer Quantizer::from_range(double min, double max) {
    Quantizer q;
    q.min = min;
    q.max = max;
    q.qs = (max - min) / 254.0;
    return q;
}

uint8_t Quantizer::encode(double displ) const {
    if (!(qs > 0.0)) return 0;  // max == min: one level
    double t = std::round((displ - min) / qs);
    if (!(t >= 0.0)) t = 0.0;  // also catches NaN
    if (t > 254.0) t = 254.0;
    return uint8_t(t);
}

double Quantizer::decode(uint8_t q) const {
    if (q >= 254) return max;  // exact top level; 255 (empty) has no displacement, decode it as max too
    return min + double(q) * qs;
}

std::string Quantizer::to_string() const {
    char buf[128];
    std::snprintf(buf, sizeof buf, "Quantizer{min=%.9g, max=%.9g, qs=%.9g}", min, max, qs);
    return buf;
}

glm::dvec3 ReliefGeometry::f() const { return glm::normalize(glm::cross(a, b)); }

static bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string ReliefGeometry::validate() const {
    if (!finite3(origin)) return "origin is not finite";
    if (!finite3(a)) return "a is not finite";
    if (!finite3(b)) return "b is not finite";
    const double la = glm::length(a), lb = glm::length(b);
    if (!(la > 0.0)) return "a has zero length";
    if (!(lb > 0.0)) return "b has zero length";
    if (!(glm::length(glm::cross(a, b)) > 1e-12 * la * lb)) return "a and b are parallel";
    return {};
}

std::string ReliefGeometry::to_string() const {
    char buf[256];
    std::snprintf(buf, sizeof buf, "ReliefGeometry{origin=(%g,%g,%g), a=(%g,%g,%g), b=(%g,%g,%g)}", origin.x, origin.y,
                  origin.z, a.x, a.y, a.z, b.x, b.y, b.z);
    return buf;
}

glm::dvec3 ReliefTexture::point(int x, int row) const {
    const double u = x + 0.5, v = (height - 1 - row) + 0.5;
    return geometry.origin + geometry.a * u + geometry.b * v + geometry.f() * double(displ(x, row));
}

std::string ReliefTexture::to_string() const {
    std::ostringstream s;
    s << "ReliefTexture{" << width << "x" << height << ", " << geometry.to_string() << ", " << quant.to_string() << "}";
    return s.str();
}

ReliefTexture make_relief(const ImageRGBA8& color, const ImageF& displacement, double range_min, double range_max,
                          const ReliefGeometry& geometry) {
    if (color.width <= 0 || color.height <= 0)
        throw std::invalid_argument("color image is empty (" + std::to_string(color.width) + "x" +
                                    std::to_string(color.height) + ")");
    if (color.width != displacement.width || color.height != displacement.height)
        throw std::invalid_argument("displacement is " + std::to_string(displacement.width) + "x" +
                                    std::to_string(displacement.height) + " but color is " +
                                    std::to_string(color.width) + "x" + std::to_string(color.height));
    if (!std::isfinite(range_min) || !std::isfinite(range_max) || range_min > range_max) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "displacement range [%g, %g] is not a finite interval with min <= max",
                      range_min, range_max);
        throw std::invalid_argument(buf);
    }
    if (std::string why = geometry.validate(); !why.empty()) throw std::invalid_argument("degenerate geometry: " + why);

    ReliefTexture t;
    t.width = color.width;
    t.height = color.height;
    t.geometry = geometry;
    t.quant = Quantizer::from_range(range_min, range_max);
    const size_t n = color.pixels.size();
    std::vector<ReliefTexel>& texels = t.texels.edit();
    std::vector<float>& displ = t.displacement.edit();
    texels.resize(n);
    displ.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const Rgba8 c = color.pixels[i];
        const float d = displacement.pixels[i];
        if (!std::isfinite(d)) {
            const int x = int(i % size_t(t.width)), row = int(i / size_t(t.width));
            throw std::invalid_argument("displacement at texel (" + std::to_string(x) + ", " + std::to_string(row) +
                                        ") is not finite");
        }
        displ[i] = d;
        texels[i] = {c.r, c.g, c.b, c.a == 0 ? kEmptyIndex : t.quant.encode(d)};
    }
    return t;
}

}  // namespace rtm

namespace rtm {

std::array<glm::dvec3, 4> quad_corners(const ReliefTexture& t) {
    const ReliefGeometry& g = t.geometry;
    const glm::dvec3 aw = g.a * double(t.width), bh = g.b * double(t.height);
    return {g.origin, g.origin + aw, g.origin + aw + bh, g.origin + bh};
}

ImageRGBA8 color_image(const ReliefTexture& t) {
    ImageRGBA8 img(t.width, t.height);
    for (int r = 0; r < t.height; ++r)
        for (int x = 0; x < t.width; ++x) {
            const ReliefTexel& tx = t.texel(x, r);
            img.at(x, r) = {tx.r, tx.g, tx.b, uint8_t(tx.q == kEmptyIndex ? 0 : 255)};
        }
    return img;
}

void mark_discontinuities(ReliefTexture& t, double threshold) {
    t.breaks.clear();
    t.discontinuity_threshold = 0.0;
    if (!(threshold > 0.0) || !std::isfinite(threshold)) return;
    t.discontinuity_threshold = threshold;
    std::vector<uint8_t> breaks(t.texels.size(), 0);
    for (int r = 0; r < t.height; ++r)
        for (int x = 0; x < t.width; ++x) {
            uint8_t m = 0;
            const double d = t.displ(x, r);
            if (x + 1 < t.width && std::abs(t.displ(x + 1, r) - d) > threshold) m |= kBreakRight;
            if (r > 0 && std::abs(t.displ(x, r - 1) - d) > threshold) m |= kBreakUp;
            breaks[size_t(r) * size_t(t.width) + size_t(x)] = m;
        }
    t.breaks = std::move(breaks);
}

}  // namespace rtm
