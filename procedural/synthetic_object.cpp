#include "procedural/synthetic_object.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rtm {

namespace {

struct AaBox {
    glm::dvec3 lo, hi;
    int part;
};

// Slab test: entry distance of the ray into the box, and the axis of the entry face.
bool hit_box(const AaBox& b, const glm::dvec3& o, const glm::dvec3& d, double& t, int& axis) {
    double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
    int ax = -1;
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0) {
            if (o[i] < b.lo[i] || o[i] > b.hi[i]) return false;
            continue;
        }
        double a = (b.lo[i] - o[i]) / d[i], c = (b.hi[i] - o[i]) / d[i];
        if (a > c) std::swap(a, c);
        if (a > t0) {
            t0 = a;
            ax = i;
        }
        t1 = std::min(t1, c);
    }
    if (t0 > t1 || t1 < 0.0) return false;
    t = std::max(t0, 0.0);
    axis = ax < 0 ? 0 : ax;
    return true;
}

const std::vector<AaBox>& cross_box_parts() {
    static const std::vector<AaBox> parts = [] {
        std::vector<AaBox> p;
        p.push_back({glm::dvec3(-0.8), glm::dvec3(0.8), 0});
        for (int axis = 0; axis < 3; ++axis)
            for (int sign = -1; sign <= 1; sign += 2) {
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                for (int arm = 0; arm < 2; ++arm) {
                    glm::dvec3 lo(0.0), hi(0.0);
                    lo[axis] = sign > 0 ? 0.8 : -1.0;
                    hi[axis] = sign > 0 ? 1.0 : -0.8;
                    const int along = arm == 0 ? u : v, across = arm == 0 ? v : u;
                    lo[along] = -0.7;
                    hi[along] = 0.7;
                    lo[across] = -0.15;
                    hi[across] = 0.15;
                    p.push_back({lo, hi, 1 + axis * 2 + (sign > 0)});
                }
            }
        return p;
    }();
    return parts;
}

uint8_t channel(double v) { return uint8_t(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5); }

}  // namespace

SyntheticShape parse_synthetic_shape(const std::string& s) {
    if (s == "sphere") return SyntheticShape::sphere;
    if (s == "cross-box") return SyntheticShape::cross_box;
    if (s == "rounded-cube") return SyntheticShape::rounded_cube;
    throw std::invalid_argument("unknown synthetic object \"" + s + "\"; known: sphere, cross-box, rounded-cube");
}

std::string to_string(SyntheticShape s) {
    return s == SyntheticShape::sphere ? "sphere" : s == SyntheticShape::cross_box ? "cross-box" : "rounded-cube";
}

