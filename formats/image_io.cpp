// Image files: formats/image_io.h's functions. The usual PNG files go through libpng here (formats/png_io.h); the
// others are forwarded to the image backend (formats/image_backend.h), the program's own copy of image_io_oiio.cpp if
// it links one, else the module librtm_imageio.so, loaded on the first such call (not at start: see image_backend.h
// for the cost that avoids).
//
// The module reads in a child process (formats/isolated_call.h): OpenImageIO 2.4's readers of the less common formats
// are not safe on hostile files (random changes to images it writes itself corrupt the heap in its IFF reader within
// minutes, and make its RLA reader loop), and a crash, abort or endless loop there must end a child, not rtm. Forked
// from this process, the child has the module loaded already (loading it takes 0.35 s); the module keeps OpenImageIO
// and OpenEXR from starting threads in this process (image_io_oiio.cpp), since the child would have their pools
// without the threads. A program that links the backend itself (the fuzzers, programs built against the installed
// package) reads in its own process: it configures OpenImageIO as it likes, and the fuzzers must see the readers'
// faults.
#include "formats/image_io.h"

#include <dlfcn.h>
#include <pthread.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>
#include <vector>

#include "formats/image_backend.h"
#include "formats/isolated_call.h"
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
    std::string error;     // why api is null
    bool isolate = false;  // the module: reads go to a child (above)
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
            return {entry(), {}, true};
        }
        const char* why = ::dlerror();
        tried += (tried.empty() ? "" : "; ") + std::string(why ? why : path);
    }
    return {nullptr,
            "cannot load the image module (" + tried + "); set RTM_IMAGEIO_MODULE to the path of " + kImageModuleName};
}

// Held by this process's calls into the module (writes) and across every fork (pthread_atfork), so that no child
// starts with a lock of OpenImageIO's held by a thread it does not have.
std::mutex g_module_calls;

// `path`: the file the caller was about to read or write, for the error if there is no backend.
const LoadedBackend& loaded_backend(const std::string& path) {
    static const LoadedBackend loaded = [] {
        if (rtm_image_backend_v1 != nullptr) return LoadedBackend{rtm_image_backend_v1(), {}, false};
        LoadedBackend m = load_module();
        if (m.api)
            ::pthread_atfork([] { g_module_calls.lock(); }, [] { g_module_calls.unlock(); },
                             [] { g_module_calls.unlock(); });
        return m;
    }();
    if (!loaded.api) throw_io_error(path, loaded.error);
    return loaded;
}

// A read by the backend: in a child when the backend is the module (above), returning the image through its bytes.
constexpr IsolatedReader kImageReader{"cannot read as an image", "the image reader (OpenImageIO)",
                                      "RTM_IMAGE_READER_MB", "RTM_IMAGE_READER_SECONDS"};

template <class Pixel>
Image2D<Pixel> read_with_backend(const std::string& path,
                                 Image2D<Pixel> (*const ImageBackend::*read)(const std::string&, bool)) {
    const LoadedBackend& b = loaded_backend(path);
    const bool quiet = g_quiet_stderr.load();
    if (!b.isolate) return (b.api->*read)(path, quiet);
    std::error_code ec;
    const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);  // the child says what is wrong, if any
    constexpr size_t kHeader = 2 * sizeof(std::int32_t);
    const IsolatedOutcome r = read_isolated(
        path, ec ? 0 : std::uint64_t(file_bytes), kImageReader,
        [&](const ResultWriter& out) {
            const Image2D<Pixel> img = (b.api->*read)(path, false);  // the child's stderr is a file the parent reads
            const std::int32_t size[2] = {img.width, img.height};
            out.write(size, kHeader);
            out.write(img.pixels.data(), img.pixels.size() * sizeof(Pixel));
        },
        !quiet);
    std::int32_t size[2] = {0, 0};
    if (r.bytes.size() >= kHeader) std::memcpy(size, r.bytes.data(), kHeader);
    if (r.bytes.size() < kHeader || size[0] < 0 || size[1] < 0 ||
        r.bytes.size() - kHeader != size_t(size[0]) * size_t(size[1]) * sizeof(Pixel))
        throw_io_error(path, "cannot read as an image: the image reader's result is damaged (" +
                                 std::to_string(r.bytes.size()) + " bytes)");
    Image2D<Pixel> img;
    img.width = size[0];
    img.height = size[1];
    img.pixels.resize(size_t(size[0]) * size_t(size[1]));
    std::memcpy(img.pixels.data(), r.bytes.data() + kHeader, img.pixels.size() * sizeof(Pixel));
    return img;
}

template <class Image>
void write_with_backend(const std::string& path, const Image& img,
                        void (*const ImageBackend::*write)(const std::string&, const Image&, bool)) {
    const LoadedBackend& b = loaded_backend(path);
    std::unique_lock<std::mutex> lock(g_module_calls, std::defer_lock);
    if (b.isolate) lock.lock();
    (b.api->*write)(path, img, g_quiet_stderr.load());
}

}  // namespace

void set_quiet_image_library_stderr(bool on) { g_quiet_stderr = on; }
bool quiet_image_library_stderr() { return g_quiet_stderr.load(); }

// PNG files of the usual kinds through libpng (formats/png_io.h), everything else through the backend.
ImageRGBA8 read_rgba8(const std::string& path) {
    ImageRGBA8 img;
    if (png::read_rgba8(path, img)) return img;
    return read_with_backend(path, &ImageBackend::read_rgba8);
}
ImageF read_gray(const std::string& path) {
    ImageF img;
    if (png::read_gray(path, img)) return img;
    return read_with_backend(path, &ImageBackend::read_gray);
}
void write_rgba8(const std::string& path, const ImageRGBA8& img) {
    if (png::writes(path)) return png::write_rgba8(path, img);
    write_with_backend(path, img, &ImageBackend::write_rgba8);
}
void write_gray(const std::string& path, const ImageF& img) {
    if (png::writes(path)) return png::write_gray(path, img);
    write_with_backend(path, img, &ImageBackend::write_gray);
}

}  // namespace rtm
