#include "objects/render_method.h"

#include <stdexcept>
#include <utility>

namespace rtm {

namespace {

constexpr Reconstruction kReconstructions[] = {Reconstruction::two_pass, Reconstruction::pipelined};

// The methods by name; the warping ones are named as their reconstructions.
const std::vector<std::pair<RenderMethod, std::string>>& method_table() {
    static const std::vector<std::pair<RenderMethod, std::string>> table = [] {
        std::vector<std::pair<RenderMethod, std::string>> t = {
            {RenderMethod::flat, "flat"},
            {RenderMethod::two_pass, to_string(Reconstruction::two_pass)},
            {RenderMethod::pipelined, to_string(Reconstruction::pipelined)},
            {RenderMethod::micromesh, "micromesh"},
            {RenderMethod::raycast, "raycast"},
        };
        // The per-pixel methods, by their own table's names (perpixel/perpixel_method.h).
        for (PerPixelMethod m : all_perpixel_methods())
            t.emplace_back(RenderMethod(int(RenderMethod::parallax) + int(m)), to_string(m));
        return t;
    }();
    return table;
}

}  // namespace

RenderMethod parse_render_method(const std::string& s) {
    std::string known;
    for (const auto& [m, name] : method_table()) {
        if (s == name) return m;
        known += (known.empty() ? "" : ", ") + name;
    }
    throw std::invalid_argument("unknown method \"" + s + "\"; known: " + known);
}

std::string to_string(RenderMethod m) {
    for (const auto& [x, name] : method_table())
        if (x == m) return name;
    return "?";
}

std::vector<RenderMethod> render_methods() {
    std::vector<RenderMethod> out;
    for (const auto& entry : method_table()) out.push_back(entry.first);
    return out;
}

std::optional<PerPixelMethod> perpixel_method(RenderMethod m) {
    if (int(m) < int(RenderMethod::parallax) || int(m) > int(RenderMethod::quadric_silhouettes)) return std::nullopt;
    return PerPixelMethod(int(m) - int(RenderMethod::parallax));
}

Reconstruction parse_reconstruction(const std::string& s) {
    for (Reconstruction r : kReconstructions)
        if (s == to_string(r)) return r;
    throw std::invalid_argument("unknown reconstruction \"" + s + "\"; known: " + reconstruction_names_list());
}

std::string reconstruction_names_list() {
    std::string out;
    for (Reconstruction r : kReconstructions) out += (out.empty() ? "" : ", ") + to_string(r);
    return out;
}

}  // namespace rtm
