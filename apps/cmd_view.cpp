// rtm view: the interactive viewer (GLFW window). Drag with the left button to orbit, scroll to zoom; keys:
// 1 flat, 2 two-pass, 3 pipelined, 4 micromesh; W side polygons on/off; D depth correction on/off; K skips
// on/off; L pyramid level auto/0; F coverage filter on/off (two-pass); Esc or Q quits. With --frames N --screenshot IMG it renders N frames, writes
// the last one and exits (for tests under Xvfb). Timing of the last second goes to the window title.
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli_common.h"
#include "objects/bounds.h"
#include "formats/relief_manifest.h"
#include "objects/render_relief.h"
#include "texmap/camera_rig.h"
#include "texmap/gl_context.h"
#include "formats/image_io.h"

namespace rtm::cli {

namespace {

struct ViewArgs {
    std::string relief, screenshot;
    CameraArgs camera;
    int frames = 0;
};

// Orbit state around the bounds' centre, in the --orbit convention.
struct Orbit {
    double az = 30, el = 20, dist = 2.2;
    bool dragging = false;
    double last_x = 0, last_y = 0;
};

void run_view(const ViewArgs& a) {
    if (a.relief.empty()) throw UsageError("view needs --relief M");
    if (a.frames < 0) throw UsageError("--frames: expected N >= 0, found " + std::to_string(a.frames));
    if (!a.screenshot.empty() && a.frames == 0) throw UsageError("--screenshot needs --frames N");
    ReliefQuad quad(load_relief(a.relief));
    const Bounds bounds = relief_bounds(quad.relief());
    CameraArgs ca = a.camera;
    if (!ca.has_eye()) ca.orbit = "30,20,2.2";
    Camera cam = ca.resolve(bounds);
    Orbit orbit;
    if (!ca.orbit.empty()) {
        const glm::dvec3 o = parse_vec3(ca.orbit, "--orbit");
        orbit = {o.x, o.y, o.z};
    }
    const bool use_orbit = ca.eye.empty();

    auto ctx = GlContext::create_window(cam.width, cam.height, "rtm view: " + a.relief, a.frames == 0,
                                        {.pin_llvmpipe_threads = true});
    Renderer renderer;
    GLFWwindow* win = static_cast<GLFWwindow*>(ctx->native_window());
    glfwSetWindowUserPointer(win, &orbit);
    glfwSetMouseButtonCallback(win, [](GLFWwindow* w, int button, int action, int) {
        auto* o = static_cast<Orbit*>(glfwGetWindowUserPointer(w));
        if (button == GLFW_MOUSE_BUTTON_LEFT) o->dragging = action == GLFW_PRESS;
        glfwGetCursorPos(w, &o->last_x, &o->last_y);
    });
    glfwSetCursorPosCallback(win, [](GLFWwindow* w, double x, double y) {
        auto* o = static_cast<Orbit*>(glfwGetWindowUserPointer(w));
        if (o->dragging) {
            o->az -= 0.3 * (x - o->last_x);
            o->el = std::clamp(o->el + 0.3 * (y - o->last_y), -89.0, 89.0);
        }
        o->last_x = x;
        o->last_y = y;
    });
    glfwSetScrollCallback(win, [](GLFWwindow* w, double, double dy) {
        auto* o = static_cast<Orbit*>(glfwGetWindowUserPointer(w));
        o->dist = std::clamp(o->dist * std::pow(0.9, dy), 0.05, 1000.0);
    });

    RenderSettings rs;
    rs.method = RenderMethod::two_pass;
    rs.prewarp.keep_outliers = true;
    bool prev_keys[512] = {};
    bool coverage = false;
    auto pressed = [&](int key) {
        const bool down = glfwGetKey(win, key) == GLFW_PRESS;
        const bool edge = down && !prev_keys[key];
        prev_keys[key] = down;
        return edge;
    };
    ImageRGBA8 last;
    auto t_title = std::chrono::steady_clock::now();
    int frames_since = 0;
    double work_ms = 0;
    for (int frame = 0; a.frames == 0 || frame < a.frames; ++frame) {
        ctx->poll_events();
        if (ctx->should_close() || pressed(GLFW_KEY_ESCAPE) || pressed(GLFW_KEY_Q)) break;
        if (pressed(GLFW_KEY_1)) rs.method = RenderMethod::flat;
        if (pressed(GLFW_KEY_2)) rs.method = RenderMethod::two_pass;
        if (pressed(GLFW_KEY_3)) rs.method = RenderMethod::pipelined;
        if (pressed(GLFW_KEY_4)) rs.method = RenderMethod::micromesh;
        if (pressed(GLFW_KEY_W)) rs.prewarp.keep_outliers = !rs.prewarp.keep_outliers;
        if (pressed(GLFW_KEY_D)) rs.draw.depth_correction = !rs.draw.depth_correction;
        if (pressed(GLFW_KEY_K)) rs.draw.skips = !rs.draw.skips;
        if (pressed(GLFW_KEY_L)) rs.draw.level = rs.draw.level < 0 ? 0 : -1;
        if (pressed(GLFW_KEY_F)) coverage = !coverage;
        // The coverage filter exists for the two-pass reconstruction only.
        rs.prewarp.filter = coverage && rs.method == RenderMethod::two_pass ? Filter::coverage : Filter::point;
        if (use_orbit) {
            cam.eye = orbit_eye(bounds.centre(), bounds.radius(), {orbit.az, orbit.el, orbit.dist});
            cam.fit_clip_planes(bounds.centre(), std::max(bounds.radius(), 1e-12));
        }
        cam.width = ctx->width();
        cam.height = ctx->height();
        StageTimes st;
        DrawReport rep;
        last = render_relief_frame(quad, &renderer, cam, rs, st, &rep);
        ctx->swap_buffers();
        work_ms += st.total_ms;
        ++frames_since;
        const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_title).count();
        if (since > 1.0) {
            char title[256];
            std::snprintf(title, sizeof title, "rtm view: %s | %s%s%s%s | level %d | %.1f fps, %.2f ms/frame",
                          a.relief.c_str(), to_string(rs.method).c_str(), rs.prewarp.keep_outliers ? " +walls" : "",
                          rs.draw.depth_correction ? " +depth" : "",
                          rs.prewarp.filter == Filter::coverage ? " +coverage" : "", rep.level, frames_since / since,
                          work_ms / frames_since);
            glfwSetWindowTitle(win, title);
            t_title = std::chrono::steady_clock::now();
            frames_since = 0;
            work_ms = 0;
        }
    }
    if (!a.screenshot.empty()) write_rgba8(a.screenshot, last);
}

}  // namespace

void add_view_command(CLI::App& app) {
    auto a = std::make_shared<ViewArgs>();
    CLI::App* sub = app.add_subcommand("view", "Interactive viewer (GLFW window)");
    sub->add_option("--relief", a->relief, "Relief texture manifest")->required();
    a->camera.add_to(*sub);
    sub->add_option("--frames", a->frames, "Render N frames and exit (0 = until closed)")->capture_default_str();
    sub->add_option("--screenshot", a->screenshot, "Write the last frame to IMG (with --frames)");
    sub->callback([a] { run_view(*a); });
}

}  // namespace rtm::cli
