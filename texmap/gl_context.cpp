// OpenGL 3.3 core contexts: OSMesa (headless, renders into a buffer we own) and a GLFW window.
//
// glad 2 keeps its GL function pointers in globals, so they belong to whichever context loaded them last. Each
// context records the loader it needs and make_current() reloads the pointers when a different context was
// current before; with one context per process (the usual case) the loading happens once.
#include "texmap/gl_context.h"

#include "texmap/llvmpipe_threads.h"

// glad must come first: it defines __gl_h_ so that osmesa.h's #include <GL/gl.h> is skipped. osmesa.h still needs
// the two calling-convention macros that GL/gl.h would have defined.
#include <glad/gl.h>
#ifndef GLAPI
#define GLAPI extern
#endif
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#include <GL/osmesa.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <sstream>
#include <vector>

namespace rtm {
namespace {

const void* g_loaded_for = nullptr;  // the context whose entry points glad holds

std::string gl_string(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "?";
}

// Loads the GL entry points for `owner` with `loader`; throws if the context is not at least GL 3.3.
void load_gl(const void* owner, GLADloadfunc loader, const char* backend) {
    if (g_loaded_for == owner) return;
    int version = gladLoadGL(loader);
    if (version == 0) {
        g_loaded_for = nullptr;
        throw GlError(std::string(backend) + ": cannot load the OpenGL entry points (gladLoadGL failed)");
    }
    const int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
    if (major < 3 || (major == 3 && minor < 3)) {
        g_loaded_for = nullptr;
        throw GlError(std::string(backend) + ": OpenGL 3.3 core is required but the context provides " +
                      std::to_string(major) + "." + std::to_string(minor) + " (" + gl_string(GL_VERSION) + ")");
    }
    g_loaded_for = owner;
}

void check_size(const char* backend, int width, int height) {
    // 16384 is the largest render target Mesa's llvmpipe accepts; a bigger request is a user error, not a crash.
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw GlError(std::string(backend) + ": cannot create a " + std::to_string(width) + "x" +
                      std::to_string(height) + " context (each side must be 1..16384)");
}

// ---------------------------------------------------------------------------------------------------------------
// OSMesa

class OsMesaContext final : public GlContext {
public:
    OsMesaContext(int width, int height, const ContextOptions& options) : width_(width), height_(height) {
        check_size("OSMesa", width, height);
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               24,
                               OSMESA_STENCIL_BITS,
                               0,
                               OSMESA_ACCUM_BITS,
                               0,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               3,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               3,
                               0};
        const std::vector<int> threads_before = options.pin_llvmpipe_threads ? process_threads() : std::vector<int>{};
        ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
        if (!ctx_)
            throw GlError(
                "OSMesa: cannot create an OpenGL 3.3 core context (OSMesaCreateContextAttribs failed; is "
                "Mesa's libOSMesa built with llvmpipe?)");
        buffer_.resize(size_t(width) * size_t(height) * 4);
        try {
            make_current();
        } catch (...) {
            OSMesaDestroyContext(ctx_);
            if (g_loaded_for == this) g_loaded_for = nullptr;
            throw;
        }
        if (options.pin_llvmpipe_threads) spread_llvmpipe_threads(threads_before);
    }
    ~OsMesaContext() override {
        if (OSMesaGetCurrentContext() == ctx_) OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
        OSMesaDestroyContext(ctx_);
        if (g_loaded_for == this) g_loaded_for = nullptr;
    }

    void make_current() override {
        if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
            throw GlError("OSMesa: cannot make the context current (OSMesaMakeCurrent failed for " +
                          std::to_string(width_) + "x" + std::to_string(height_) + ")");
        load_gl(this, reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress), "OSMesa");
    }
    int width() const override { return width_; }
    int height() const override { return height_; }
    std::string describe() const override {
        return "OSMesa (offscreen), " + gl_string(GL_RENDERER) + ", OpenGL " + gl_string(GL_VERSION);
    }

private:
    OSMesaContext ctx_ = nullptr;
    int width_, height_;
    std::vector<uint8_t> buffer_;  // the colour buffer OSMesa renders into (RGBA8, bottom row first)
};

// ---------------------------------------------------------------------------------------------------------------
// GLFW

std::mutex g_glfw_mutex;
int g_glfw_users = 0;
std::string g_glfw_last_error;

