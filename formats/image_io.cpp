// Image files: formats/image_io.h's functions, forwarded to the image backend (formats/image_backend.h). The backend
// is the program's own copy of image_io_oiio.cpp if it links one, else the module librtm_imageio.so, loaded on the
// first call (not at start: see image_backend.h for the cost that avoids).
#include "formats/image_io.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "formats/image_backend.h"

// Weak: null unless the program links image_io_oiio.cpp itself (and then taken from an archive only when the program
// asks for it, as formats/CMakeLists.txt says).
extern "C" __attribute__((weak)) const rtm::ImageBackend* rtm_image_backend_v1();

#ifndef RTM_IMAGEIO_MODULE_DIR
#error "RTM_IMAGEIO_MODULE_DIR: the module's folder relative to the programs' folder (formats/CMakeLists.txt)"
#endif

namespace rtm {
namespace {

std::atomic<bool> g_quiet_stderr{false};

struct LoadedBackend {
    const ImageBackend* api = nullptr;
    std::string error;  // why api is null
};

LoadedBackend load_module() {
    std::string path;
    if (const char* env = std::getenv("RTM_IMAGEIO_MODULE"); env && *env) {
        path = env;
    } else {
        std::error_code ec;
        const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (ec)
            return {nullptr, "cannot find the running program to find " + std::string(kImageModuleName) +
                                 " beside it (/proc/self/exe: " + ec.message() + "); set RTM_IMAGEIO_MODULE"};
        path = (exe.parent_path() / RTM_IMAGEIO_MODULE_DIR / kImageModuleName).lexically_normal().string();
    }
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = ::dlerror();
        return {nullptr, "cannot load the image module (" + std::string(why ? why : path) +
                             "); set RTM_IMAGEIO_MODULE to the path of " + kImageModuleName};
    }
    auto entry = reinterpret_cast<const ImageBackend* (*)()>(::dlsym(handle, "rtm_image_backend_v1"));
    if (!entry) return {nullptr, "the image module " + path + " is not this version's (no rtm_image_backend_v1)"};
    return {entry(), {}};
}

// `path`: the file the caller was about to read or write, for the error if there is no backend.
const ImageBackend& backend(const std::string& path) {
    static const LoadedBackend loaded = rtm_image_backend_v1 != nullptr ? LoadedBackend{rtm_image_backend_v1(), {}}
                                                                        : load_module();
    if (!loaded.api) throw_io_error(path, loaded.error);
    return *loaded.api;
}

}  // namespace

void set_quiet_image_library_stderr(bool on) { g_quiet_stderr = on; }
bool quiet_image_library_stderr() { return g_quiet_stderr.load(); }

ImageRGBA8 read_rgba8(const std::string& path) { return backend(path).read_rgba8(path, g_quiet_stderr.load()); }
ImageF read_gray(const std::string& path) { return backend(path).read_gray(path, g_quiet_stderr.load()); }
void write_rgba8(const std::string& path, const ImageRGBA8& img) {
    backend(path).write_rgba8(path, img, g_quiet_stderr.load());
}
void write_gray(const std::string& path, const ImageF& img) {
    backend(path).write_gray(path, img, g_quiet_stderr.load());
}

}  // namespace rtm
