#include "viewer/viewer_app.h"

#include <glad/gl.h>  // before GLFW, which then includes no GL header of its own
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <glm/geometric.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "formats/image_io.h"
#include "measure/image_diff.h"
#include "texmap/gl_context.h"
#include "texmap/renderer.h"
#include "viewer/camera_path.h"
#include "viewer/frame_stats.h"
#include "viewer/keys.h"
#include "viewer/open_file.h"
#include "viewer/overlays.h"
#include "viewer/panel.h"
#include "viewer/panel_cache.h"
#include "viewer/screenshot.h"
#include "warp/timing.h"

namespace rtm::viewer {

namespace {

// The state the window's callbacks change.
struct Input {
    bool dragging = false;
    double last_x = 0, last_y = 0;
    double drag_x = 0, drag_y = 0, wheel = 0;  // accumulated since the last frame
    std::vector<int> presses;
    std::optional<std::string> dropped;
    std::optional<float> content_scale;  // the window's new content scale (moved to another monitor)
    bool changed = true;  // any event since the last frame drawn (an unchanged still view is not drawn again)
    // An event the panel may show (all but the cursor moving or the wheel turning away from it): the panel is
    // rendered again, not copied (viewer/panel_cache.h). Dragging the view does not re-render it every frame.
    bool panel_changed = true;
};

Input& input_of(GLFWwindow* w) { return *static_cast<Input*>(glfwGetWindowUserPointer(w)); }

// An event: the frame is drawn again, and the panel rendered again when `panel` (the event may change what it shows).
void changed(GLFWwindow* w, bool panel = true) {
    input_of(w).changed = true;
    input_of(w).panel_changed = input_of(w).panel_changed || panel;
}

// The window moved to a monitor of another content scale (DPI): the panel's font and sizes follow at the next frame.
void on_content_scale(GLFWwindow* w, float x, float) {
    changed(w);
    input_of(w).content_scale = x;
}

void install_callbacks(GLFWwindow* win) {
    // Installed before ImGui's GLFW back end, which calls them after its own (unless the panel takes the input).
    glfwSetMouseButtonCallback(win, [](GLFWwindow* w, int button, int action, int) {
        Input& in = input_of(w);
        changed(w);
        if (button != GLFW_MOUSE_BUTTON_LEFT) return;
        in.dragging = action == GLFW_PRESS && !ImGui::GetIO().WantCaptureMouse;
        glfwGetCursorPos(w, &in.last_x, &in.last_y);
    });
    glfwSetCursorPosCallback(win, [](GLFWwindow* w, double x, double y) {
        Input& in = input_of(w);
        // Over the panel (or leaving it: WantCaptureMouse is still the last position's) the hover may change.
        changed(w, ImGui::GetIO().WantCaptureMouse);
        if (in.dragging) {
            in.drag_x += x - in.last_x;
            in.drag_y += y - in.last_y;
        }
        in.last_x = x;
        in.last_y = y;
    });
    glfwSetScrollCallback(win, [](GLFWwindow* w, double, double dy) {
        changed(w, ImGui::GetIO().WantCaptureMouse);
        if (!ImGui::GetIO().WantCaptureMouse) input_of(w).wheel += dy;
    });
    glfwSetKeyCallback(win, [](GLFWwindow* w, int key, int, int action, int) {
        changed(w);
        if (action == GLFW_PRESS && !ImGui::GetIO().WantCaptureKeyboard) input_of(w).presses.push_back(key);
    });
    glfwSetDropCallback(win, [](GLFWwindow* w, int count, const char** paths) {
        changed(w);
        if (count > 0) input_of(w).dropped = std::string(paths[0]);
    });
    glfwSetWindowRefreshCallback(win, [](GLFWwindow* w) { changed(w); });
    glfwSetFramebufferSizeCallback(win, [](GLFWwindow* w, int, int) { changed(w); });
    glfwSetCharCallback(win, [](GLFWwindow* w, unsigned) { changed(w); });
    glfwSetWindowFocusCallback(win, [](GLFWwindow* w, int) { changed(w); });
    glfwSetCursorEnterCallback(win, [](GLFWwindow* w, int) { changed(w); });
    glfwSetWindowContentScaleCallback(win, on_content_scale);
}

ImTextureID imgui_texture(const GlTexture& t) { return reinterpret_cast<ImTextureID>(static_cast<intptr_t>(t.id())); }

bool same_view(const Camera& a, const Camera& b) {
    return a.eye == b.eye && a.look_at == b.look_at && a.up == b.up && a.fov_deg == b.fov_deg && a.width == b.width &&
           a.height == b.height;
}

// Clears the whole framebuffer (colour black, depth far) outside the renderer, for frames it draws nothing in.
void clear_framebuffer(int w, int h) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.f, 0.f, 0.f, 1.f);
    glClearDepth(1.0);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

// The panel's scale in ImGui units for a screen content scale: the content scale divided by the framebuffer scale
// (which ImGui applies already where the framebuffer is larger than the window), within [1, 4].
float ui_scale_of(GLFWwindow* win, float content_scale) {
    int ww = 0, wh = 0, fw = 0, fh = 0;
    glfwGetWindowSize(win, &ww, &wh);
    glfwGetFramebufferSize(win, &fw, &fh);
    const float fb_scale = ww > 0 && fw > 0 ? float(fw) / float(ww) : 1.f;
    return std::clamp(content_scale / fb_scale, 1.f, 4.f);
}

// The panel's style at `ui_scale`: Dear ImGui's dark style, its sizes and font scaled. Lines are not anti-aliased:
// on llvmpipe each anti-aliased line is a textured, blended quad wider than the line (with the opaque panel, the
// relief's overlay rendering the panel every frame fell from 4.2 to 10 ms to 4.3 ms, docs/BENCHMARKS.md "Viewer"),
// and the cached panel's edges stay inside its rectangle (viewer/panel_cache.h).
void apply_style(float ui_scale) {
    ImGuiStyle style;
    ImGui::StyleColorsDark(&style);
    style.AntiAliasedLines = false;
    if (ui_scale != 1.f) style.ScaleAllSizes(ui_scale);
    ImGui::GetStyle() = style;
    ImGui::GetIO().FontGlobalScale = ui_scale;
}

struct ImGuiSession {
    float ui_scale = 1.f;
    explicit ImGuiSession(GLFWwindow* win) {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
        // High-DPI: the panel's font and sizes follow the screen's content scale, in ImGui's units (window
        // coordinates; where the framebuffer is larger than the window, ImGui maps them onto it already).
        float sx = 1.f, sy = 1.f;
        glfwGetWindowContentScale(win, &sx, &sy);
        rescale(win, sx);
        if (!ImGui_ImplGlfw_InitForOpenGL(win, true)) throw GlError("Dear ImGui: the GLFW back end failed to start");
        if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
            ImGui_ImplGlfw_Shutdown();
            throw GlError("Dear ImGui: the OpenGL 3 back end failed to start");
        }
    }
    void rescale(GLFWwindow* win, float content_scale) {
        ui_scale = ui_scale_of(win, content_scale);
        apply_style(ui_scale);
    }
    ~ImGuiSession() {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
};

}  // namespace

