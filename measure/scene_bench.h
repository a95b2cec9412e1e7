// The frame time of a scene along its camera path (the relief town of docs/SCENES.md), for the scene sections of
// `rtm bench` (the frame with all skips against none, and where the frame's time goes) and `rtm bench-skips` (what
// each skip is worth on the path). Each variant draws the path with its own freshly loaded scene: two frames to warm
// up, then one timed pass over the path (the skips that keep state, such as reuse-prewarp, see the path in order),
// the variants' passes interleaved frame by frame.
//
// Benchmarks are programs, not tests: nothing here asserts a time.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "objects/frame_plan.h"
#include "objects/quad_frame.h"

namespace rtm {

struct SceneVariant {
    std::string name, description;
    DrawOptions draw;              // depth_correction is set by the bench from the field below
    bool depth_correction = true;  // as rtm render --scene draws; off, the pre-warps run on the fast kernels
    QuadFrameOptions frame;        // concurrent pre-warps, finish per quad
    int stride = 1;       // every stride-th frame of the path (only for variants that keep no state between frames)
    bool repeat = false;  // each frame drawn twice, the second timed: the frame when nothing needs pre-warping
    // The picture check's bound (rtm bench-skips fails beyond it): the most pixels of a frame, as a fraction of its
    // pixels, more than 8 levels off the first variant's frame of the same camera; negative: reported, not checked.
    double max_fraction_off = -1.0;
};

struct SceneBenchRow {
    SceneVariant variant;
    int frames = 0;
    // Medians over the frames, milliseconds (stage times as SceneFrameReport measures them).
    double prewarp_ms = 0, upload_ms = 0, texture_map_ms = 0, total_ms = 0;
    double fps = 0;  // 1000 / total_ms
    // The process's CPU time a frame (all threads: the pre-warps' and llvmpipe's), median: on a shared machine the
    // work a frame does, where the wall times above also hold the time other jobs had the cores.
    double cpu_ms = 0;
    double ratio = 0;                             // total_ms / the first row's total_ms
    double drawn = 0, prewarped = 0, texels = 0;  // means per frame
    std::map<std::string, long long> skips;       // skip name -> quads it fired for, over the frames
    std::map<int, long long> levels;              // pyramid level -> quads drawn at it, over the frames
    // The picture check: each frame against the first row's frame of the same camera (the frames both drew), the
    // most pixels of one frame more than 8 levels off in a channel, and how many frames differed at all.
    long long pixels_off_max = 0;
    int frames_off = 0, frames_compared = 0;
};

struct SceneBench {
    std::string scene, gl_renderer;
    int width = 0, height = 0, path_frames = 0, quads = 0;
    std::string load_before, load_after;
    bool interleaved = true;
    std::vector<SceneBenchRow> rows;
};

// For rtm bench: all skips (concurrent pre-warps, one finish a frame) first, then the level by texel density alone
// (the rule before objects/level_choice.h), the frame loop before this one (serial pre-warps, a finish per quad),
// serial pre-warps with one finish, no pyramid level per quad, no depth correction (the pre-warps on the fast
// kernels), no skips at all, and the floor: each frame again once its pre-warps are done (only texture mapping and
// the frame's set-up), with and without depth correction.
std::vector<SceneVariant> scene_frame_variants();
// The variants of `all` named in `names` (separated by ';'), in the order of `all`; std::invalid_argument naming an
// unknown one.
std::vector<SceneVariant> select_scene_variants(const std::vector<SceneVariant>& all, const std::string& names);
// For rtm bench-skips: all skips first, then without each skip in turn, then none.
std::vector<SceneVariant> scene_skip_variants();

// Draws `scene_path`'s camera path at width x height through an offscreen context (two-pass, side polygons, depth
// correction, all threads), each variant with its own copy of the scene, the variants interleaved frame by frame
// (frame k of every variant before frame k + 1 of any, their order rotated each frame) so that the machine's drift
// over the run falls on all of them alike. Each timed frame is read back whole and compared with the first variant's
// frame of the same camera (SceneBenchRow::pixels_off_max). Throws IoError for an unreadable scene,
// std::runtime_error for one without a path.
// `interleaved` false: one variant's whole path after another (the method before, to compare the two).
SceneBench bench_scene(const std::string& scene_path, int width, int height, const std::vector<SceneVariant>& variants,
                       const std::function<void(const std::string&)>& progress, bool interleaved = true);
// The variants whose picture check exceeded their max_fraction_off, one line each ("" when none).
std::string scene_picture_failures(const SceneBench& b);

std::string scene_bench_markdown(const SceneBench& b);
nlohmann::json scene_bench_json(const SceneBench& b);

}  // namespace rtm
