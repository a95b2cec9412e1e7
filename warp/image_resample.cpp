#include "warp/image_resample.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rtm {

namespace {

// The taps of one axis: for each output index, the source indices (clamped to the edge) and their weights.
struct Taps {
    std::vector<int> first, count;
    std::vector<int> index;
    std::vector<double> weight;
};

Taps tent_taps(int n_in, int n_out) {
    Taps t;
    const double s = double(n_in) / double(n_out);
    const double r = std::max(1.0, s);  // bilinear when enlarging, the scale factor when shrinking
    for (int o = 0; o < n_out; ++o) {
        const double c = (o + 0.5) * s - 0.5;  // the output texel's centre in source texel coordinates
        const int lo = int(std::floor(c - r)) + 1, hi = int(std::ceil(c + r)) - 1;
        t.first.push_back(int(t.index.size()));
        double sum = 0.0;
        for (int x = lo; x <= hi; ++x) {
            const double w = 1.0 - std::abs(x - c) / r;
            if (w <= 0.0) continue;
            t.index.push_back(std::clamp(x, 0, n_in - 1));
            t.weight.push_back(w);
            sum += w;
        }
        t.count.push_back(int(t.index.size()) - t.first.back());
        for (size_t k = size_t(t.first.back()); k < t.weight.size(); ++k) t.weight[k] /= sum;
    }
    return t;
}

// Resamples `channels` interleaved double channels of a w x h image to width x height.
std::vector<double> resample(const std::vector<double>& src, int w, int h, int channels, int width, int height) {
    const Taps tx = tent_taps(w, width), ty = tent_taps(h, height);
    std::vector<double> rows(size_t(width) * size_t(h) * size_t(channels), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < width; ++x)
            for (int k = 0; k < tx.count[size_t(x)]; ++k) {
                const size_t tap = size_t(tx.first[size_t(x)] + k);
                const double* s = &src[(size_t(y) * size_t(w) + size_t(tx.index[tap])) * size_t(channels)];
                double* d = &rows[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels)];
                for (int c = 0; c < channels; ++c) d[c] += tx.weight[tap] * s[c];
            }
    std::vector<double> out(size_t(width) * size_t(height) * size_t(channels), 0.0);
    for (int y = 0; y < height; ++y)
        for (int k = 0; k < ty.count[size_t(y)]; ++k) {
            const size_t tap = size_t(ty.first[size_t(y)] + k);
            const double* s = &rows[size_t(ty.index[tap]) * size_t(width) * size_t(channels)];
            double* d = &out[size_t(y) * size_t(width) * size_t(channels)];
            for (size_t i = 0; i < size_t(width) * size_t(channels); ++i) d[i] += ty.weight[tap] * s[i];
        }
    return out;
}

void check(int src_w, int src_h, int width, int height) {
    if (src_w < 1 || src_h < 1) throw std::invalid_argument("resample_tent: the source image is empty");
    if (width < 1 || height < 1)
        throw std::invalid_argument("resample_tent: expected an output size of at least 1x1, found " +
                                    std::to_string(width) + "x" + std::to_string(height));
}

}  // namespace

ImageF resample_tent(const ImageF& src, int width, int height) {
    check(src.width, src.height, width, height);
    const std::vector<double> in(src.pixels.begin(), src.pixels.end());
    const std::vector<double> r = resample(in, src.width, src.height, 1, width, height);
    ImageF out(width, height);
    for (size_t i = 0; i < r.size(); ++i) out.pixels[i] = float(r[i]);
    return out;
}

ImageRGBA8 resample_tent(const ImageRGBA8& src, int width, int height) {
    check(src.width, src.height, width, height);
    std::vector<double> in;
    in.reserve(src.pixels.size() * 4);
    for (const Rgba8& p : src.pixels) in.insert(in.end(), {double(p.r), double(p.g), double(p.b), double(p.a)});
    const std::vector<double> r = resample(in, src.width, src.height, 4, width, height);
    ImageRGBA8 out(width, height);
    auto level = [](double v) { return uint8_t(std::clamp(std::lround(v), 0L, 255L)); };
    for (size_t i = 0; i < out.pixels.size(); ++i)
        out.pixels[i] = {level(r[4 * i]), level(r[4 * i + 1]), level(r[4 * i + 2]), level(r[4 * i + 3])};
    return out;
}

}  // namespace rtm