void glfw_error_callback(int code, const char* description) {
    g_glfw_last_error = description ? description : ("GLFW error " + std::to_string(code));
}

std::string take_glfw_error() {
    std::string e = g_glfw_last_error;
    g_glfw_last_error.clear();
    return e.empty() ? std::string("unknown GLFW error") : e;
}

bool have_display() {
    const char* x = std::getenv("DISPLAY");
    const char* w = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (w && *w);
}

class GlfwContext final : public GlContext {
public:
    GlfwContext(int width, int height, const std::string& title, bool visible, const ContextOptions& options) {
        check_size("GLFW", width, height);
        {
            std::lock_guard<std::mutex> lock(g_glfw_mutex);
            glfwSetErrorCallback(glfw_error_callback);
            if (g_glfw_users == 0) {
                if (!have_display())
                    throw GlError(
                        "cannot open a window: no display (set DISPLAY, or run under xvfb-run; rtm render draws "
                        "without one)");
                if (!glfwInit()) throw GlError("cannot open a window: glfwInit failed: " + take_glfw_error());
            }
            ++g_glfw_users;
        }
        glfwDefaultWindowHints();
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
        glfwWindowHint(GLFW_DEPTH_BITS, 24);
        glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
        const std::vector<int> threads_before = options.pin_llvmpipe_threads ? process_threads() : std::vector<int>{};
        window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
        if (!window_) {
            std::string e = take_glfw_error();
            release_glfw();
            throw GlError("cannot open a window: no OpenGL 3.3 core context (" + e + ")");
        }
        try {
            make_current();
        } catch (...) {
            glfwDestroyWindow(window_);
            if (g_loaded_for == this) g_loaded_for = nullptr;
            release_glfw();
            throw;
        }
        glfwSwapInterval(0);
        if (options.pin_llvmpipe_threads) spread_llvmpipe_threads(threads_before);
    }
    ~GlfwContext() override {
        if (glfwGetCurrentContext() == window_) glfwMakeContextCurrent(nullptr);
        glfwDestroyWindow(window_);
        if (g_loaded_for == this) g_loaded_for = nullptr;
        release_glfw();
    }

    void make_current() override {
        glfwMakeContextCurrent(window_);
        if (glfwGetCurrentContext() != window_)
            throw GlError("GLFW: cannot make the window's context current: " + take_glfw_error());
        load_gl(this, reinterpret_cast<GLADloadfunc>(glfwGetProcAddress), "GLFW");
    }
    // The framebuffer size, in pixels (it differs from the window size on high-DPI screens).
    int width() const override {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        return w;
    }
    int height() const override {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        return h;
    }
    void swap_buffers() override { glfwSwapBuffers(window_); }
    bool should_close() override { return glfwWindowShouldClose(window_); }
    void poll_events() override { glfwPollEvents(); }
    void* native_window() override { return window_; }
    std::string describe() const override {
        return "GLFW window, " + gl_string(GL_RENDERER) + ", OpenGL " + gl_string(GL_VERSION);
    }

private:
    static void release_glfw() {
        std::lock_guard<std::mutex> lock(g_glfw_mutex);
        if (--g_glfw_users == 0) glfwTerminate();
    }
    GLFWwindow* window_ = nullptr;
};

const char* gl_error_name(GLenum e) {
    switch (e) {
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        default: return nullptr;
    }
}

}  // namespace

std::unique_ptr<GlContext> GlContext::create_offscreen(int width, int height, const ContextOptions& options) {
    return std::make_unique<OsMesaContext>(width, height, options);
}

std::unique_ptr<GlContext> GlContext::create_window(int width, int height, const std::string& title, bool visible,
                                                    const ContextOptions& options) {
    return std::make_unique<GlfwContext>(width, height, title, visible, options);
}

void check_gl(const char* what) {
    if (!glad_glGetError) throw GlError(std::string(what) + ": no OpenGL context was made current");
    GLenum first = glGetError();
    if (first == GL_NO_ERROR) return;
    // Drain the remaining flags so the next check starts clean.
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {
    }
    std::ostringstream os;
    os << what << ": OpenGL error ";
    if (const char* name = gl_error_name(first))
        os << name;
    else
        os << "0x" << std::hex << first;
    throw GlError(os.str());
}

}  // namespace rtm
