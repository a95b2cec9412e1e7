#include "procedural/known_answer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

namespace rtm {
namespace {

constexpr double kRange = 0.25;

// height(x, y) in [0, 1] over the unit square (x right, y up).
ProceduralRelief make(const std::string& name, int size, const std::function<double(double, double)>& height) {
    if (size < 8 || size > 8192)
        throw std::invalid_argument("known-answer relief \"" + name + "\": size must be 8..8192, found " +
                                    std::to_string(size));
    ProceduralRelief p;
    p.name = name;
    p.color = ImageRGBA8(size, size);
    p.displacement = ImageF(size, size);
    p.range_min = 0.0;
    p.range_max = kRange;
    p.geometry.origin = {0, 0, 0};
    p.geometry.a = {1.0 / size, 0, 0};
    p.geometry.b = {0, 1.0 / size, 0};
    for (int row = 0; row < size; ++row)
        for (int i = 0; i < size; ++i) {
            const double x = (i + 0.5) / size, y = (size - 1 - row + 0.5) / size;
            const double h = std::clamp(height(x, y), 0.0, 1.0);
            p.displacement.at(i, row) = float(h);
            auto c = [](double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
            p.color.at(i, row) = {c(0.5 + 0.4 * std::sin(2 * std::numbers::pi * 3 * x)),
                                  c(0.5 + 0.4 * std::sin(2 * std::numbers::pi * 3 * y)), c(0.2 + 0.7 * h), 255};
        }
    return p;
}

}  // namespace

ProceduralRelief make_step(int size) {
    return make("step", size, [](double x, double y) { return x > 0.3 && x < 0.7 && y > 0.3 && y < 0.7 ? 1.0 : 0.0; });
}

ProceduralRelief make_pyramid(int size) {
    return make("pyramid", size,
                [](double x, double y) { return 1.0 - std::max(std::abs(x - 0.5), std::abs(y - 0.5)) / 0.3; });
}

ProceduralRelief make_sphere_cap(int size) {
    return make("sphere-cap", size, [](double x, double y) {
        const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5), R = 0.35, below = 0.1;
        const double z = R * R > r2 ? std::sqrt(R * R - r2) - below : 0.0;
        return z / (R - below);
    });
}

std::vector<std::string> known_answer_names() { return {"step", "pyramid", "sphere-cap"}; }

ProceduralRelief make_known_answer(const std::string& name, int size) {
    if (name == "step") return make_step(size);
    if (name == "pyramid") return make_pyramid(size);
    if (name == "sphere-cap") return make_sphere_cap(size);
    throw std::invalid_argument("unknown known-answer relief \"" + name + "\"; known: step, pyramid, sphere-cap");
}

}  // namespace rtm
