#include "procedural/town.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "formats/relief_manifest.h"

namespace rtm {

namespace {

// House dimensions in world units: the facade is one unit square (the procedural facade's own size).
constexpr double kWidth = 1.0, kDepth = 0.8, kWall = 1.0, kRidge = 0.35, kGarden = 0.16, kGardenGap = 0.3;
constexpr double kStreetHalf = 0.75;  // from the street's centre line to the houses' garden walls

double roof_length() { return std::sqrt(0.25 * kDepth * kDepth + kRidge * kRidge); }
double roof_pitch_deg() { return glm::degrees(std::atan2(kRidge, 0.5 * kDepth)); }

uint32_t hash(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}
double hash01(int a, int b, int c) {
    return double(hash(uint32_t(a) * 73856093U ^ uint32_t(b) * 19349663U ^ uint32_t(c) * 83492791U)) / 4294967296.0;
}

// The relief in its own frame: lower left corner at the origin, texel spacing `t` along a and b (or `ta`, `tb`).
void frame(ProceduralRelief& p, double ta, double tb) {
    p.geometry.origin = glm::dvec3(0.0);
    p.geometry.a = {ta, 0.0, 0.0};
    p.geometry.b = {0.0, tb, 0.0};
}

uint8_t clamp8(double v) { return uint8_t(std::clamp(std::lround(v), 0L, 255L)); }

ProceduralRelief recolour(ProceduralRelief p, int variant) {
    // Three colourings of one facade: the walls' warm beige kept, turned grey-blue, or turned ochre. Only bright,
    // low-saturation pixels (render, sills, frames) change; windows, shutters and the roof band keep theirs.
    static const double kTint[3][3] = {{1.0, 1.0, 1.0}, {0.86, 0.93, 1.04}, {1.04, 0.9, 0.7}};
    for (Rgba8& px : p.color.pixels) {
        const int mx = std::max({px.r, px.g, px.b}), mn = std::min({px.r, px.g, px.b});
        if (mx < 150 || mx - mn > 60) continue;
        px.r = clamp8(px.r * kTint[variant][0]);
        px.g = clamp8(px.g * kTint[variant][1]);
        px.b = clamp8(px.b * kTint[variant][2]);
    }
    p.name = "facade" + std::to_string(variant);
    return p;
}

// Roof tiles in rows that overlap downwards (each row's lower edge stands out), and a brick chimney.
ProceduralRelief make_roof(int w, int h) {
    ProceduralRelief p;
    p.name = "roof";
    p.range_min = 0.0;
    p.range_max = 0.16;
    p.color = ImageRGBA8(w, h);
    p.displacement = ImageF(w, h);
    const double t = kWidth / w;
    const double course = 0.045, tile = 0.07;  // world units
    for (int row = 0; row < h; ++row) {
        for (int i = 0; i < w; ++i) {
            const double x = (i + 0.5) * t, y = (h - 1 - row + 0.5) * t;
            const double cy = y / course;
            const int c = int(std::floor(cy));
            const double fy = cy - c;  // 0 at a row's lower edge, 1 at its top (under the next row)
            const double cx = (x + ((c & 1) ? 0.5 * tile : 0.0)) / tile;
            const int k = int(std::floor(cx));
            const double fx = cx - k;
            double d = 0.014 * (1.0 - fy);  // a tile's lower edge stands out
            const double v = 0.85 + 0.3 * hash01(k, c, 1);
            double r = 150 * v, g = 62 * v, b = 42 * v;
            if (fx < 0.06 || fx > 0.94) r *= 0.55, g *= 0.55, b *= 0.55;    // the gap between tiles
            r *= 0.8 + 0.2 * fy, g *= 0.8 + 0.2 * fy, b *= 0.8 + 0.2 * fy;  // shade under the next row
            // The chimney: a brick block standing 0.15 out of the roof near its top right.
            const double x0 = 0.68, x1 = 0.8, y0 = 0.55 * roof_length(), y1 = 0.85 * roof_length();
            if (x >= x0 && x < x1 && y >= y0 && y < y1) {
                d = 0.15;
                const bool joint = std::fmod(y, 0.03) < 0.005 ||
                                   std::fmod(x + (int(y / 0.03) & 1) * 0.02, 0.04) < 0.005;
                r = joint ? 170 : 140, g = joint ? 165 : 70, b = joint ? 158 : 52;
                if (y > y1 - 0.015) r = 60, g = 55, b = 52;  // the cap
            }
            p.color.at(i, row) = {clamp8(r), clamp8(g), clamp8(b), 255};
            p.displacement.at(i, row) = float((d - p.range_min) / (p.range_max - p.range_min));
        }
    }
    frame(p, t, t);
    return p;
}

// A side wall: bricks, with the gable above the eaves (texels above the roof line are empty).
ProceduralRelief make_side(int n) {
    ProceduralRelief p = make_brick_wall(n);
    p.name = "side";
    const double ta = kDepth / n, tb = (kWall + kRidge) / n;
    for (int row = 0; row < n; ++row) {
        for (int i = 0; i < n; ++i) {
            const double x = (i + 0.5) * ta, y = (n - 1 - row + 0.5) * tb;
            const double roof = kWall + kRidge * (1.0 - std::abs(x - 0.5 * kDepth) / (0.5 * kDepth));
            if (y > roof) p.color.at(i, row) = {0, 0, 0, 0};
        }
    }
    frame(p, ta, tb);
    return p;
}

// The lowest courses of the brick wall.
ProceduralRelief make_garden(int n) {
    const ProceduralRelief wall = make_brick_wall(n);
    const int h = std::max(2, int(std::lround(kGarden * n)));
    ProceduralRelief p = wall;
    p.name = "garden";
    p.color = ImageRGBA8(n, h);
    p.displacement = ImageF(n, h);
    for (int row = 0; row < h; ++row)
        for (int i = 0; i < n; ++i) {
            p.color.at(i, row) = wall.color.at(i, n - h + row);
            p.displacement.at(i, row) = wall.displacement.at(i, n - h + row);
        }
    frame(p, kWidth / n, kWidth / n);
    return p;
}

// Placement of a part in its house's frame (house centre on the ground at the origin, front towards +z).
SceneTransform part_transform(const std::string& part) {
    SceneTransform t;
    const double hw = 0.5 * kWidth, hd = 0.5 * kDepth;
    if (part.rfind("facade", 0) == 0) {
        t.translate = {-hw, 0.0, hd};
    } else if (part == "back") {
        t.rotate = {{0, 1, 0, 180}};
        t.translate = {hw, 0.0, -hd};
    } else if (part == "side+") {
        t.rotate = {{0, 1, 0, 90}};
        t.translate = {hw, 0.0, hd};
    } else if (part == "side-") {
        t.rotate = {{0, 1, 0, -90}};
        t.translate = {-hw, 0.0, -hd};
    } else if (part == "roof+") {
        t.rotate = {{1, 0, 0, roof_pitch_deg() - 90.0}};
        t.translate = {-hw, kWall, hd};
    } else if (part == "roof-") {
        t.rotate = {{1, 0, 0, roof_pitch_deg() - 90.0}, {0, 1, 0, 180}};
        t.translate = {hw, kWall, -hd};
    } else if (part == "garden") {
        t.translate = {-hw, 0.0, hd + kGardenGap};
    } else {
        throw std::logic_error("unknown town part " + part);
    }
    return t;
}

// The part's transform followed by the house's: rotation about y by `yaw` degrees, then a move to `at`.
SceneTransform place(SceneTransform t, const glm::dvec3& at, double yaw) {
    const glm::dmat4 r = glm::rotate(glm::dmat4(1.0), glm::radians(yaw), glm::dvec3(0, 1, 0));
    t.translate = at + glm::dvec3(r * glm::dvec4(t.translate, 1.0));
    t.rotate.push_back({0, 1, 0, yaw});
    return t;
}

}  // namespace

const std::vector<std::string>& town_part_names() {
    static const std::vector<std::string> names = {"facade0", "facade1", "facade2", "back", "side", "roof", "garden"};
    return names;
}

ProceduralRelief make_town_part(const std::string& part, const TownOptions& o) {
    const int n = o.texels;
    if (n < 8 || n > 2048) throw std::invalid_argument("town: texels must be in 8..2048, found " + std::to_string(n));
    if (part.rfind("facade", 0) == 0 && part.size() == 7 && part[6] >= '0' && part[6] <= '2') {
        ProceduralRelief p = recolour(make_facade(n), part[6] - '0');
        frame(p, kWidth / n, kWall / n);
        return p;
    }
    if (part == "back") {
        ProceduralRelief p = make_brick_wall(n);
        p.name = "back";
        frame(p, kWidth / n, kWall / n);
        return p;
    }
    if (part == "side") return make_side(n);
    if (part == "roof") return make_roof(n, std::max(2, int(std::lround(roof_length() * n))));
    if (part == "garden") return make_garden(n);
    throw std::invalid_argument("town: unknown part \"" + part + "\"");
}

std::string write_town(const std::string& dir, const TownOptions& o) {
    if (o.houses < 2) throw std::invalid_argument("town: at least 2 houses, found " + std::to_string(o.houses));
    if (o.path_frames < 2) throw std::invalid_argument("town: at least 2 path frames");
    namespace fs = std::filesystem;
    std::map<std::string, std::string> relief_path;
    for (const std::string& part : town_part_names()) {
        const ProceduralRelief p = make_town_part(part, o);
        ReliefManifest m;
        m.name = "town_" + part;
        m.range_min = p.range_min;
        m.range_max = p.range_max;
        m.geometry = p.geometry;
        const std::string path = (fs::path(dir) / ("town_" + part + ".relief.json")).string();
        write_relief(path, m, p.color, p.displacement);
        relief_path[part] = path;
    }
    SceneManifest s;
    s.path = (fs::path(dir) / "town.scene.json").string();
    s.name = "town";
    const int per_side = (o.houses + 1) / 2;
    const double spacing = kWidth + 0.25;
    const double z_front = kStreetHalf + kGardenGap + 0.5 * kDepth;  // house centre from the street's centre line
    for (int k = 0; k < o.houses; ++k) {
        const bool south = k < per_side;
        const int slot = south ? k : k - per_side;
        const glm::dvec3 at(slot * spacing, 0.0, south ? -z_front : z_front);
        const double yaw = south ? 0.0 : 180.0;
        const std::string facade = "facade" + std::to_string(k % 3);
        for (const char* part : {"facade", "back", "side+", "side-", "roof+", "roof-", "garden"}) {
            std::string p = part;
            const std::string tex = p == "facade" ? facade : p.substr(0, p.find_first_of("+-"));
            SceneItem item;
            item.kind = SceneItem::Kind::relief;
            item.relief_path = relief_path.at(tex);
            item.transform = place(part_transform(p == "facade" ? facade : p), at, yaw);
            s.items.push_back(item);
        }
    }
    // The ground: the street and the gardens, one grey polygon a little below the houses' feet (the walls' lowest
    // texels are recessed mortar at displacement < 0, which must not sink into it).
    const double x0 = -1.5, x1 = (per_side - 1) * spacing + 1.5, z = z_front + 1.0;
    SceneItem ground;
    ground.kind = SceneItem::Kind::polygon;
    ground.vertices = {{x0, -0.001, z}, {x1, -0.001, z}, {x1, -0.001, -z}, {x0, -0.001, -z}};
    ground.color = {0.42, 0.42, 0.4};
    s.items.push_back(ground);

    const double x_end = (per_side - 1) * spacing;
    s.camera = SceneCameraKey{{-1.3, 0.9, 0.2}, {0.45 * x_end, 0.35, 0.0}, {0, 1, 0}, 55.0};
    // A walk down the street at eye height, looking a little ahead and from side to side.
    const double eye_h = 0.3;
    s.path_keys = {
        {{-1.2, eye_h, 0.0}, {0.5, eye_h + 0.05, -0.3}, {0, 1, 0}, 60.0},
        {{0.25 * x_end, eye_h, 0.1}, {0.25 * x_end + 1.5, eye_h + 0.1, -0.6}, {0, 1, 0}, 60.0},
        {{0.5 * x_end, eye_h, -0.1}, {0.5 * x_end + 1.5, eye_h + 0.1, 0.6}, {0, 1, 0}, 60.0},
        {{0.75 * x_end, eye_h, 0.0}, {0.75 * x_end + 1.5, eye_h + 0.05, -0.4}, {0, 1, 0}, 60.0},
        {{x_end + 0.8, eye_h, 0.0}, {x_end + 2.5, eye_h, 0.0}, {0, 1, 0}, 60.0},
    };
    s.path_frames = o.path_frames;
    write_scene_manifest(s.path, s);
    return s.path;
}

}  // namespace rtm
