// One OpenGL 3.3 core context abstraction with two back ends: OSMesa (headless, software llvmpipe; the default
// everywhere) and a GLFW window. Both load GL entry points through the glad 2 loader generated at build time.
// Creation failures throw rtm::GlError with a message that says what failed.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace rtm {

struct GlError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// What creating a context may do to the whole process; each effect is opt-in.
struct ContextOptions {
    // Pin llvmpipe's rasterizer threads one per CPU once the context exists (spread_llvmpipe_threads,
    // texmap/llvmpipe_threads.h): changes the CPU affinity of threads of the whole process (every later context of
    // the process shares them) and may wait up to 50 ms for new threads to name themselves. It makes the texture
    // mapping's times steady on a 2-core machine and changes no pixel; for the tools that time frames (rtm bench,
    // bench-skips, compare, render, view). Off: the threads keep the process's mask.
    bool pin_llvmpipe_threads = false;
};

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual void make_current() = 0;
    virtual int width() const = 0;
    virtual int height() const = 0;
    virtual void swap_buffers() {}
    virtual bool should_close() { return false; }  // window closed by the user
    virtual void poll_events() {}
    virtual void* native_window() { return nullptr; }  // GLFWwindow* for the window back end
    virtual std::string describe() const = 0;          // back end, GL_RENDERER, GL_VERSION

    static std::unique_ptr<GlContext> create_offscreen(int width, int height, const ContextOptions& options = {});
    static std::unique_ptr<GlContext> create_window(int width, int height, const std::string& title,
                                                    bool visible = true, const ContextOptions& options = {});
};

// Throws GlError naming `what` if glGetError reports an error.
void check_gl(const char* what);

}  // namespace rtm
