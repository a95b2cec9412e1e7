// Relief textures made by program, in the spirit of the paper's figures: a brick wall whose bricks have zero
// displacement and whose mortar is recessed (Figure 21), a building facade with protruding window frames and
// dormers and a recessed door (Figures 9 and 12), a smooth bumpy surface, and a field of steep ridges that fold
// over when seen obliquely. Deterministic: the same call gives the same bytes.
#pragma once

#include <string>
#include <vector>

#include "warp/image.h"
#include "warp/relief_texture.h"

namespace rtm {

struct ProceduralRelief {
    std::string name;
    ImageRGBA8 color;
    ImageF displacement;  // normalized 0..1 over [range_min, range_max]
    double range_min = 0.0, range_max = 0.0;
    ReliefGeometry geometry;
};

ProceduralRelief make_brick_wall(int size);
// The brick wall with every displacement moved by `shift` (world units): the same quantized levels over a shifted
// range, so the same texels are equal and neighbours differ alike, but no level decodes to 0 (nothing still): the
// lifted (+0.05) and sunk (-0.05) walls `rtm bench-skips` times against the wall.
ProceduralRelief make_shifted_brick_wall(int size, double shift);
ProceduralRelief make_facade(int size);
ProceduralRelief make_bumps(int size);
ProceduralRelief make_ridges(int size);
std::vector<std::string> procedural_names();                          // {"bricks", "facade", "bumps", "ridges"}
std::string procedural_names_list();                                  // "bricks, facade, bumps, ridges", for messages
ProceduralRelief make_procedural(const std::string& name, int size);  // throws std::invalid_argument

// Converts to a relief texture (quantized) directly, without files.
ReliefTexture to_relief(const ProceduralRelief& p);

}  // namespace rtm
