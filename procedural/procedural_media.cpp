// Procedural relief textures (see procedural_media.h).
//
// Every generator works in relief coordinates x = (i + 0.5)/size to the right and y = (h - 1 - row + 0.5)/size
// upwards (docs/FORMATS.md: the image shows the surface from +f with a to the right and b up), computes a
// colour and a displacement in world units, and stores the displacement normalized over [range_min, range_max].
// Randomness is a fixed integer hash of texel or cell coordinates, never a global generator, so the same call gives
// the same bytes. Colours get a little baked lighting from the displacement (the paper's relief textures come from
// photographs and renderings, which carry their shading), so the flat colour image reads as a picture of a relief.
#include "procedural/procedural_media.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

namespace rtm {
namespace {

constexpr int kMinSize = 8;
constexpr int kMaxSize = 8192;

void check_size(const char* name, int size) {
    if (size < kMinSize || size > kMaxSize)
        throw std::invalid_argument(std::string("procedural relief \"") + name + "\": size must be " +
                                    std::to_string(kMinSize) + ".." + std::to_string(kMaxSize) + ", found " +
                                    std::to_string(size));
}

// ---- Deterministic noise -------------------------------------------------------------------------------------

uint32_t mix32(uint32_t x) {  // "lowbias32" integer finalizer
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

uint32_t hash3(int x, int y, uint32_t seed) {
    return mix32(uint32_t(x) * 0x9E3779B1U ^ mix32(uint32_t(y) * 0x85EBCA77U ^ mix32(seed + 0x27d4eb2dU)));
}

// Uniform in [0, 1).
double hash01(int x, int y, uint32_t seed) { return double(hash3(x, y, seed) >> 8) * (1.0 / 16777216.0); }

// Smoothly interpolated value noise in [0, 1].
double value_noise(double x, double y, uint32_t seed) {
    const double fx = std::floor(x), fy = std::floor(y);
    const int ix = int(fx), iy = int(fy);
    double tx = x - fx, ty = y - fy;
    tx = tx * tx * (3.0 - 2.0 * tx);
    ty = ty * ty * (3.0 - 2.0 * ty);
    const double v00 = hash01(ix, iy, seed), v10 = hash01(ix + 1, iy, seed);
    const double v01 = hash01(ix, iy + 1, seed), v11 = hash01(ix + 1, iy + 1, seed);
    return (v00 * (1 - tx) + v10 * tx) * (1 - ty) + (v01 * (1 - tx) + v11 * tx) * ty;
}

// Fractal sum of value noise, in [0, 1].
double fbm(double x, double y, uint32_t seed, int octaves = 4) {
    double sum = 0.0, norm = 0.0, amp = 1.0, freq = 1.0;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * value_noise(x * freq, y * freq, seed + uint32_t(o) * 101U);
        norm += amp;
        amp *= 0.5;
        freq *= 2.0;
    }
    return sum / norm;
}

// ---- Colours ---------------------------------------------------------------------------------------------------

struct Rgb {
    double r = 0, g = 0, b = 0;
};
Rgb operator*(Rgb c, double s) { return {c.r * s, c.g * s, c.b * s}; }
Rgb operator+(Rgb a, Rgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
Rgb lerp(Rgb a, Rgb b, double t) { return a * (1.0 - t) + b * t; }

uint8_t to_byte(double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 255.0))); }

double frac(double x) { return x - std::floor(x); }

// ---- Canvas ----------------------------------------------------------------------------------------------------

// A relief under construction: albedo and world-unit displacement per texel.
struct Canvas {
    int size = 0;
    int width = 0, height = 0;
    std::vector<Rgb> albedo;
    std::vector<double> displ;  // world units

    explicit Canvas(int s) : size(s), width(s), height(s), albedo(size_t(s) * size_t(s)), displ(albedo.size()) {}
    double x_of(int i) const { return (i + 0.5) / size; }
    double y_of(int row) const { return (height - 1 - row + 0.5) / size; }
    size_t idx(int i, int row) const { return size_t(row) * size_t(width) + size_t(i); }
    double d_clamped(int i, int row) const {
        return displ[idx(std::clamp(i, 0, width - 1), std::clamp(row, 0, height - 1))];
    }
};

