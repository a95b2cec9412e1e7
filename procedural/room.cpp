#include "procedural/room.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include "formats/image_io.h"
#include "formats/scene_manifest.h"
#include "mesh/ply_writer.h"

namespace rtm {
namespace {

// A wall's frame: s runs along `right` from the corner at `origin`, t up, d along `normal` into the room.
struct Wall {
    const char* name;
    glm::dvec3 origin, right, normal;
    glm::dvec3 paper_a, paper_b;  // the paint at the ceiling and at the floor
    glm::dvec3 at(double s, double t, double d) const { return origin + right * s + glm::dvec3(0, t, 0) + normal * d; }
};

const std::array<Wall, 4>& walls() {
    static const std::array<Wall, 4> w = {{
        {"back", {-kRoomHalf, 0, -kRoomHalf}, {1, 0, 0}, {0, 0, 1}, {0.86, 0.80, 0.62}, {0.80, 0.72, 0.52}},
        {"left", {-kRoomHalf, 0, kRoomHalf}, {0, 0, -1}, {1, 0, 0}, {0.66, 0.80, 0.64}, {0.58, 0.72, 0.56}},
        {"right", {kRoomHalf, 0, -kRoomHalf}, {0, 0, 1}, {-1, 0, 0}, {0.62, 0.72, 0.86}, {0.54, 0.64, 0.80}},
        {"front", {kRoomHalf, 0, kRoomHalf}, {-1, 0, 0}, {0, 0, -1}, {0.86, 0.68, 0.68}, {0.78, 0.60, 0.60}},
    }};
    return w;
}

// Shading baked into the vertex colours (the renderers are unlit): faces looking up are brightest, sideways ones
// a little darker by direction, downward ones darkest, so the fittings' shapes read in a picture.
double shade(const glm::dvec3& n) {
    if (n.y > 0.5) return 1.0;
    if (n.y < -0.5) return 0.55;
    return std::abs(n.z) > 0.5 ? 0.9 : 0.75;
}

struct Rect {
    double s0, s1, t0, t1;
    bool contains(double s, double t) const { return s > s0 && s < s1 && t > t0 && t < t1; }
};

class Builder {
public:
    TriangleMesh mesh;

