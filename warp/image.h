// Plain CPU images. Conventions (docs/FORMATS.md): storage is row-major with row 0 the TOP row of the
// picture (the first row of an image file). Relief-texture "v" rows count from the bottom: v-row j is storage
// row h - 1 - j. Pixel (x, row) covers u in [x, x+1), v in [h-1-row, h-row).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rtm {

struct Rgba8 {
    uint8_t r = 0, g = 0, b = 0, a = 0;
    friend bool operator==(const Rgba8&, const Rgba8&) = default;
};

template <class T>
struct Image2D {
    int width = 0;
    int height = 0;
    std::vector<T> pixels;  // row-major, row 0 = top

    Image2D() = default;
    Image2D(int w, int h, T fill = T{}) : width(w), height(h), pixels(size_t(w) * size_t(h), fill) {}
    void resize(int w, int h, T fill = T{}) {
        width = w;
        height = h;
        pixels.assign(size_t(w) * size_t(h), fill);
    }
    T& at(int x, int row) { return pixels[size_t(row) * size_t(width) + size_t(x)]; }
    const T& at(int x, int row) const { return pixels[size_t(row) * size_t(width) + size_t(x)]; }
    T* row(int r) { return pixels.data() + size_t(r) * size_t(width); }
    const T* row(int r) const { return pixels.data() + size_t(r) * size_t(width); }
    bool empty() const { return pixels.empty(); }
    friend bool operator==(const Image2D&, const Image2D&) = default;
};

using ImageRGBA8 = Image2D<Rgba8>;
using ImageF = Image2D<float>;

std::string to_string(const Rgba8& c);

}  // namespace rtm