struct Lighting {
    double strength = 1.0;  // 0 = albedo only
    bool shadows = true;
    double shadow_factor = 0.7;
};

// Lambert shading relative to a flat surface (a flat texel keeps its albedo), from the upper left and in front,
// plus hard shadows marched through the height field.
std::vector<double> shading(const Canvas& c, const Lighting& l) {
    std::vector<double> shade(c.albedo.size(), 1.0);
    if (l.strength <= 0.0) return shade;
    const double lx0 = -0.45, ly0 = 0.55, lz0 = 0.70;
    const double ln = std::sqrt(lx0 * lx0 + ly0 * ly0 + lz0 * lz0);
    const double lx = lx0 / ln, ly = ly0 / ln, lz = lz0 / ln;
    const double ambient = 0.45;
    const double flat = ambient + (1.0 - ambient) * lz;
    const double texel = 1.0 / c.size;
    const double dmax = *std::max_element(c.displ.begin(), c.displ.end());
    // Marching towards the light: one texel in the image plane per step, the ray rises `rise` world units.
    const double lxy = std::sqrt(lx * lx + ly * ly);
    const double sx = lx / lxy, sy = ly / lxy, rise = texel * lz / lxy;
    for (int row = 0; row < c.height; ++row) {
        for (int i = 0; i < c.width; ++i) {
            // Central differences in world units; y is up, so "up" is row - 1.
            const double dx = (c.d_clamped(i + 1, row) - c.d_clamped(i - 1, row)) / (2 * texel);
            const double dy = (c.d_clamped(i, row - 1) - c.d_clamped(i, row + 1)) / (2 * texel);
            const double nn = std::sqrt(dx * dx + dy * dy + 1.0);
            const double ndotl = std::max(0.0, (-dx * lx - dy * ly + lz) / nn);
            double s = (ambient + (1.0 - ambient) * ndotl) / flat;
            if (l.shadows) {
                const double d0 = c.displ[c.idx(i, row)];
                for (int t = 1;; ++t) {
                    const double ray = d0 + t * rise;
                    if (ray > dmax) break;
                    const int si = int(std::lround(i + t * sx)), sr = int(std::lround(row - t * sy));
                    if (si < 0 || si >= c.width || sr < 0 || sr >= c.height) break;
                    if (c.displ[c.idx(si, sr)] > ray + 0.25 * texel) {
                        s *= l.shadow_factor;
                        break;
                    }
                }
            }
            shade[c.idx(i, row)] = 1.0 + l.strength * (s - 1.0);
        }
    }
    return shade;
}

// Bakes lighting, normalizes displacement and fills in the geometry (quad centred on the world origin, about one
// world unit wide, texel spacing 1/size).
ProceduralRelief finish(const char* name, const Canvas& c, double range_min, double range_max, const Lighting& l) {
    ProceduralRelief p;
    p.name = name;
    p.range_min = range_min;
    p.range_max = range_max;
    const double t = 1.0 / c.size;
    p.geometry.origin = {-0.5 * c.width * t, -0.5 * c.height * t, 0.0};
    p.geometry.a = {t, 0.0, 0.0};
    p.geometry.b = {0.0, t, 0.0};
    const std::vector<double> shade = shading(c, l);
    p.color.resize(c.width, c.height);
    p.displacement.resize(c.width, c.height);
    const double span = range_max - range_min;
    for (size_t k = 0; k < c.albedo.size(); ++k) {
        const Rgb col = c.albedo[k] * shade[k];
        p.color.pixels[k] = {to_byte(col.r), to_byte(col.g), to_byte(col.b), 255};
        const double n = span > 0.0 ? (c.displ[k] - range_min) / span : 0.0;
        p.displacement.pixels[k] = float(std::clamp(n, 0.0, 1.0));
    }
    return p;
}

}  // namespace

