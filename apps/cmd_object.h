// rtm render --object and rtm prewarp --object: a six-face object (objects/relief_object.h, docs/OBJECTS.md).
#pragma once

#include <string>

#include "cli_common.h"

namespace rtm::cli {

struct ObjectRenderArgs {
    std::string object, out, json, method = "two-pass", level = "0", filter = "point";
    CameraArgs camera;
    bool exact = false, depth_correction = false, no_skips = false;
    int repeat = 1, threads = 0;
    double discontinuity = -1;  // >= 0: re-mark every face's discontinuities with this threshold (0 = none)
};
void run_render_object(const ObjectRenderArgs& a);

struct ObjectPrewarpArgs {
    std::string object, eye, out, method = "two-pass", level = "0", json, filter = "point";
    bool exact = false;
    int repeat = 1, threads = 0;
    std::string isa = "auto";  // --isa, as for --relief
};
void run_prewarp_object(const ObjectPrewarpArgs& a);

// OUT with a face suffix before the extension: "dir/x.png", "+x" -> "dir/x_+x.png".
std::string face_output_path(const std::string& out, const std::string& face_key);

}  // namespace rtm::cli
