// Synthetic reliefs with a known answer, for checking the per-pixel methods against the exact ray caster: a
// square step (a raised block with vertical walls), a square pyramid and a sphere cap, each centred on a unit
// square (a = (1/size, 0, 0), b = (0, 1/size, 0), f = +z) with zero displacement along the borders and
// displacement range [0, 0.25]. The colour is smooth (two sinusoids and the height), so a point found at the
// wrong place shows as a colour error without the aliasing of hard edges.
#pragma once

#include <string>
#include <vector>

#include "procedural/procedural_media.h"

namespace rtm {

ProceduralRelief make_step(int size);           // block [0.3, 0.7]^2 at full height
ProceduralRelief make_pyramid(int size);        // base [0.2, 0.8]^2, apex at full height
ProceduralRelief make_sphere_cap(int size);     // sphere of radius 0.35 centred 0.1 below the plane, scaled in z
std::vector<std::string> known_answer_names();  // {"step", "pyramid", "sphere-cap"}
ProceduralRelief make_known_answer(const std::string& name, int size);  // throws std::invalid_argument

}  // namespace rtm