// ---- Bricks (paper Figure 21) -------------------------------------------------------------------------------------
//
// Running bond, 6 bricks per course and 16 courses, so the texture tiles. Brick faces have displacement exactly 0
// (range [-0.04, 0], normalized 1.0, which decodes to 0.0 exactly); mortar joints are recessed with a step at the
// brick edge and a rounded (concave) profile down to -0.04 at the joint's centre line.
ProceduralRelief make_brick_wall(int size) {
    check_size("bricks", size);
    constexpr double kMin = -0.04, kMax = 0.0;
    constexpr int kBricksPerCourse = 6;
    constexpr double kCourse = 1.0 / 16.0, kLength = 1.0 / kBricksPerCourse;
    constexpr double kHalfJoint = 0.0075;
    Canvas c(size);
    const Rgb mortar{178, 174, 166};
    for (int row = 0; row < c.height; ++row) {
        for (int i = 0; i < c.width; ++i) {
            const double x = c.x_of(i), y = c.y_of(row);
            const double cy = y / kCourse;
            const int course = int(std::floor(cy));
            const double fy = (cy - course) * kCourse;
            const double offset = (course & 1) ? 0.5 * kLength : 0.0;
            const double cx = (x + offset) / kLength;
            const int brick = int(std::floor(cx));
            const double fx = (cx - brick) * kLength;
            const double s = std::min({fx, kLength - fx, fy, kCourse - fy});  // distance to the joint's centre line
            Rgb col;
            double d;
            if (s >= kHalfJoint) {
                // One brick: its own body colour, a little mottling, occasional darker (over-fired) bricks.
                const int id = ((brick % kBricksPerCourse) + kBricksPerCourse) % kBricksPerCourse;
                const double h0 = hash01(id, course, 11), h1 = hash01(id, course, 12), h2 = hash01(id, course, 13);
                Rgb base = lerp(Rgb{168, 72, 48}, Rgb{196, 108, 70}, h0);
                base = lerp(base, Rgb{120, 62, 50}, h1 < 0.15 ? 0.6 : 0.0);
                base = base * (0.9 + 0.2 * h2);
                const double mottle = fbm(x * 48.0, y * 48.0, 21) - 0.5;
                const double grain = hash01(i, row, 22) - 0.5;
                col = base * (1.0 + 0.22 * mottle + 0.08 * grain);
                d = 0.0;
            } else {
                const double t = s / kHalfJoint;  // 0 at the joint's centre, 1 at the brick edge
                const double depth = 0.5 + 0.5 * std::sqrt(std::max(0.0, 1.0 - t * t));
                d = kMin * depth;
                col = mortar * (1.0 + 0.12 * (fbm(x * 90.0, y * 90.0, 31) - 0.5) + 0.06 * (hash01(i, row, 32) - 0.5));
            }
            c.albedo[c.idx(i, row)] = col;
            c.displ[c.idx(i, row)] = d;
        }
    }
    ProceduralRelief p = finish("bricks", c, kMin, kMax, Lighting{0.8, true, 0.72});
    // Brick faces must decode to exactly zero: store exactly 1.0, not a value computed through the division.
    for (size_t k = 0; k < c.displ.size(); ++k)
        if (c.displ[k] == 0.0) p.displacement.pixels[k] = 1.0f;
    return p;
}

