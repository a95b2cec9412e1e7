// The viewer's window and frame loop (rtm view): a GLFW window with an OpenGL 3.3 core context, what is loaded
// drawn with the chosen method, the Dear ImGui panel and the overlays, the orbit and fly cameras, a camera path,
// keys, drag and drop, screenshots. Scripted runs (frames > 0) use a hidden window, vsync off, and take the keys
// and camera-path times from the options, so that each frame is the same from run to run.
#pragma once

#include <glm/vec4.hpp>

#include <memory>
#include <string>
#include <vector>

#include "texmap/camera.h"
#include "viewer/cameras.h"
#include "viewer/loaded.h"

namespace rtm::viewer {

struct ViewerOptions {
    Camera camera;           // the starting camera (size, field of view, up; eye and look-at if fixed)
    bool start_fly = false;  // start with the fly camera at camera.eye looking at camera.look_at (--eye)
    OrbitCamera orbit;       // the orbit camera's start (--orbit, or the default 30,20,2.2)
    ViewSettings settings;
    int frames = 0;                 // > 0: scripted, render this many frames and return
    std::string screenshot;         // scripted: write the last frame here
    std::string camera_path;        // a camera path file (viewer/camera_path.h)
    bool own_camera_path = false;   // play what is loaded's own camera path (a scene's) instead
    std::vector<int> keys;          // scripted key presses, applied in order before the first frame
    double fly_step_s = 0.1;        // a scripted fly key moves the eye by this many seconds of travel
    int timed_every = 16;           // the stage times (Table 1) are measured in 1 frame of this many (1: every frame)
    double panel_refresh_ms = 100;  // the panel is rendered at least this often (viewer/panel_cache.h); 0: every frame
    float content_scale = 0;        // > 0: the window's content scale changes to this before the first frame, as when
                                    // it moves to another monitor (the callback's path, testable without one)
};

// What a run measured (scripted runs report it with --json).
struct ViewerResult {
    int frames = 0;
    double fps = 0;                // frames after the first tenth, over their wall time
    std::vector<double> frame_ms;  // every frame
    // The timed frames (1 in ViewerOptions::timed_every): the stages, and the parts of other_ms (the panel and
    // overlays drawn, the buffer swap).
    std::vector<double> prewarp_ms, upload_ms, texture_map_ms, other_ms;
    std::vector<double> overlay_ms, swap_ms;
    std::vector<long long> texels_warped;
    long long panel_renders = 0, panel_blits = 0;  // frames that rendered the panel; that showed it from its cache
    glm::vec4 panel{0.f}, insets{0.f};  // the last frame's rectangles (x, y, w, h) in framebuffer pixels, top-left
    int width = 0, height = 0;
    std::string renderer;
};

ViewerResult run_viewer(std::unique_ptr<Loaded> loaded, const ViewerOptions& options);

}  // namespace rtm::viewer
