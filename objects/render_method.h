// How a relief is rendered, and the names of the methods and reconstructions as the command line and the reports
// write them: one table each (the reconstructions' is warp's to_string(Reconstruction)).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "perpixel/perpixel_method.h"
#include "warp/prewarp.h"

namespace rtm {

// After raycast: the per-pixel methods (perpixel/perpixel_method.h), by the same names, in the same order.
enum class RenderMethod {
    flat,
    two_pass,
    pipelined,
    micromesh,
    raycast,
    parallax,
    parallax_offset_limiting,
    steep_parallax,
    parallax_occlusion,
    relief_mapping,
    interval_mapping,
    protruded_displacement,
    quadric_silhouettes
};

RenderMethod parse_render_method(const std::string& s);  // throws std::invalid_argument naming s and the known ones
std::string to_string(RenderMethod m);
std::vector<RenderMethod> render_methods();                     // all of them, in the order of the table
std::optional<PerPixelMethod> perpixel_method(RenderMethod m);  // nullopt for the other methods
// Whether m pre-warps the relief (two-pass or pipelined: relief texture mapping), as the other methods do not.
inline bool prewarps(RenderMethod m) { return m == RenderMethod::two_pass || m == RenderMethod::pipelined; }

// "two-pass" or "pipelined" (to_string(Reconstruction)); throws std::invalid_argument naming s and the known ones.
Reconstruction parse_reconstruction(const std::string& s);
// "two-pass, pipelined", for messages.
std::string reconstruction_names_list();

}  // namespace rtm