// ---- Facade (paper Figures 9 and 12) -----------------------------------------------------------------------------
//
// A two-storey house front: plinth, a recessed door with a protruding frame and a step, windows with white frames,
// shutters, sills and lintels, glass recessed behind the frames, a string course, a stepped cornice with dentils, a
// tiled roof sloping back from the gutter, two dormers protruding from the roof and a chimney. Wall plane at 0.
namespace {

struct FacadeSample {
    Rgb c;
    double d = 0.0;
};

bool in_rect(double x, double y, double x0, double y0, double x1, double y1) {
    return x >= x0 && x < x1 && y >= y0 && y < y1;
}

const Rgb kWallColour{228, 211, 175};
const Rgb kWhite{242, 240, 232};
const Rgb kTrim{232, 226, 210};
const Rgb kStone{152, 148, 140};
const Rgb kShutter{66, 104, 78};
const Rgb kWood{108, 60, 33};
const Rgb kTerracotta{166, 74, 50};

Rgb glass(double x, double y, double y0, double y1) {
    const double t = std::clamp((y - y0) / std::max(1e-9, y1 - y0), 0.0, 1.0);
    Rgb g = lerp(Rgb{34, 46, 64}, Rgb{78, 98, 122}, t);
    // A diagonal reflection streak.
    const double streak = std::exp(-std::pow((frac((x + y) * 9.0) - 0.5) * 6.0, 2.0));
    return g + Rgb{30, 34, 38} * (0.6 * streak);
}

// Window: glass (xc +- gw, y0..y1) behind a white frame, with mullions, shutters, a sill and a lintel.
void window(FacadeSample& s, double x, double y, double xc, double y0, double y1, double gw, bool shutters) {
    constexpr double fw = 0.016;  // frame width
    constexpr double sw = 0.045;  // shutter width
    const double fx0 = xc - gw - fw, fx1 = xc + gw + fw, fy0 = y0 - fw, fy1 = y1 + fw;
    if (shutters && y >= fy0 && y < fy1 && ((x >= fx0 - sw && x < fx0) || (x >= fx1 && x < fx1 + sw))) {
        const double slat = frac((y - fy0) / 0.012);  // louvres, each leaning out at its bottom edge
        const bool edge = x < fx0 - sw + 0.006 || x >= fx1 + sw - 0.006 || (x >= fx0 - 0.006 && x < fx0) ||
                          (x >= fx1 && x < fx1 + 0.006);
        s.d = edge ? 0.016 : 0.010 + 0.004 * (1.0 - slat);
        s.c = kShutter * (edge ? 1.05 : 0.82 + 0.18 * slat);
        return;
    }
    const double ox = 0.012;                                    // sill and lintel overhang beyond the frame
    if (in_rect(x, y, fx0 - ox, fy0 - 0.016, fx1 + ox, fy0)) {  // sill
        s.d = 0.05;
        s.c = kTrim * 0.97;
        return;
    }
    if (in_rect(x, y, fx0 - ox, fy1, fx1 + ox, fy1 + 0.02)) {  // lintel
        s.d = 0.035;
        s.c = kTrim;
        return;
    }
    if (in_rect(x, y, xc - 0.012, fy1 + 0.02, xc + 0.012, fy1 + 0.03)) {  // keystone
        s.d = 0.045;
        s.c = kTrim;
        return;
    }
    if (!in_rect(x, y, fx0, fy0, fx1, fy1)) return;
    if (!in_rect(x, y, xc - gw, y0, xc + gw, y1)) {  // frame
        s.d = 0.025;
        s.c = kWhite;
        return;
    }
    const double ym = y0 + 0.62 * (y1 - y0);
    if (std::abs(x - xc) < 0.005 || std::abs(y - ym) < 0.005) {  // mullions
        s.d = -0.015;
        s.c = kWhite * 0.95;
        return;
    }
    s.d = -0.03;
    s.c = glass(x, y, y0, y1);
}

void door(FacadeSample& s, double x, double y) {
    constexpr double xc = 0.5, hw = 0.06, y0 = 0.06, y1 = 0.33, fw = 0.016;
    if (in_rect(x, y, xc - hw - 0.02, 0.0, xc + hw + 0.02, y0)) {  // step
        s.d = 0.035;
        s.c = kStone * (1.12 + 0.1 * (fbm(x * 60, y * 60, 41) - 0.5));
        return;
    }
    if (!in_rect(x, y, xc - hw - fw, y0, xc + hw + fw, y1 + fw)) return;
    if (!in_rect(x, y, xc - hw, y0, xc + hw, y1)) {  // frame
        s.d = 0.025;
        s.c = kWhite;
        return;
    }
    if (y >= y1 - 0.05) {  // fanlight
        const bool bar = std::abs(y - (y1 - 0.05)) < 0.005 || std::abs(x - xc) < 0.004;
        s.d = bar ? -0.045 : -0.05;
        s.c = bar ? kWhite * 0.92 : glass(x, y, y1 - 0.05, y1);
        return;
    }
    // Door leaf: stiles and rails at -0.04, four panels recessed to -0.046, a brass knob.
    const double grain = fbm(x * 30.0, y * 220.0, 43);
    Rgb wood = kWood * (0.85 + 0.3 * grain);
    const double kx = xc + hw - 0.018, ky = 0.19;
    if ((x - kx) * (x - kx) + (y - ky) * (y - ky) < 0.006 * 0.006) {
        s.d = -0.03;
        s.c = Rgb{205, 172, 72};
        return;
    }
    const double lx = x - (xc - hw), ly = y - y0, lw = 2 * hw, lh = (y1 - 0.05) - y0;
    const double m = 0.018;
    const bool panel_x = (lx > m && lx < lw / 2 - m / 2) || (lx > lw / 2 + m / 2 && lx < lw - m);
    const bool panel_y = (ly > m && ly < lh * 0.45 - m / 2) || (ly > lh * 0.45 + m / 2 && ly < lh - m);
    if (panel_x && panel_y) {
        s.d = -0.046;
        s.c = wood * 0.9;
    } else {
        s.d = -0.04;
        s.c = wood;
    }
}

void dormer(FacadeSample& s, double x, double y, double xc) {
    constexpr double hw = 0.07, y0 = 0.79, y1 = 0.90, apex = 0.955, over = 0.085, board = 0.012;
    const Rgb cladding = kWallColour * 0.96;
    if (y >= y1 && y < apex) {  // gable
        const double half = over * (apex - y) / (apex - y1);
        const double ax = std::abs(x - xc);
        if (ax >= half) return;
        // Barge boards: the band just inside the gable's sloping edges (measured across the edge).
        const double slope_len = std::sqrt(over * over + (apex - y1) * (apex - y1));
        const double dist = (half - ax) * (apex - y1) / slope_len;
        if (dist < board) {
            s.d = 0.12;
            s.c = kWhite * 0.96;
        } else {
            s.d = 0.11;
            s.c = cladding * (0.97 + 0.06 * fbm(x * 80, y * 80, 51));
        }
        return;
    }
    if (!in_rect(x, y, xc - hw, y0, xc + hw, y1)) return;
    constexpr double gw = 0.035, gy0 = 0.805, gy1 = 0.88, fw = 0.01;
    s.d = 0.11;
    s.c = cladding * (0.97 + 0.06 * fbm(x * 80, y * 80, 51));
    if (in_rect(x, y, xc - gw - fw, gy0 - fw, xc + gw + fw, gy1 + fw)) {
        if (!in_rect(x, y, xc - gw, gy0, xc + gw, gy1)) {
            s.d = 0.115;
            s.c = kWhite;
        } else if (std::abs(x - xc) < 0.004 || std::abs(y - 0.5 * (gy0 + gy1)) < 0.004) {
            s.d = 0.095;
            s.c = kWhite * 0.95;
        } else {
            s.d = 0.085;
            s.c = glass(x, y, gy0, gy1);
        }
    }
}

FacadeSample facade_sample(double x, double y) {
    FacadeSample s;
    // Wall: stucco with a little low-frequency staining and fine grain.
    s.c = kWallColour * (0.95 + 0.08 * (fbm(x * 12, y * 12, 61) - 0.5) * 2 + 0.05 * (fbm(x * 120, y * 120, 62) - 0.5));
    s.d = 0.0;
    if (y < 0.06) {  // plinth with a capping course
        s.d = y >= 0.052 ? 0.016 : 0.012;
        s.c = kStone * (0.92 + 0.18 * (fbm(x * 40, y * 40, 63) - 0.5) * 2);
    }
    if (in_rect(x, y, 0.0, 0.385, 1.0, 0.40)) {  // string course between the storeys
        s.d = 0.015;
        s.c = kTrim;
    }
    // Ground floor: two windows and the door; first floor: three windows.
    window(s, x, y, 0.2, 0.13, 0.31, 0.055, true);
    window(s, x, y, 0.8, 0.13, 0.31, 0.055, true);
    door(s, x, y);
    for (double xc : {0.2, 0.5, 0.8}) window(s, x, y, xc, 0.46, 0.63, 0.055, true);
    // Cornice: dentils, then three steps out, then the gutter.
    if (in_rect(x, y, 0.0, 0.685, 1.0, 0.70) && frac(x / 0.025) < 0.5) {
        s.d = 0.02;
        s.c = kTrim * 0.97;
    }
    if (y >= 0.70 && y < 0.745) {
        const int step = std::min(2, int((y - 0.70) / 0.015));
        s.d = 0.03 + 0.02 * step;
        s.c = kTrim * (0.94 + 0.03 * step);
    }
    if (y >= 0.745 && y < 0.76) {  // half-round gutter
        const double t = (y - 0.745) / 0.015;
        s.d = 0.10 + 0.02 * std::sin(std::numbers::pi * t);
        s.c = Rgb{92, 86, 80};
    }
    if (y >= 0.76) {
        // Roof: slopes back from +0.10 at the eaves to -0.04 at the top; each row of tiles leans out at its lower
        // edge. Tiles staggered per row, each with its own shade.
        const double ty = (y - 0.76) / 0.02;
        const int trow = int(std::floor(ty));
        const double tv = ty - trow;
        const double tx = x / 0.03 + ((trow & 1) ? 0.5 : 0.0);
        const int tcol = int(std::floor(tx));
        s.d = 0.10 - (y - 0.76) / 0.24 * 0.14 + 0.008 * (1.0 - tv);
        const double shade = 0.85 + 0.25 * hash01(tcol, trow, 71);
        const bool gap = frac(tx) < 0.08;
        s.c = kTerracotta * (shade * (gap ? 0.7 : 1.0) * (0.96 + 0.08 * fbm(x * 150, y * 150, 72)));
        if (y >= 0.975) {  // ridge tiles
            s.d += 0.01;
            s.c = kTerracotta * 0.8;
        }
        // Chimney: stands out of the roof, brick with mortar lines, a stone cap.
        if (in_rect(x, y, 0.84, 0.86, 0.91, 1.0)) {
            s.d = 0.07;
            const double by = (y - 0.86) / 0.014;
            const double bx = (x - 0.84) / 0.024 + ((int(std::floor(by)) & 1) ? 0.5 : 0.0);
            const bool joint = frac(by) < 0.18 || frac(bx) < 0.08;
            s.c = joint ? Rgb{170, 165, 158}
                        : Rgb{150, 66, 46} * (0.9 + 0.2 * hash01(int(std::floor(bx)), int(by), 73));
            if (y >= 0.975) {
                s.d = 0.08;
                s.c = kStone * 1.1;
            }
        }
        dormer(s, x, y, 0.3);
        dormer(s, x, y, 0.68);
    }
    return s;
}

}  // namespace

