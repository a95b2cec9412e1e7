// NAME.relief.json (docs/FORMATS.md):
//   { "color": "x_color.png", "displacement": "x_disp.png", "displacement_range": [min, max],
//     "origin": [x,y,z], "a": [x,y,z], "b": [x,y,z] }
// Optional: "name" (string), "discontinuity_threshold" (number, world units, >= 0).
// Paths are relative to the manifest. Unknown fields are ignored; malformed fields are rejected.
// Every error throws rtm::IoError whose message starts with the file's path and says what is wrong, e.g.
//   "media/x.relief.json: field \"a\" must be an array of 3 finite numbers, found [1, 2]".
#pragma once

#include <optional>
#include <string>

#include "warp/relief_texture.h"

namespace rtm {

struct ReliefManifest {
    std::string path;               // the manifest itself
    std::string name;               // "name" field, or the file stem without ".relief"
    std::string color_path;         // resolved against the manifest's folder
    std::string displacement_path;  // resolved against the manifest's folder
    double range_min = 0.0, range_max = 0.0;
    ReliefGeometry geometry;
    std::optional<double> discontinuity_threshold;
};

ReliefManifest parse_relief_manifest(const std::string& path);
// Parses the manifest, reads both images (sizes must match, displacement finite) and builds the texture. When the
// manifest has a "discontinuity_threshold", the texture's discontinuities are marked with it (mark_discontinuities).
ReliefTexture load_relief(const std::string& manifest_path, ReliefManifest* manifest_out = nullptr);
// Writes a manifest (paths relative to its folder) plus images; used by the media generator and `bake`.
void write_relief(const std::string& manifest_path, const ReliefManifest& m, const ImageRGBA8& color,
                  const ImageF& displacement_normalized);

}  // namespace rtm
