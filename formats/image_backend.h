// The image backend: what reads and writes image files, behind formats/image_io.h, but for the usual PNG files
// (formats/png_io.h). One implementation, formats/image_io_oiio.cpp over OpenImageIO, built as the module
// librtm_imageio.so.
//
// Why a module: Debian's OpenImageIO brings about 260 shared libraries (OpenCV, FFmpeg, GDAL, ...), and loading them
// costs a process about 0.35 s at start (an empty program linked with OpenImageIO, on a Zen 5 guest; rtm --help took
// 0.45 s). rtm and the test programs load the module on the first image read or write instead, so a command that reads
// no image (a manifest error, --help, a test that renders procedural media) starts without that cost
// (docs/BENCHMARKS.md, "Start-up").
//
// The functions throw rtm::IoError as formats/image_io.h says; `quiet` is set_quiet_image_library_stderr's choice.
#pragma once

#include <string>

#include "formats/image_io.h"

namespace rtm {

struct ImageBackend {
    ImageRGBA8 (*read_rgba8)(const std::string& path, bool quiet);
    ImageF (*read_gray)(const std::string& path, bool quiet);
    void (*write_rgba8)(const std::string& path, const ImageRGBA8& img, bool quiet);
    void (*write_gray)(const std::string& path, const ImageF& img, bool quiet);
};

// Where rtm looks for the module (formats/image_io.cpp): $RTM_IMAGEIO_MODULE if set, else RTM_IMAGEIO_MODULE_DIR
// (the library folder relative to the binaries' folder, "../lib/rtm" for the usual layout; the build tree has the
// same layout) beside the running program, then where the build put it (for a program copied elsewhere).
inline constexpr const char* kImageModuleName = "librtm_imageio.so";

}  // namespace rtm

// The module's one exported symbol. A program that links image_io_oiio.cpp itself (the fuzzers, and programs built
// against the installed CMake package, which asks the linker for this symbol) uses that copy and loads no module.
// The name carries a version: a struct that changes gets a new name, so a stale module is refused, not misread.
// (image_io.cpp declares it weak.)
extern "C" const rtm::ImageBackend* rtm_image_backend_v1();