    // A planar quad, corners in order; colour shaded by its normal unless `shaded` is false.
    void quad(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3,
              const glm::dvec3& color, bool shaded = true) {
        const glm::dvec3 n = glm::normalize(glm::cross(p1 - p0, p3 - p0));
        const glm::dvec3 c = glm::clamp(color * (shaded ? shade(n) : 1.0), 0.0, 1.0) * 255.0;
        const glm::u8vec4 c8(uint8_t(std::lround(c.r)), uint8_t(std::lround(c.g)), uint8_t(std::lround(c.b)), 255);
        const auto base = uint32_t(mesh.vertices.size());
        for (const glm::dvec3& p : {p0, p1, p2, p3}) mesh.vertices.push_back({glm::vec3(p), {0, 0}, c8});
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    // A quad whose normal must point along `outward` (for the shading): the corners reordered if needed.
    void face(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3,
              const glm::dvec3& outward, const glm::dvec3& color) {
        if (glm::dot(glm::cross(p1 - p0, p3 - p0), outward) >= 0)
            quad(p0, p1, p2, p3, color);
        else
            quad(p3, p2, p1, p0, color);
    }
    // A prism in a wall's frame: the cross-section `sec` (4 points, counter-clockwise) in the plane of the wall's
    // normal and one wall axis, extruded along the other axis from x0 to x1. along_t: sec is (s, d), extruded
    // along t (upright); else sec is (t, d), extruded along s (horizontal).
    void prism(const Wall& w, bool along_t, const std::array<glm::dvec2, 4>& sec, double x0, double x1,
               const glm::dvec3& c) {
        auto at = [&](const glm::dvec2& q, double x) { return along_t ? w.at(q.x, x, q.y) : w.at(x, q.x, q.y); };
        const glm::dvec3 axis = along_t ? glm::dvec3(0, 1, 0) : w.right;
        const glm::dvec3 first = along_t ? w.right : glm::dvec3(0, 1, 0);
        for (size_t i = 0; i < 4; ++i) {
            const glm::dvec2 e = sec[(i + 1) % 4] - sec[i];
            const glm::dvec3 out = first * e.y - w.normal * e.x;  // the edge's outward normal (counter-clockwise)
            face(at(sec[i], x0), at(sec[(i + 1) % 4], x0), at(sec[(i + 1) % 4], x1), at(sec[i], x1), out, c);
        }
        face(at(sec[0], x0), at(sec[1], x0), at(sec[2], x0), at(sec[3], x0), -axis, c);
        face(at(sec[0], x1), at(sec[1], x1), at(sec[2], x1), at(sec[3], x1), axis, c);
    }
    // A box in a wall's frame, [s0, s1] x [t0, t1] x [d0, d1]: its six faces.
    void box(const Wall& w, double s0, double s1, double t0, double t1, double d0, double d1, const glm::dvec3& c) {
        auto p = [&](int k) { return w.at(k & 1 ? s1 : s0, k & 2 ? t1 : t0, k & 4 ? d1 : d0); };
        quad(p(4), p(5), p(7), p(6), c);  // front (d1)
        quad(p(0), p(2), p(3), p(1), c);  // back (d0)
        quad(p(2), p(6), p(7), p(3), c);  // top
        quad(p(0), p(1), p(5), p(4), c);  // bottom
        quad(p(0), p(4), p(6), p(2), c);  // s0 side
        quad(p(1), p(3), p(7), p(5), c);  // s1 side
    }
    // A recess behind a hole [s0, s1] x [t0, t1] of the wall, `depth` deep, its sides splayed: its back is the
    // hole inset by `splay` on each side (a door's threshold rises too), so the bake, looking straight at the
    // wall, sees the sides too (sides square to the wall would be edge-on to it and lost). Returns the back's
    // rectangle.
    Rect recess(const Wall& w, const Rect& r, double depth, double splay, const glm::dvec3& back,
                const glm::dvec3& sides) {
        const double d = -depth;
        const Rect in{r.s0 + splay, r.s1 - splay, r.t0 + splay, r.t1 - splay};
        quad(w.at(in.s0, in.t0, d), w.at(in.s1, in.t0, d), w.at(in.s1, in.t1, d), w.at(in.s0, in.t1, d), back);
        quad(w.at(r.s0, r.t0, 0), w.at(r.s1, r.t0, 0), w.at(in.s1, in.t0, d), w.at(in.s0, in.t0, d), sides);  // sill
        quad(w.at(in.s0, in.t1, d), w.at(in.s1, in.t1, d), w.at(r.s1, r.t1, 0), w.at(r.s0, r.t1, 0), sides);
        quad(w.at(in.s0, in.t0, d), w.at(in.s0, in.t1, d), w.at(r.s0, r.t1, 0), w.at(r.s0, r.t0, 0), sides);
        quad(w.at(r.s1, r.t0, 0), w.at(r.s1, r.t1, 0), w.at(in.s1, in.t1, d), w.at(in.s1, in.t0, d), sides);
        return in;
    }
    // The wall surface in cells of 1/8 unit, less the holes; the paint darkens a little towards the floor (a
    // smooth shade: sharp patterns would add the same resampling error to every method and hide the differences
    // that depth makes).
    void wall(const Wall& w, const std::vector<Rect>& holes) {
        constexpr double cell = 0.125;
        const int ns = int(std::lround(2 * kRoomHalf / cell)), nt = int(std::lround(kRoomHeight / cell));
        for (int i = 0; i < ns; ++i)
            for (int j = 0; j < nt; ++j) {
                const double s = i * cell, t = j * cell;
                bool hole = false;
                for (const Rect& h : holes) hole = hole || h.contains(s + 0.5 * cell, t + 0.5 * cell);
                if (hole) continue;
                const glm::dvec3 c = glm::mix(w.paper_b, w.paper_a, (t + 0.5 * cell) / kRoomHeight);
                // The border cells reach kWallOverlap beyond the room's corners, floor and ceiling (behind the
                // neighbouring walls, below the floor, above the ceiling: unseen from the room), as real walls
                // run into their joints: a relief's rectangle reaching a little beyond the room has surface
                // there, so its pre-warp covers the room's edges whole (no crack where two reliefs meet).
                const double s0 = i == 0 ? -kWallOverlap : s, s1 = i == ns - 1 ? s + cell + kWallOverlap : s + cell;
                const double t0 = j == 0 ? -kWallOverlap : t, t1 = j == nt - 1 ? t + cell + kWallOverlap : t + cell;
                quad(w.at(s0, t0, 0), w.at(s1, t0, 0), w.at(s1, t1, 0), w.at(s0, t1, 0), c);
            }
    }
};

// Deterministic pseudo-random numbers in [0, 1) for the books.
struct Lcg {
    uint32_t state;
    double next() {
        state = state * 1664525u + 1013904223u;
        return double(state >> 8) / double(1u << 24);
    }
};

// Shelves between s0 and s1 with boards at the given heights, uprights at both ends, books on each board.
void shelves(Builder& b, const Wall& w, double s0, double s1, const std::vector<double>& boards, uint32_t seed) {
    const glm::dvec3 wood(0.55, 0.36, 0.2);
    const double depth = 0.44, thick = 0.04;
    // Uprights with tapered outer faces: seen from the front, as the bake sees the wall, their sides show.
    const double t0 = boards.front() - 0.2, t1 = boards.back() + 0.45, taper = 0.6 * depth;
    b.prism(w, true, {{{s0, 0}, {s0, depth}, {s0 - thick, depth}, {s0 - thick - taper, 0}}}, t0, t1, wood);
    b.prism(w, true, {{{s1, 0}, {s1 + thick + taper, 0}, {s1 + thick, depth}, {s1, depth}}}, t0, t1, wood);
    Lcg rng{seed};
    static const glm::dvec3 covers[] = {{0.7, 0.15, 0.12}, {0.15, 0.3, 0.6}, {0.2, 0.5, 0.25}, {0.85, 0.7, 0.25},
                                        {0.45, 0.2, 0.5},  {0.9, 0.9, 0.85}, {0.2, 0.2, 0.22}, {0.8, 0.45, 0.2}};
    for (double t : boards) {
        b.box(w, s0, s1, t - thick, t, 0, depth, wood);
        double s = s0 + 0.02;
        while (true) {
            const double width = 0.035 + 0.05 * rng.next(), height = 0.18 + 0.14 * rng.next();
            if (s + width > s1 - 0.02) break;
            // Packed spines, flush at the front: a book's sides are hidden by its neighbours, as on a real shelf
            // (a relief texture records one surface per texel: the sides of books standing apart would be lost).
            b.box(w, s, s + width, t, t + height, 0.01, 0.43, covers[size_t(rng.next() * 8) % 8]);
            s += width;
        }
    }
}

// A framed plaque: a raised bronze panel with lines of dark lettering, in a wooden frame standing out further.
void plaque(Builder& b, const Wall& w, const Rect& r) {
    const glm::dvec3 frame(0.35, 0.2, 0.1), panel(0.78, 0.62, 0.3), letters(0.25, 0.18, 0.1);
    const double fw = 0.1, fd = 0.26;
    // The frame's members bevelled outwards (a moulding): the bake, looking straight at the wall, sees them whole.
    const double bevel = 0.1;
    b.prism(w, false, {{{r.t0, 0}, {r.t0 + fw, 0}, {r.t0 + fw, fd}, {r.t0 + bevel * 0.5, fd}}}, r.s0, r.s1, frame);
    b.prism(w, false, {{{r.t1, 0}, {r.t1 - bevel * 0.5, fd}, {r.t1 - fw, fd}, {r.t1 - fw, 0}}}, r.s0, r.s1, frame);
    b.prism(w, true, {{{r.s0, 0}, {r.s0 + fw, 0}, {r.s0 + fw, fd}, {r.s0 + bevel * 0.5, fd}}}, r.t0 + fw, r.t1 - fw,
            frame);
    b.prism(w, true, {{{r.s1, 0}, {r.s1 - bevel * 0.5, fd}, {r.s1 - fw, fd}, {r.s1 - fw, 0}}}, r.t0 + fw, r.t1 - fw,
            frame);
    b.box(w, r.s0 + fw, r.s1 - fw, r.t0 + fw, r.t1 - fw, 0, 0.05, panel);
    Lcg rng{7};
    const double left = r.s0 + fw + 0.08, right = r.s1 - fw - 0.08;
    for (int line = 0; line < 4; ++line) {
        const double t = r.t1 - fw - 0.12 - line * 0.11;
        double s = left + (line == 0 ? 0.12 : 0.0);
        while (s < right - (line == 0 ? 0.12 : 0.0)) {
            const double width = 0.03 + 0.05 * rng.next();
            b.box(w, s, std::min(s + width, right), t - 0.05, t, 0.05, 0.056, letters);
            s += width + 0.03;
        }
    }
}

}  // namespace

glm::dvec3 room_floor_color() { return {0.52, 0.4, 0.3}; }
glm::dvec3 room_ceiling_color() { return {0.93, 0.92, 0.88}; }

TriangleMesh make_room_mesh() {
    Builder b;
    const auto& w = walls();
    const double h = kRoomHalf;
    // Floor and ceiling: one colour each, unshaded (the scene draws them as plain polygons of these colours).
    b.quad({-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, room_floor_color(), false);
    b.quad({-h, kRoomHeight, -h}, {h, kRoomHeight, -h}, {h, kRoomHeight, h}, {-h, kRoomHeight, h}, room_ceiling_color(),
           false);

    // Back wall: shelves on the left, the framed plaque on the right.
    b.wall(w[0], {});
    shelves(b, w[0], 0.85, 2.0, {0.7, 1.15, 1.6}, 11);
    plaque(b, w[0], {2.3, 3.4, 1.05, 1.85});

    // Left wall: a window niche 0.4 deep with a sill standing out below it and a window cross in the glass.
    const Rect window{1.375, 2.625, 0.75, 2.0};
    b.wall(w[1], {window});
    const Rect glass = b.recess(w[1], window, 0.4, 0.2, {0.62, 0.8, 0.95}, {0.9, 0.88, 0.84});
    const glm::dvec3 bar(0.95, 0.95, 0.95);
    b.box(w[1], 1.975, 2.025, glass.t0, glass.t1, -0.4, -0.35, bar);
    b.box(w[1], glass.s0, glass.s1, 1.35, 1.4, -0.4, -0.35, bar);
    b.box(w[1], window.s0 - 0.1, window.s1 + 0.1, window.t0 - 0.05, window.t0, 0, 0.1, {0.9, 0.9, 0.88});

    // Right wall: a door in a recess 0.2 deep, a frame standing out around it, a handle.
    const Rect door{1.5, 2.5, 0.0, 2.0};
    b.wall(w[2], {door});
    b.recess(w[2], door, 0.2, 0.1, {0.5, 0.3, 0.16}, {0.8, 0.78, 0.74});
    const glm::dvec3 trim(0.93, 0.92, 0.88);
    b.box(w[2], door.s0 - 0.1, door.s0, 0, door.t1 + 0.1, 0, 0.08, trim);
    b.box(w[2], door.s1, door.s1 + 0.1, 0, door.t1 + 0.1, 0, 0.08, trim);
    b.box(w[2], door.s0, door.s1, door.t1, door.t1 + 0.1, 0, 0.08, trim);
    b.box(w[2], door.s0 + 0.12, door.s1 - 0.12, 1.15, 1.85, -0.2, -0.17, {0.45, 0.27, 0.14});  // upper panel
    b.box(w[2], door.s0 + 0.12, door.s1 - 0.12, 0.15, 0.95, -0.2, -0.17, {0.45, 0.27, 0.14});  // lower panel
    b.box(w[2], door.s1 - 0.2, door.s1 - 0.13, 0.95, 1.0, -0.2, -0.1, {0.85, 0.75, 0.3});      // handle

    // Front wall: a long shelf unit.
    b.wall(w[3], {});
    shelves(b, w[3], 0.8, 3.2, {0.6, 1.05, 1.5}, 23);

    TriangleMesh& m = b.mesh;
    m.materials.push_back({"room", glm::vec4(1.0f), {}});
    m.parts.push_back({0, uint32_t(m.indices.size()), 0, false, true});
    m.lo = glm::dvec3(1e30);
    m.hi = glm::dvec3(-1e30);
    for (const MeshVertexAttribs& v : m.vertices) {
        m.lo = glm::min(m.lo, glm::dvec3(v.position));
        m.hi = glm::max(m.hi, glm::dvec3(v.position));
    }
    return m;
}

std::vector<BakePlane> room_planes(const RoomOptions& o) {
    if (o.texels_per_unit < 8 || o.texels_per_unit > 512)
        throw std::invalid_argument("room: texels per unit must be in 8..512, found " +
                                    std::to_string(o.texels_per_unit));
    if (!(o.look_down_deg >= 0.0 && o.look_down_deg <= 30.0))
        throw std::invalid_argument("room: look_down_deg must be in 0..30, found " + std::to_string(o.look_down_deg));
    const double texel = 1.0 / o.texels_per_unit;
    if (o.border_texels < 0 || o.border_texels * texel > kWallOverlap)
        throw std::invalid_argument("room: border_texels must be in 0.." + std::to_string(int(kWallOverlap / texel)) +
                                    " at " + std::to_string(o.texels_per_unit) + " texels per unit, found " +
                                    std::to_string(o.border_texels));
    const double down = o.look_down_deg * M_PI / 180.0;
    const glm::dvec3 up(0, 1, 0);
    std::vector<BakePlane> planes;
    for (const Wall& w : walls()) {
        const glm::dvec3 g = std::cos(down) * w.normal + std::sin(down) * up;
        BakePlane p;
        p.name = w.name;
        // The wall's texel steps projected along g onto the plane through its floor corner normal to g.
        p.geometry.a = (w.right - g * glm::dot(g, w.right)) * texel;
        p.geometry.b = (up - g * glm::dot(g, up)) * texel;
        const double k = o.border_texels;
        p.geometry.origin = w.origin - p.geometry.a * k - p.geometry.b * k;
        p.width = int(std::lround(2 * kRoomHalf / texel)) + 2 * o.border_texels;
        p.height = int(std::lround(kRoomHeight / texel)) + 2 * o.border_texels;
        // From behind the deepest recess (the window niche, 0.4) to beyond the shelves (0.44), measured along g
        // from the wall's own surface, which lies between 0 (floor) and kRoomHeight * sin(down) (ceiling).
        p.range_lo = -0.45 * std::cos(down) - 0.01;
        p.range_hi = kRoomHeight * std::sin(down) + 0.45 * std::cos(down) + 0.05;
        p.cull_back_faces = true;
        planes.push_back(p);
    }
    return planes;
}

std::vector<std::array<glm::dvec3, 2>> room_seams() {
    std::vector<std::array<glm::dvec3, 2>> seams;
    for (double x : {-kRoomHalf, kRoomHalf})
        for (double z : {-kRoomHalf, kRoomHalf}) seams.push_back({glm::dvec3(x, 0, z), glm::dvec3(x, kRoomHeight, z)});
    return seams;
}

std::string write_room(const std::string& dir, const RoomOptions& o) {
    if (o.path_frames < 2) throw std::invalid_argument("room: at least 2 path frames");
    namespace fs = std::filesystem;
    const std::string mesh_path = (fs::path(dir) / "room.ply").string();
    write_ply(mesh_path, make_room_mesh());
    // Bake what a user would: the file as assimp reads it.
    const TriangleMesh mesh = load_mesh(mesh_path);
    const std::vector<std::string> reliefs = bake_planes(mesh, room_planes(o), dir, "room");
    RoomOptions flat = o;
    flat.look_down_deg = 0.0;
    const std::vector<std::string> wall_maps = bake_planes(mesh, room_planes(flat), dir, "room_walls");

    SceneManifest s;
    s.path = (fs::path(dir) / "room.scene.json").string();
    s.name = "room";
    for (const std::string& r : reliefs) {
        SceneItem item;
        item.kind = SceneItem::Kind::relief;
        item.relief_path = r;
        s.items.push_back(item);
    }
    const double h = kRoomHalf;
    SceneItem floor;
    floor.kind = SceneItem::Kind::polygon;
    floor.vertices = {{-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}};
    floor.color = room_floor_color();
    s.items.push_back(floor);
    SceneItem ceiling = floor;
    ceiling.vertices = {{-h, kRoomHeight, -h}, {h, kRoomHeight, -h}, {h, kRoomHeight, h}, {-h, kRoomHeight, h}};
    ceiling.color = room_ceiling_color();
    s.items.push_back(ceiling);

    s.camera = SceneCameraKey{{1.3, 1.5, 1.4}, {-0.6, 1.2, -2.0}, {0, 1, 0}, 60.0};
    // A walk round the room, looking at each wall's fittings in turn.
    s.path_keys = {
        {{1.3, 1.5, 1.4}, {-0.6, 1.2, -2.0}, {0, 1, 0}, 60.0},  // the back wall's shelves and plaque
        {{-0.9, 1.5, 1.2}, {1.2, 1.3, -2.0}, {0, 1, 0}, 60.0},  // the plaque from the other side
        {{-0.6, 1.6, -0.8}, {2.0, 1.1, 0.4}, {0, 1, 0}, 60.0},  // the door
        {{1.0, 1.5, -1.0}, {-2.0, 1.3, 0.4}, {0, 1, 0}, 60.0},  // the window niche
        {{0.4, 1.4, -1.2}, {-0.4, 1.1, 2.0}, {0, 1, 0}, 60.0},  // the front wall's shelves
    };
    s.path_frames = o.path_frames;
    write_scene_manifest(s.path, s);
    // The same room on the walls' own planes: what conventional texture maps of the walls would be.
    SceneManifest walls_scene = s;
    walls_scene.path = (fs::path(dir) / "room_walls.scene.json").string();
    walls_scene.name = "room_walls";
    for (size_t i = 0; i < wall_maps.size(); ++i) walls_scene.items[i].relief_path = wall_maps[i];
    write_scene_manifest(walls_scene.path, walls_scene);
    return s.path;
}

}  // namespace rtm
