// The registered room of the paper's Figures 22 and 23 (Oliveira, Bishop and McAllister, "Relief Texture Mapping",
// SIGGRAPH 2000, section 4.4): a room mesh generated here (walls with shelves, a framed plaque, a door frame, a
// window niche; flat vertex colours with the shading baked in), acquired as four relief textures, one per wall, on
// planes chosen in the wall surfaces (mesh/bake_planes.h), plus plain polygons for the floor and the ceiling.
// The walls meet at the room's corners; their registration is by depth alone. Deterministic.
//
// Room frame: the floor is y = 0, the ceiling y = kRoomHeight, the walls x = +-kRoomHalf and z = +-kRoomHalf;
// every wall's relief normal f points into the room, so shelves and frames stand out (d > 0) and the niche, the
// door and the window recess (d < 0). Nothing stands within kCornerClear of a corner, so the walls seen edge-on
// by the neighbouring walls' views are the only geometry in their slabs there.
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

struct RoomOptions {
    int texels_per_unit = 128;  // relief texels per world unit along the walls (8..512)
    int path_frames = 96;
};

// The room's colours (linear 0..1): floor and ceiling, shared by the mesh and the scene's plain polygons.
glm::dvec3 room_floor_color();
glm::dvec3 room_ceiling_color();

// The room as one vertex-coloured mesh (walls, floor, ceiling and the fittings), in the room frame.
TriangleMesh make_room_mesh();

// The four walls' bake planes ("back" z = -kRoomHalf, "left" x = -kRoomHalf, "right", "front"): each spans its
// wall from floor to ceiling and corner to corner, slab from the deepest recess to the furthest protrusion.
std::vector<BakePlane> room_planes(const RoomOptions& o = {});

// The vertical lines where two relief walls meet (the room's four corners), bottom point first.
std::vector<std::array<glm::dvec3, 2>> room_seams();

// Writes DIR/room.ply (the mesh), DIR/room_WALL.relief.json with their images (the bake, which needs a current
// GlContext), and DIR/room.scene.json: the four walls, the floor and ceiling polygons, a default camera and a
// camera path through the room. Returns the scene manifest's path.
std::string write_room(const std::string& dir, const RoomOptions& o = {});

}  // namespace rtm
