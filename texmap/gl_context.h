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
    virtual std::string describe() const = 0;           // back end, GL_RENDERER, GL_VERSION

    static std::unique_ptr<GlContext> create_offscreen(int width, int height);
    static std::unique_ptr<GlContext> create_window(int width, int height, const std::string& title, bool visible = true);
};

// Throws GlError naming `what` if glGetError reports an error.
void check_gl(const char* what);

}  // namespace rtm
