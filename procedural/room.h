// The registered room of the paper's Figures 22 and 23 (Oliveira, Bishop and McAllister, "Relief Texture Mapping",
// SIGGRAPH 2000, section 4.4): a room mesh generated here (walls with shelves, a framed plaque, a door frame, a
// window niche; flat vertex colours with the shading baked in), acquired as four relief textures, one per wall, on
// user-chosen planes (mesh/bake_planes.h) that look down at the walls a few degrees (so the tops of books, boards
// and sills are recorded too), plus plain polygons for the floor and the ceiling. The reliefs overlap at the
// room's corners; their registration is by depth alone. Deterministic.
//
// Room frame: the floor is y = 0, the ceiling y = kRoomHeight, the walls x = +-kRoomHalf and z = +-kRoomHalf;
// every wall's relief normal f points into the room (and up by look_down_deg), so shelves and frames stand out
// of the wall and the niche, the door and the window recess into it. Nothing stands within kCornerClear of a
// corner, so the walls seen edge-on by the neighbouring walls' views are the only geometry in their slabs there.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/bake_planes.h"
#include "mesh/triangle_mesh.h"

namespace rtm {

constexpr double kRoomHalf = 2.0;
constexpr double kRoomHeight = 2.5;
constexpr double kCornerClear = 0.5;
// How far the walls' surfaces reach beyond the room's corners, floor and ceiling (procedural/room.cpp).
constexpr double kWallOverlap = 0.02;

struct RoomOptions {
    int texels_per_unit = 256;  // relief texels per world unit along the walls (8..512)
    // Each relief looks at its wall from this many degrees above the horizontal (0..30): its plane is tilted back
    // by that much, so the bake sees the tops of books, boards, sills and frames, not only what faces the wall's
    // normal (docs/ACCURACY.md, "The registered room"). 0 gives planes in the walls' own surfaces.
    double look_down_deg = 6.0;
    // Texels each relief reaches beyond its wall's corners, floor and ceiling (at most kWallOverlap's worth).
    int border_texels = 2;
    int path_frames = 96;
};

// The room's colours (linear 0..1): floor and ceiling, shared by the mesh and the scene's plain polygons.
glm::dvec3 room_floor_color();
glm::dvec3 room_ceiling_color();

// The room as one vertex-coloured mesh (walls, floor, ceiling and the fittings), in the room frame.
TriangleMesh make_room_mesh();

// The four walls' bake planes ("back" z = -kRoomHalf, "left" x = -kRoomHalf, "right", "front"). Each is seen
// along -g, g = cos(look_down) * (the wall's normal) + sin(look_down) * up: its plane is normal to g and its texel
// vectors are the wall's texel steps projected onto that plane, so texel (u, v) sees the wall point u texels from
// the corner and v texels up (the wall's own surface lies at displacement v * texel * sin(look_down)); the
// rectangle spans the wall from floor to ceiling and corner to corner plus border_texels on each side; the slab
// reaches from behind the deepest recess to beyond the furthest protrusion. Back faces are culled: looking down,
// the rays of the top rows enter through the ceiling from above. Throws std::invalid_argument for options out of
// range.
std::vector<BakePlane> room_planes(const RoomOptions& o = {});

// The vertical lines where two relief walls meet (the room's four corners), bottom point first.
std::vector<std::array<glm::dvec3, 2>> room_seams();

// Writes DIR/room.ply (the mesh), DIR/room_WALL.relief.json with their images (the bake, which needs a current
// GlContext), and DIR/room.scene.json: the four walls, the floor and ceiling polygons, a default camera and a
// camera path through the room. Also DIR/room_walls.scene.json with DIR/room_walls_WALL.relief.json: the same
// room baked onto the walls' own planes (look_down_deg 0), the conventional texture maps of the walls that flat
// texture mapping is measured with. Returns the first scene manifest's path.
std::string write_room(const std::string& dir, const RoomOptions& o = {});

}  // namespace rtm
