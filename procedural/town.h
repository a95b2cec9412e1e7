// The relief town of the paper's Figures 1 and 2: a street of houses, each seven relief-textured quads (the facade,
// the back and two side walls, two roof faces, and a low garden wall in front) on a ground polygon, with a camera
// path walking down the street. The houses share a handful of textures (three facade colourings of the procedural
// facade, one brick wall, one roof), so the whole town is a few hundred kilobytes. Deterministic.
#pragma once

#include <functional>
#include <string>

#include "formats/scene_manifest.h"
#include "procedural/procedural_media.h"

namespace rtm {

struct TownOptions {
    int houses = 12;   // >= 2; half on each side of the street
    int texels = 256;  // texels across a house's front (8..2048)
    int path_frames = 120;
};

// The parts of one house as relief textures in their own frames (origin at the quad's lower left corner, a along
// +x, b along +y, so f = +z): facade (variant 0..2), back, side (with its gable; empty texels above the roof line),
// roof, garden wall.
ProceduralRelief make_town_part(const std::string& part, const TownOptions& o);
// The names make_town_part takes: facade0, facade1, facade2, back, side, roof, garden.
const std::vector<std::string>& town_part_names();

// Writes DIR/town.scene.json, DIR/town_PART.relief.json and their images. Returns the manifest's path.
std::string write_town(const std::string& dir, const TownOptions& o = {});

}  // namespace rtm
