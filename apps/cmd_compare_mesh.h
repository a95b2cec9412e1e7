// rtm compare --mesh: bakes a mesh into a six-face object (or takes --object) and renders both from a ring of 32
// views (measure/object_accuracy.h), the object by two-pass and pipelined relief texture mapping against the mesh
// (docs/ACCURACY.md).
#pragma once

#include <string>

namespace rtm::cli {

struct CompareMeshArgs {
    std::string mesh, object, out, size = "512x512";
    int threads = 0, texels = 256;
    double discontinuity = -1;  // re-mark every face's discontinuities (world units); -1: the manifest's
    bool no_images = false, texels_given = false;
};

// Writes OUT/compare.md, OUT/compare.json and (unless no_images) the pictures.
void run_compare_mesh(const CompareMeshArgs& a);

}  // namespace rtm::cli
