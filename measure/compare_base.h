// The bases `rtm compare` draws a relief on, each with a truth of its own: "flat", the relief on its quad (measured
// against raycast, or micromesh for an object or a scene); "curved", the relief bent over the cylinder patch of
// quadric silhouettes; "sphere", bent over the sphere patch (perpixel/curved_patch.h). A curved base's rows are
// measured against its own micro-polygon mesh, "<base>-micromesh", never against another base's truth; its summary
// rows and Pareto front are its own. Results files written before the base existed leave it empty: flat.
#pragma once

#include <array>
#include <string>

namespace rtm {

inline constexpr std::array<const char*, 3> kCompareBases = {"flat", "curved", "sphere"};
inline constexpr std::array<const char*, 2> kCurvedBases = {"curved", "sphere"};

inline bool is_curved_base(const std::string& base) { return base == "curved" || base == "sphere"; }
// The base as written, empty (older files) as flat.
inline std::string base_name(const std::string& base) { return base.empty() ? "flat" : base; }
// The id of a curved base's truth drawn by `method` ("micromesh", the reference of its rows, or "raycast"):
// "curved-micromesh", "sphere-raycast", ...
inline std::string curved_truth_id(const std::string& base, const std::string& method) { return base + "-" + method; }

}  // namespace rtm