ViewerResult run_viewer(std::unique_ptr<Loaded> loaded, const ViewerOptions& o) {
    const bool scripted = o.frames > 0;
    ViewSettings s = o.settings;
    Bounds bounds = loaded->bounds();
    Camera cam = o.camera;
    OrbitCamera orbit = o.orbit;
    FlyCamera fly;
    fly.speed = std::max(bounds.radius(), 1e-12);  // one radius per second
    double look_distance = std::max(glm::length(cam.look_at - cam.eye), 1e-12);
    if (o.start_fly) {
        fly.look_from(cam.eye, cam.look_at);
        s.fly = true;
    } else {
        fly.look_from(orbit.eye(bounds), orbit.centre(bounds));
        look_distance = glm::length(orbit.centre(bounds) - fly.eye);
    }
    bool was_fly = s.fly;

    // The camera path: a file's, or the scene's own (played when asked for, else ready to play with Space).
    std::optional<CameraPath> path;
    if (!o.camera_path.empty())
        path = load_camera_path(o.camera_path);
    else
        path = loaded->own_camera_path();
    const bool path_given = !o.camera_path.empty() || o.own_camera_path;
    bool path_active = path.has_value() && path_given, playing = path_active;
    double path_time = 0;

    auto ctx = GlContext::create_window(cam.width, cam.height, "rtm view: " + loaded->name(), !scripted);
    GLFWwindow* win = static_cast<GLFWwindow*>(ctx->native_window());
    if (!scripted) glfwSetWindowAttrib(win, GLFW_RESIZABLE, GLFW_TRUE);
    Input input;
    glfwSetWindowUserPointer(win, &input);
    install_callbacks(win);
    Renderer renderer;
    ImGuiSession imgui(win);
    PanelCache panel_cache(o.panel_refresh_ms);
    if (o.content_scale > 0) on_content_scale(win, o.content_scale, o.content_scale);  // as if the window moved
    std::string status;
    // One-time work in the window's context (a mesh's bake), with progress on stderr, in the title and the panel.
    auto prepare = [&](Loaded& l) {
        bool shown = false;
        l.prepare([&](const std::string& line) {
            std::fprintf(stderr, isatty(2) ? "\r%s" : "%s\n", line.c_str());  // a log gets one line each
            glfwSetWindowTitle(win, ("rtm view: " + line).c_str());
            status = line;
            ctx->poll_events();
            shown = true;
        });
        if (shown && isatty(2)) std::fprintf(stderr, "\n");
        status.clear();
    };
    prepare(*loaded);
    if (scripted) s.vsync = false;  // scripted runs are timed: never wait for the display
    bool vsync = s.vsync;
    glfwSwapInterval(vsync ? 1 : 0);

    ViewerResult result;
    result.renderer = ctx->describe();
    FrameStats stats, timed_stats;  // every frame drawn; the timed ones (their stages)
    long long drawn_frames = 0;
    FrameReport report;
    GlTexture still_tex, heat_tex;
    Camera still_for;  // the camera the ray-cast still was made for
    bool still_valid = false;
    ViewSettings still_settings;
    std::vector<int> pending = o.keys;
    Camera drawn_cam;  // the camera and settings of the last frame drawn
    ViewSettings drawn_settings;
    int settle = 0, panel_settle = 0;
    auto t_title = Clock::now();
    auto t_prev = Clock::now();
    const int warm = o.frames / 10;
    Clock::time_point t_warm = Clock::now();

    for (int frame = 0; !scripted || frame < o.frames; ++frame) {
        const auto t_frame = Clock::now();
        const double dt = scripted ? 1.0 / (path ? path->fps : 60.0)
                                   : std::chrono::duration<double>(t_frame - t_prev).count();
        t_prev = t_frame;
        if (frame == warm) t_warm = t_frame;
        ctx->poll_events();
        if (ctx->should_close()) break;
        if (input.content_scale) {
            imgui.rescale(win, *input.content_scale);
            input.content_scale.reset();
        }

        // Keys: the scripted ones first, then the window's.
        KeyRequests req;
        for (int k : pending) apply_key(k, s, req);
        pending.clear();
        for (int k : input.presses) {
            if (s.fly && fly_axes(k) != glm::dvec3(0.0)) continue;  // held movement keys move below
            apply_key(k, s, req);
        }
        input.presses.clear();
        if (req.quit) break;
        if (input.dropped) {
            const std::string file = *input.dropped;
            input.dropped.reset();
            try {
                std::unique_ptr<Loaded> opened = open_file(file);
                prepare(*opened);
                loaded = std::move(opened);
                bounds = loaded->bounds();
                path = loaded->own_camera_path();
                path_active = playing = false;
                path_time = 0;
                orbit.frame();
                fly.frame(bounds);
                still_valid = false;
                status.clear();
                glfwSetWindowTitle(win, ("rtm view: " + file).c_str());
            } catch (const std::exception& e) {
                status = e.what();
                std::fprintf(stderr, "%s\n", e.what());
            }
        }
        if (s.fly != was_fly) {  // switching cameras keeps the view
            if (s.fly) {
                fly.look_from(cam.eye, cam.look_at);
                look_distance = std::max(glm::length(cam.look_at - cam.eye), 1e-12);
            }
            was_fly = s.fly;
        }
        if (req.toggle_play && path) {
            playing = !playing;
            path_active = true;
            if (playing && path_time >= path->duration()) path_time = 0;
        }
        if (req.frame) {
            path_active = false;
            if (s.fly)
                fly.frame(bounds);
            else
                orbit.frame();
        }
        // Mouse and held keys.
        if (input.drag_x != 0 || input.drag_y != 0 || input.wheel != 0) {
            path_active = false;
            if (s.fly) {
                fly.look(input.drag_x, input.drag_y);
                fly.scroll_speed(input.wheel);
            } else {
                orbit.drag(input.drag_x, input.drag_y);
                orbit.zoom(input.wheel);
            }
            input.drag_x = input.drag_y = input.wheel = 0;
        }
        if (s.fly) {
            glm::dvec3 axes = req.fly;
            double seconds = o.fly_step_s;  // a scripted press is one step
            if (!scripted && !ImGui::GetIO().WantCaptureKeyboard) {
                for (int k : {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_E, GLFW_KEY_Q})
                    if (glfwGetKey(win, k) == GLFW_PRESS) axes += fly_axes(k);
                seconds = std::min(dt, 0.1);
            }
            if (axes != glm::dvec3(0.0)) {
                path_active = false;
                fly.move(axes, seconds);
            }
        }
        if (!scripted && s.vsync != vsync) {
            vsync = s.vsync;
            glfwSwapInterval(vsync ? 1 : 0);
        }

        // The camera: the path while it is active, else the fly or orbit camera.
        glm::dvec3 eye, look_at;
        if (path && path_active) {
            if (scripted)
                path_time = frame / path->fps;
            else if (playing)
                path_time = std::min(path_time + dt, path->duration());
            path->at(path_time, bounds, eye, look_at);
            if (const double fov = path->fov_at(path_time); fov > 0) cam.fov_deg = fov;
        } else if (s.fly) {
            eye = fly.eye;
            look_at = fly.eye + fly.forward() * look_distance;
        } else {
            eye = orbit.eye(bounds);
            look_at = orbit.centre(bounds);
        }
        Camera base = cam;
        base.width = ctx->width();
        base.height = ctx->height();
        if (base.width <= 0 || base.height <= 0) {  // minimized
            glfwWaitEventsTimeout(0.1);
            continue;
        }
        cam = make_camera(base, eye, look_at, bounds);
        const int W = cam.width, H = cam.height;
        // Interactive and nothing changed (no event, the same camera and settings, no path playing): the window
        // keeps the last frame, so none is drawn (a still view costs nothing). A few frames are drawn after each
        // event, for the panel to settle (hover, layout).
        if (input.changed) settle = 3;
        if (input.panel_changed) panel_settle = 3;
        input.changed = input.panel_changed = false;
        const bool moving = path && path_active && playing && path_time < path->duration();
        if (!scripted && settle == 0 && !moving && !req.screenshot && same_view(cam, drawn_cam) &&
            s == drawn_settings) {
            glfwWaitEventsTimeout(0.25);
            continue;
        }
        // The panel is rendered again (not shown from its cache) after an event it may show and while it settles
        // (not while the view is dragged), after a changed setting, and for a screenshot. A scripted run's hidden
        // window ignores its events (focus, cursor): its panel is rendered at the same frames from run to run, but for
        // the refresh interval.
        const bool panel_refresh = (!scripted && panel_settle > 0) || !(s == drawn_settings) || frame == 0 ||
                                   req.screenshot;
        if (panel_settle > 0) --panel_settle;
        if (settle > 0) --settle;
        drawn_cam = cam;
        drawn_settings = s;  // the panel may change s after the draw: the next frame then draws again

        // The frame. Its stages are timed (each waits for the GPU) in 1 frame of o.timed_every only: the others run
        // the GPU's work without waiting between stages, which on llvmpipe is most of a frame's cost.
        const bool timed_frame = o.timed_every <= 1 || drawn_frames % o.timed_every == 0;
        ++drawn_frames;
        renderer.set_timed(timed_frame);
        report = FrameReport{};
        const std::string no_raycast = s.method == RenderMethod::raycast ? loaded->raycast_unavailable() : "";
        if (!no_raycast.empty()) {
            report.note = no_raycast;
        } else if (s.method == RenderMethod::raycast) {
            // The truth as a still: ray cast again only when the camera or the settings changed.
            const bool settings_same = still_settings.discontinuity == s.discontinuity &&
                                       still_settings.threads == s.threads;
            if (!still_valid || !same_view(still_for, cam) || !settings_same) {
                const auto t0 = Clock::now();
                still_tex.upload(loaded->raycast(cam, s));
                report.times.texture_map_ms = ms_since(t0);
                report.times.total_ms = report.times.texture_map_ms;
                still_for = cam;
                still_valid = true;
                still_settings = s;
            }
        } else {
            ImageRGBA8 truth;
            if (s.split == SplitMode::truth) {
                ViewSettings t = s;
                t.method = RenderMethod::micromesh;
                FrameReport tr;
                renderer.begin_frame(cam);
                loaded->draw(renderer, cam, t, tr);
                truth = read_framebuffer(W, H);
            }
            renderer.begin_frame(cam);
            loaded->draw(renderer, cam, s, report);
            renderer.clear_if_pending();  // a frame with nothing drawn (every quad skipped) is still cleared
            if (s.split == SplitMode::truth) {
                ImageRGBA8 heat;
                diff_images(truth, read_framebuffer(W, H), &heat);
                heat_tex.upload(heat);
            } else if (s.split == SplitMode::method) {
                ViewSettings t = s;
                t.method = s.split_method;
                FrameReport tr;
                glEnable(GL_SCISSOR_TEST);
                glScissor(W / 2, 0, W - W / 2, H);
                renderer.begin_frame(cam);
                loaded->draw(renderer, cam, t, tr);
                renderer.clear_if_pending();
                glDisable(GL_SCISSOR_TEST);
            }
        }

        // Overlays and panel (Dear ImGui, in window units: framebuffer pixels / scale).
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        const ImGuiIO& io = ImGui::GetIO();
        const float scale = io.DisplayFramebufferScale.x > 0 ? io.DisplayFramebufferScale.x : 1.f;
        const float dw = io.DisplaySize.x, dh = io.DisplaySize.y;
        ImDrawList* bg = ImGui::GetBackgroundDrawList();
        if (!no_raycast.empty()) {
            clear_framebuffer(W, H);
        } else if (s.method == RenderMethod::raycast) {
            clear_framebuffer(W, H);
            bg->AddImage(imgui_texture(still_tex), ImVec2(0, 0), ImVec2(dw, dh));
        } else if (s.split != SplitMode::off) {
            if (s.split == SplitMode::truth)
                bg->AddImage(imgui_texture(heat_tex), ImVec2(dw / 2, 0), ImVec2(dw, dh), ImVec2(0.5f, 0), ImVec2(1, 1));
            bg->AddLine(ImVec2(dw / 2, 0), ImVec2(dw / 2, dh), IM_COL32(255, 255, 255, 200), 1.f);
        }
        if (s.outlines) draw_outlines(bg, cam, report, scale);
        glm::vec4 inset_box(0.f), panel_box(0.f);
        if (s.insets) inset_box = draw_insets(bg, report, dw, dh);
        if (s.panel) {
            PanelContext pc;
            pc.loaded_name = loaded->name();
            pc.loaded_kind = loaded->kind();
            pc.gl_renderer = result.renderer;
            pc.status = status.empty() ? report.note : report.note.empty() ? status : status + "\n" + report.note;
            pc.report = &report;
            pc.stats = &stats;
            pc.timed_stats = &timed_stats;
            pc.timed_every = std::max(o.timed_every, 1);
            pc.fly = &fly;
            pc.has_path = path.has_value();
            pc.path_time = &path_time;
            pc.path_duration = path ? path->duration() : 0;
            pc.playing = &playing;
            pc.ui_scale = imgui.ui_scale;
            const double before = path_time;
            KeyRequests buttons;  // the panel's buttons, apart from this frame's keys (already applied)
            panel_box = draw_panel(s, pc, buttons);
            if (path_time != before) path_active = true;  // scrubbed
            if (buttons.toggle_play && path) {
                playing = !playing;
                path_active = true;
            }
            if (buttons.frame) {
                path_active = false;
                s.fly ? fly.frame(bounds) : orbit.frame();
            }
            req.screenshot = req.screenshot || buttons.screenshot;
        }
        const bool last = scripted && frame == o.frames - 1;
        const auto t_overlay = Clock::now();
        ImGui::Render();
        panel_cache.render(ImGui::GetDrawData(), s.panel ? panel_box : glm::vec4(0.f), panel_refresh);
        if (timed_frame) glFinish();  // timed apart from the swap (which would wait for it anyway)
        const double overlay_ms = ms_since(t_overlay);
        result.panel = panel_box * scale;
        result.insets = inset_box * scale;

        if (req.screenshot || (last && !o.screenshot.empty())) {
            const std::string file = last && !o.screenshot.empty() ? o.screenshot : timestamped_name();
            write_rgba8(file, read_framebuffer(W, H));
            if (!scripted) std::fprintf(stderr, "screenshot: %s\n", file.c_str());
        }
        const auto t_swap = Clock::now();
        ctx->swap_buffers();
        const double swap_ms = ms_since(t_swap);

        FrameSample fs;
        fs.frame_ms = ms_since(t_frame);
        fs.stages = report.times;
        fs.texels_warped = report.texels_warped;
        stats.add(fs);
        if (timed_frame) timed_stats.add(fs);
        if (scripted && frame >= warm) {
            result.frame_ms.push_back(fs.frame_ms);
            result.texels_warped.push_back(fs.texels_warped);
        }
        if (scripted && frame >= warm && timed_frame) {
            result.prewarp_ms.push_back(fs.stages.prewarp_ms);
            result.upload_ms.push_back(fs.stages.upload_ms);
            result.texture_map_ms.push_back(fs.stages.texture_map_ms);
            result.other_ms.push_back(fs.other_ms());
            result.overlay_ms.push_back(overlay_ms);
            result.swap_ms.push_back(swap_ms);
        }
        result.frames = frame + 1;
        result.panel_renders = panel_cache.renders();
        result.panel_blits = panel_cache.blits();
        result.width = W;
        result.height = H;
        if (!scripted && std::chrono::duration<double>(Clock::now() - t_title).count() > 1.0) {
            char title[512];
            std::snprintf(title, sizeof title, "rtm view: %s | %s | %.1f fps", loaded->name().c_str(),
                          to_string(s.method).c_str(), stats.fps());
            glfwSetWindowTitle(win, title);
            t_title = Clock::now();
        }
    }
    if (scripted && result.frames > warm) {
        const double secs = std::chrono::duration<double>(Clock::now() - t_warm).count();
        result.fps = secs > 0 ? double(result.frames - warm) / secs : 0;
    }
    return result;
}

}  // namespace rtm::viewer
