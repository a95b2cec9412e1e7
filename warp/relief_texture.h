// A relief texture: a parallel-projection image with one orthogonal displacement per texel (paper section 3.1).
//
// Geometry (docs/FORMATS.md): the 3-D point of texel centre (u, v) is
//     X(u, v) = origin + a*u + b*v + f*displ(u, v),   f = normalize(cross(a, b)).
// Texel (i, row) -- column i, row counted from the TOP of the image -- has its centre at u = i + 0.5,
// v = (h - 1 - row) + 0.5. The relief quad has corners origin, origin + a*w, origin + a*w + b*h, origin + b*h.
//
// Storage: colour and the 8-bit quantized displacement index live together in one 4-byte texel (cache
// coherence, as the paper keeps the index in the alpha channel). Index 255 marks an empty texel. The exact
// displacement (world units) is kept beside it for the --exact path and for ground truth.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "image.h"
#include "shared_array.h"

namespace rtm {

inline constexpr uint8_t kEmptyIndex = 255;
inline constexpr int kQuantLevels = 255;
inline constexpr uint8_t kBreakRight = 1;
inline constexpr uint8_t kBreakUp = 2;  // indices 0..254 carry displacement

struct ReliefTexel {
    uint8_t r = 0, g = 0, b = 0;
    uint8_t q = kEmptyIndex;  // quantized displacement index, 255 = empty
    friend bool operator==(const ReliefTexel&, const ReliefTexel&) = default;
};

// Uniform 8-bit quantization of displacement: index q in 0..254 decodes to min + q*qs, qs = (max - min)/254.
// Index 254 decodes to max exactly (no rounding drift) and max == min is legal (every texel gets index 0).
struct Quantizer {
    double min = 0.0;
    double max = 0.0;
    double qs = 0.0;

    static Quantizer from_range(double min, double max);
    // Nearest level (round to nearest, so |displ - decode(encode(displ))| <= qs/2; the paper truncates).
    uint8_t encode(double displ) const;
    double decode(uint8_t q) const;
    std::string to_string() const;
};

struct ReliefGeometry {
    glm::dvec3 origin{0.0};
    glm::dvec3 a{1.0, 0.0, 0.0};
    glm::dvec3 b{0.0, 1.0, 0.0};

    glm::dvec3 f() const;  // unit normal, normalize(cross(a, b))
    // Returns an empty string when a, b and origin describe a usable plane; otherwise what is wrong.
    std::string validate() const;
    std::string to_string() const;
};

struct ReliefTexture {
    int width = 0;
    int height = 0;
    ReliefGeometry geometry;
    Quantizer quant;
    // The arrays below are shared between copies of a ReliefTexture until one is changed (SharedArray).
    SharedArray<ReliefTexel> texels;  // row-major, row 0 = top
    SharedArray<float> displacement;  // exact displacement in world units, same layout (undefined where empty)
    // Surface discontinuities (paper section 4.1.1), filled by mark_discontinuities: bit kBreakRight means "not
    // connected to the texel on the right", kBreakUp "not connected to the texel above" (v + 1, storage row - 1).
    // Empty when no discontinuity handling is wanted.
    SharedArray<uint8_t> breaks;
    double discontinuity_threshold = 0.0;  // world units; 0 = none

    const ReliefTexel& texel(int x, int row) const { return texels[size_t(row) * size_t(width) + size_t(x)]; }
    float displ(int x, int row) const { return displacement[size_t(row) * size_t(width) + size_t(x)]; }
    bool empty_at(int x, int row) const { return texel(x, row).q == kEmptyIndex; }
    // World position of texel (x, row) with its exact displacement.
    glm::dvec3 point(int x, int row) const;
    std::string to_string() const;
};

// The relief quad's corners in world space: origin, origin + a*w, origin + a*w + b*h, origin + b*h.
std::array<glm::dvec3, 4> quad_corners(const ReliefTexture& t);

// The texels' colours as an image (same layout), alpha 255 where non-empty and 0 where empty.
ImageRGBA8 color_image(const ReliefTexture& t);

// Builds a relief texture from colour (alpha 0 = empty texel) and exact displacement in world units. The
// quantizer's range is `range` (the manifest's displacement_range); values outside it are clamped when
// quantized. Throws std::invalid_argument naming the problem (sizes differ, non-finite values, bad geometry).
ReliefTexture make_relief(const ImageRGBA8& color, const ImageF& displacement, double range_min, double range_max,
                          const ReliefGeometry& geometry);

// Marks every pair of 4-connected non-empty texels whose displacements differ by more than `threshold` (world
// units, > 0) as not connected. A threshold <= 0 clears the marks.
void mark_discontinuities(ReliefTexture& t, double threshold);

}  // namespace rtm