bool synthetic_hit(SyntheticShape s, const glm::dvec3& o, const glm::dvec3& d, double& t, Rgba8& color) {
    if (s == SyntheticShape::sphere) {
        const double b = glm::dot(o, d), c = glm::dot(o, o) - 1.0, disc = b * b - c;
        if (disc < 0.0) return false;
        const double sq = std::sqrt(disc);
        t = -b - sq;
        if (t < 0.0) t = -b + sq;
        if (t < 0.0) return false;
        const glm::dvec3 p = o + d * t;
        const double lon = std::atan2(p.z, p.x), lat = std::asin(std::clamp(p.y, -1.0, 1.0));
        const int band = int(std::floor(lon / (M_PI / 6.0))) + int(std::floor(lat / (M_PI / 8.0)));
        const double shade = (band & 1) ? 0.55 : 1.0;
        color = {channel(shade * (0.5 + 0.5 * p.x)), channel(shade * (0.5 + 0.5 * p.y)),
                 channel(shade * (0.5 + 0.5 * p.z)), 255};
        return true;
    }
    if (s == SyntheticShape::rounded_cube) {
        // Entry into the intersection of the cube and the sphere: the later of the two entries, if before both exits.
        constexpr double R = 1.3;
        const double b = glm::dot(o, d), c = glm::dot(o, o) - R * R, disc = b * b - c;
        if (disc < 0.0) return false;
        const double s0 = -b - std::sqrt(disc), s1 = -b + std::sqrt(disc);
        double tb;
        int axis;
        if (!hit_box({glm::dvec3(-1.0), glm::dvec3(1.0), 0}, o, d, tb, axis)) return false;
        double tb1 = std::numeric_limits<double>::infinity();  // the cube's exit
        for (int i = 0; i < 3; ++i)
            if (d[i] != 0.0) tb1 = std::min(tb1, std::max((-1.0 - o[i]) / d[i], (1.0 - o[i]) / d[i]));
        t = std::max(tb, s0);
        if (t > std::min(tb1, s1) || t < 0.0) return false;
        const glm::dvec3 p = o + d * t;
        const bool check = (int(std::floor(p.x * 4.0)) + int(std::floor(p.y * 4.0)) + int(std::floor(p.z * 4.0))) & 1;
        const double k = check ? 0.55 : 1.0;
        color = {channel(k * (0.55 + 0.4 * p.x)), channel(k * (0.55 + 0.4 * p.y)), channel(k * (0.55 + 0.4 * p.z)),
                 255};
        return true;
    }
    double best = std::numeric_limits<double>::infinity();
    int best_part = -1, best_axis = 0;
    for (const AaBox& b : cross_box_parts()) {
        double tb;
        int axis;
        if (hit_box(b, o, d, tb, axis) && tb < best) {
            best = tb;
            best_part = b.part;
            best_axis = axis;
        }
    }
    if (best_part < 0) return false;
    t = best;
    const glm::dvec3 p = o + d * t;
    const int u = (best_axis + 1) % 3, v = (best_axis + 2) % 3;
    const bool check = (int(std::floor(p[u] * 5.0)) + int(std::floor(p[v] * 5.0))) & 1;
    static const double palette[7][3] = {{0.8, 0.8, 0.75}, {0.9, 0.2, 0.2}, {0.2, 0.8, 0.3}, {0.2, 0.3, 0.9},
                                         {0.9, 0.8, 0.1},  {0.8, 0.2, 0.8}, {0.1, 0.8, 0.8}};
    const double* c = palette[best_part == 0 ? 0 : 1 + (best_part - 1) % 6];
    const double k = (check ? 0.6 : 1.0) * (0.7 + 0.1 * best_axis);
    color = {channel(c[0] * k), channel(c[1] * k), channel(c[2] * k), 255};
    return true;
}

std::array<SyntheticFace, kFaceCount> synthetic_faces(SyntheticShape s, int n) {
    if (n < 1) throw std::invalid_argument("synthetic object size must be >= 1, found " + std::to_string(n));
    std::array<SyntheticFace, kFaceCount> faces;
    for (int f = 0; f < kFaceCount; ++f) {
        const ReliefGeometry g = box_face_geometry(kSyntheticBox, f, n, n);
        const glm::dvec3 into = -g.f();
        const double depth = kSyntheticBox.extent()[face_axis(f)];
        SyntheticFace& out = faces[size_t(f)];
        out.color = ImageRGBA8(n, n);
        out.displacement = ImageF(n, n);
        for (int row = 0; row < n; ++row)
            for (int x = 0; x < n; ++x) {
                const double u = x + 0.5, v = (n - 1 - row) + 0.5;
                const glm::dvec3 o = g.origin + g.a * u + g.b * v;
                double t;
                Rgba8 c;
                if (synthetic_hit(s, o, into, t, c) && t <= depth) {
                    out.color.at(x, row) = c;
                    out.displacement.at(x, row) = float(-t);
                } else {
                    out.color.at(x, row) = {0, 0, 0, 0};
                    out.displacement.at(x, row) = 0.0f;
                }
            }
    }
    return faces;
}

double synthetic_discontinuity(int n) { return 3.0 * kSyntheticBox.extent().x / n; }

SixFaceObject make_synthetic_object(SyntheticShape s, int n) {
    const auto faces = synthetic_faces(s, n);
    SixFaceObject obj;
    obj.name = to_string(s);
    obj.box = kSyntheticBox;
    for (int f = 0; f < kFaceCount; ++f) {
        const double depth = kSyntheticBox.extent()[face_axis(f)];
        ReliefTexture& t = obj.faces[size_t(f)];
        t = make_relief(faces[size_t(f)].color, faces[size_t(f)].displacement, -depth, 0.0,
                        box_face_geometry(kSyntheticBox, f, n, n));
        mark_discontinuities(t, synthetic_discontinuity(n));
    }
    return obj;
}

}  // namespace rtm
