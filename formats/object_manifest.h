// NAME.object.json: a six-face image-based object (paper section 4.1), documented in docs/OBJECTS.md.
//   { "name": "duck",
//     "box": { "min": [x0, y0, z0], "max": [x1, y1, z1] },
//     "faces": { "+x": { "color": "duck_px_color.png", "displacement": "duck_px_disp.png",
//                        "displacement_range": [-2.1, 0.0], "discontinuity": 0.05 },
//                "-x": { "relief": "other.relief.json" }, "+y": {...}, "-y": {...}, "+z": {...}, "-z": {...} } }
// Each face is a relief texture whose quad is the box face (warp/box_faces.h gives the frames), its normal pointing
// out of the box, so displacement_range [lo, hi] has lo <= hi <= 0 and lo >= -(the box's extent along the normal).
// Inline faces take their frame from the box; a face given as a relief manifest must match it within 1e-6 of the
// box size. Every texel direction of the box must have one spacing (within 1e-6 relative) on all the faces that
// step along it (the two faces of a pair, and faces sharing an edge). "discontinuity" (inline) or the relief's
// "discontinuity_threshold" (world units, >= 0) marks surface discontinuities (section 4.1.1); 0 = none.
// Unknown fields are ignored, malformed ones rejected: every error is an rtm::IoError, one line that starts with the
// object manifest's path and names the face and the field.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "warp/box_faces.h"
#include "warp/image.h"

namespace rtm {

struct ObjectFaceEntry {
    std::string relief_path;  // set when the face is given as a relief manifest (then the rest comes from it)
    std::string color_path;   // resolved against the manifest's folder
    std::string displacement_path;
    double range_min = 0.0, range_max = 0.0;
    std::optional<double> discontinuity;
    ReliefGeometry geometry;  // relief form only: the relief manifest's own frame (checked when loaded)
};

struct ObjectManifest {
    std::string path;
    std::string name;  // "name" field, or the file stem without ".object"
    Box box;
    std::array<ObjectFaceEntry, kFaceCount> faces;  // in kFaceKeys order
};

// Parses the JSON (and the relief manifests of faces given that way); does not read images.
ObjectManifest parse_object_manifest(const std::string& path);
// Parses, reads the twelve images and builds the six relief textures, checking sizes, spacings and frames.
SixFaceObject load_object(const std::string& path, ObjectManifest* manifest_out = nullptr);

// What write_object_manifest writes for one face: RGBA8 colour (alpha 0 = empty), displacement normalized 0..1
// onto [range_min, range_max] (16-bit PNG), and an optional discontinuity threshold.
struct ObjectFaceImages {
    ImageRGBA8 color;
    ImageF displacement_normalized;
    double range_min = 0.0, range_max = 0.0;
    std::optional<double> discontinuity;
};
// Writes the images (NAME_px_color.png, NAME_px_disp.png, ... px nx py ny pz nz) beside the manifest, then the
// manifest in the inline form. Refuses (IoError naming the path) what load_object would reject.
void write_object_manifest(const std::string& path, const std::string& name, const Box& box,
                           const std::array<ObjectFaceImages, kFaceCount>& faces);

// The file-name tag of a face: "px", "nx", "py", "ny", "pz", "nz".
const char* face_tag(int face);

}  // namespace rtm