ProceduralRelief make_shifted_brick_wall(int size, double shift) {
    ProceduralRelief p = make_brick_wall(size);
    p.range_min += shift;
    p.range_max += shift;
    return p;
}

ProceduralRelief make_facade(int size) {
    check_size("facade", size);
    Canvas c(size);
    for (int row = 0; row < c.height; ++row) {
        for (int i = 0; i < c.width; ++i) {
            const FacadeSample s = facade_sample(c.x_of(i), c.y_of(row));
            c.albedo[c.idx(i, row)] = s.c;
            c.displ[c.idx(i, row)] = s.d;
        }
    }
    return finish("facade", c, -0.05, 0.12, Lighting{0.9, true, 0.7});
}

// ---- Bumps ---------------------------------------------------------------------------------------------------------
//
// A smooth height field (a few Gaussian bumps over a gentle sine swell) in [0, 0.15], coloured by a smooth colour
// ramp across the quad times an 8x8 checker so that parallax shows.
ProceduralRelief make_bumps(int size) {
    check_size("bumps", size);
    struct Bump {
        double x, y, sigma, amp;
    };
    static constexpr Bump kBumps[] = {{0.25, 0.30, 0.09, 1.0},  {0.70, 0.25, 0.08, 0.8},  {0.50, 0.62, 0.12, 1.0},
                                      {0.18, 0.78, 0.07, 0.7},  {0.82, 0.75, 0.085, 0.9}, {0.42, 0.10, 0.05, 0.5},
                                      {0.92, 0.45, 0.05, 0.55}, {0.08, 0.50, 0.05, 0.45}};
    Canvas c(size);
    double lo = 1e300, hi = -1e300;
    std::vector<double> h(c.albedo.size());
    for (int row = 0; row < c.height; ++row) {
        for (int i = 0; i < c.width; ++i) {
            const double x = c.x_of(i), y = c.y_of(row);
            double v = 0.18 * (std::sin(2 * std::numbers::pi * (2 * x + 0.1)) *
                                   std::sin(2 * std::numbers::pi * (1.5 * y + 0.2)) +
                               1.0);
            for (const Bump& b : kBumps) {
                const double r2 = (x - b.x) * (x - b.x) + (y - b.y) * (y - b.y);
                v += b.amp * std::exp(-r2 / (2 * b.sigma * b.sigma));
            }
            h[c.idx(i, row)] = v;
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    const Rgb bl{40, 120, 170}, br{235, 140, 50}, tl{140, 70, 175}, tr{175, 205, 60};
    for (int row = 0; row < c.height; ++row) {
        for (int i = 0; i < c.width; ++i) {
            const double x = c.x_of(i), y = c.y_of(row);
            const double n = (h[c.idx(i, row)] - lo) / (hi - lo);
            const Rgb ramp = lerp(lerp(bl, br, x), lerp(tl, tr, x), y);
            const bool dark = ((int(std::floor(x * 8)) + int(std::floor(y * 8))) & 1) != 0;
            c.albedo[c.idx(i, row)] = ramp * (dark ? 0.62 : 1.0);
            c.displ[c.idx(i, row)] = 0.15 * n;
        }
    }
    // No cast shadows: on a smooth field their hard edges read as blotches rather than as relief.
    return finish("bumps", c, 0.0, 0.15, Lighting{0.8, false, 1.0});
}

// ---- Ridges -------------------------------------------------------------------------------------------------------
//
// Eight sharp triangular ridges running along y (crest 0.3, trough 0; slope 4.8), tall enough to fold over when
// seen obliquely. Each ridge has its own hue; its left and right faces differ in tone, brightness rises with height
// and horizontal bands every 1/16 show how texels move.
ProceduralRelief make_ridges(int size) {
    check_size("ridges", size);
    constexpr double kPeriod = 1.0 / 8.0, kHeight = 0.3;
    static const Rgb kHues[] = {{215, 70, 60},  {230, 160, 40}, {120, 180, 60}, {40, 160, 150},
                                {60, 110, 210}, {150, 80, 200}, {210, 90, 150}, {200, 200, 80}};
    Canvas c(size);
    for (int row = 0; row < c.height; ++row) {
        for (int i = 0; i < c.width; ++i) {
            const double x = c.x_of(i), y = c.y_of(row);
            const double px = x / kPeriod;
            const int ridge = int(std::floor(px));
            const double t = px - ridge;
            const double n = 1.0 - std::abs(2.0 * t - 1.0);  // 0 at troughs, 1 at the crest
            const Rgb hue = kHues[((ridge % 8) + 8) % 8];
            const Rgb face = t < 0.5 ? hue : lerp(hue, Rgb{40, 50, 90}, 0.45);
            const bool band = (int(std::floor(y * 16)) & 1) != 0;
            c.albedo[c.idx(i, row)] = face * ((0.55 + 0.45 * n) * (band ? 0.78 : 1.0));
            c.displ[c.idx(i, row)] = kHeight * n;
        }
    }
    return finish("ridges", c, 0.0, kHeight, Lighting{0.35, false, 1.0});
}

// ---- Dispatch ------------------------------------------------------------------------------------------------------

namespace {

// The procedural reliefs by name: the one table of their names.
struct NamedRelief {
    const char* name;
    ProceduralRelief (*make)(int size);
};
constexpr NamedRelief kProcedural[] = {
    {"bricks", make_brick_wall},
    {"facade", make_facade},
    {"bumps", make_bumps},
    {"ridges", make_ridges},
};

}  // namespace

std::vector<std::string> procedural_names() {
    std::vector<std::string> out;
    for (const NamedRelief& r : kProcedural) out.push_back(r.name);
    return out;
}

std::string procedural_names_list() {
    std::string out;
    for (const NamedRelief& r : kProcedural) out += (out.empty() ? "" : ", ") + std::string(r.name);
    return out;
}

ProceduralRelief make_procedural(const std::string& name, int size) {
    for (const NamedRelief& r : kProcedural)
        if (name == r.name) return r.make(size);
    throw std::invalid_argument("unknown procedural relief \"" + name + "\"; known: " + procedural_names_list());
}

ReliefTexture to_relief(const ProceduralRelief& p) {
    // Same mapping as load_relief: world = min + n*(max - min), in double, stored as float.
    ImageF world(p.displacement.width, p.displacement.height);
    const double span = p.range_max - p.range_min;
    for (size_t k = 0; k < world.pixels.size(); ++k)
        world.pixels[k] = float(p.range_min + double(p.displacement.pixels[k]) * span);
    return make_relief(p.color, world, p.range_min, p.range_max, p.geometry);
}

}  // namespace rtm
