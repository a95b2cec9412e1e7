// Image files: formats/image_io.h's functions. The usual PNG files go through libpng here (formats/png_io.h); the
// others are forwarded to the image backend (formats/image_backend.h), the program's own copy of image_io_oiio.cpp if
// it links one, else the module librtm_imageio.so, loaded on the first such call (not at start: see image_backend.h
// for the cost that avoids).
#include "formats/image_io.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "formats/image_backend.h"
#include "formats/png_io.h"

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

// The module where the build put it: a program copied elsewhere (build/bin/rtm to ~/bin) still finds it there.
#ifndef RTM_IMAGEIO_MODULE_BUILT
#define RTM_IMAGEIO_MODULE_BUILT ""
#endif

// Where to look: $RTM_IMAGEIO_MODULE alone if set; else beside the running program, then where the build put it.
std::vector<std::string> module_candidates(std::string& error) {
    if (const char* env = std::getenv("RTM_IMAGEIO_MODULE"); env && *env) return {env};
    std::vector<std::string> paths;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec)
        error = "/proc/self/exe: " + ec.message();
    else
        paths.push_back((exe.parent_path() / RTM_IMAGEIO_MODULE_DIR / kImageModuleName).lexically_normal().string());
    const std::string built = RTM_IMAGEIO_MODULE_BUILT;
    if (!built.empty() && (paths.empty() || paths[0] != built)) paths.push_back(built);
    return paths;
}

LoadedBackend load_module() {
    std::string tried;
    for (const std::string& path : module_candidates(tried)) {
        if (void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
            auto entry = reinterpret_cast<const ImageBackend* (*)()>(::dlsym(handle, "rtm_image_backend_v1"));
            if (!entry)
                return {nullptr, "the image module " + path + " is not this version's (no rtm_image_backend_v1)"};
            return {entry(), {}};
        }
        const char* why = ::dlerror();
        tried += (tried.empty() ? "" : "; ") + std::string(why ? why : path);
    }
    return {nullptr,
            "cannot load the image module (" + tried + "); set RTM_IMAGEIO_MODULE to the path of " + kImageModuleName};
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

// PNG files of the usual kinds through libpng (formats/png_io.h), everything else through the backend.
ImageRGBA8 read_rgba8(const std::string& path) {
    ImageRGBA8 img;
    if (png::read_rgba8(path, img)) return img;
    return backend(path).read_rgba8(path, g_quiet_stderr.load());
}
ImageF read_gray(const std::string& path) {
    ImageF img;
    if (png::read_gray(path, img)) return img;
    return backend(path).read_gray(path, g_quiet_stderr.load());
}
void write_rgba8(const std::string& path, const ImageRGBA8& img) {
    if (png::writes(path)) return png::write_rgba8(path, img);
    backend(path).write_rgba8(path, img, g_quiet_stderr.load());
}
void write_gray(const std::string& path, const ImageF& img) {
    if (png::writes(path)) return png::write_gray(path, img);
    backend(path).write_gray(path, img, g_quiet_stderr.load());
}

}  // namespace rtm
