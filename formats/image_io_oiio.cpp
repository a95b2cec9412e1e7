// Image files through OpenImageIO 2.4: the image backend (formats/image_backend.h), built as the module
// librtm_imageio.so that formats/image_io.cpp loads on first use.
//
// Reading checks the file itself (exists, is a regular file, is not empty, no PNG chunk or OpenEXR attribute
// claims more bytes than the file holds) and then the header's claimed size against kMaxImagePixels before any
// pixel buffer is allocated (formats/image_checks.h; docs/DESIGN.md, "Input limits"). Alpha stays unassociated
// ("oiio:UnassociatedAlpha"), so a PNG round trip is bit-exact and the colour of a texel with alpha 0 survives.
//
// Writing goes to a temporary file in the destination folder (same file system, so std::rename is atomic) and is
// renamed over `path` only when the writer reports success; on any failure the temporary file is removed.
#include "formats/image_backend.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <new>
#include <set>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "formats/atomic_file.h"
#include "formats/image_checks.h"

namespace rtm {
namespace {

static_assert(sizeof(Rgba8) == 4, "Rgba8 must be 4 tightly packed bytes");

#ifdef RTM_IMAGEIO_MODULE_BUILD
// The ids of this process's threads.
std::set<long> thread_ids() {
    std::set<long> ids;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator("/proc/self/task", ec))
        ids.insert(std::strtol(e.path().filename().c_str(), nullptr, 10));
    return ids;
}

// As the module (rtm's own programs), this code reads in a child process forked from the program
// (formats/image_io.cpp), which has the parent's memory but only the forking thread. A thread pool OpenImageIO or
// OpenEXR started in the parent would be there without its threads, and a read handing work to it would wait forever;
// a thread that held one of their locks as the program forked leaves it held in the child forever. So from the
// moment the module is loaded the program has no thread of theirs: OpenEXR's pool is never started ("exr_threads" -1:
// its global thread count stays 0), and OpenImageIO's pool is made empty ("threads" 1). OpenImageIO 2.4 creates that
// pool with one thread at least and, asked for none, tells the thread to end without waiting for it; the thread takes
// the pool's lock as it ends, and a fork meanwhile left a child spinning on that lock forever (reading TIFF files right
// after the module loaded: 9 reads in 10). So the loading waits until the threads that appeared have ended (at most
// 2 s: another part of the program may start a thread of its own meanwhile).
const bool g_no_library_threads = [] {
    const std::set<long> before = thread_ids();
    OIIO::attribute("exr_threads", -1);
    OIIO::attribute("threads", 1);
    for (int i = 0; i < 20000; ++i) {
        const std::set<long> now = thread_ids();
        if (std::includes(before.begin(), before.end(), now.begin(), now.end())) break;
        ::usleep(100);
    }
    return true;
}();
#endif

// OpenImageIO accumulates one error per line; join them into one line.
std::string one_line(const std::string& s) {
    std::string out;
    size_t start = 0;
    while (start <= s.size()) {
        size_t end = s.find('\n', start);
        if (end == std::string::npos) end = s.size();
        std::string line = s.substr(start, end - start);
        while (!line.empty() && (line.back() == ' ' || line.back() == '.' || line.back() == '\r')) line.pop_back();
        if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
        start = end + 1;
    }
    return out;
}

// libpng reports a corrupt file through OpenImageIO's error handler (which we turn into the IoError message) and
// then prints the same text as "libpng error: ..." on stderr itself, because OpenImageIO's handler returns. When the
// program opted in (set_quiet_image_library_stderr: `quiet`), an OpenImageIO call runs inside one of these, with
// stderr pointed at /dev/null; else it does nothing. The mutex keeps concurrent readers from restoring each other's
// descriptor out of order.
class QuietStderr {
public:
    explicit QuietStderr(bool quiet) {
        if (!quiet) return;
        lock_ = std::unique_lock<std::mutex>(mutex());
        std::fflush(stderr);
        saved_ = ::dup(STDERR_FILENO);
        int devnull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (saved_ >= 0 && devnull >= 0) ::dup2(devnull, STDERR_FILENO);
        if (devnull >= 0) ::close(devnull);
    }
    ~QuietStderr() {
        if (!lock_.owns_lock()) return;
        std::fflush(stderr);
        if (saved_ >= 0) {
            ::dup2(saved_, STDERR_FILENO);
            ::close(saved_);
        }
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

private:
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    std::unique_lock<std::mutex> lock_;
    int saved_ = -1;
};

// For a catch (...) around OpenImageIO: some of its readers throw on corrupt files instead of reporting an error
// (the SGI reader's std::length_error, "vector::_M_default_append", found by fuzz/fuzz_relief_loader).
std::string reader_exception() {
    try {
        throw;
    } catch (const std::bad_alloc&) {
        return "the reader ran out of memory (corrupt file?)";
    } catch (const std::exception& e) {
        return "the reader failed (" + one_line(e.what()) + "; corrupt file?)";
    } catch (...) {
        return "the reader failed (corrupt file?)";
    }
}

// An opened image whose size has been checked; `spec` describes subimage 0, mip level 0.
struct OpenedImage {
    std::unique_ptr<OIIO::ImageInput> in;
    OIIO::ImageSpec spec;
};

OpenedImage open_checked(const std::string& path, bool quiet) {
    const std::uintmax_t file_size = check_readable_file(path);
    check_container(path);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> in;
    try {
        QuietStderr silenced(quiet);
        in = OIIO::ImageInput::open(path, &config);
    } catch (...) {
        throw_io_error(path, "cannot read as an image: " + reader_exception());
    }
    if (!in) {
        std::string msg = one_line(OIIO::geterror());
        throw_io_error(path, "cannot read as an image" + (msg.empty() ? std::string() : ": " + msg));
    }
    OIIO::ImageSpec spec = in->spec();
    // Check the claimed size before anything allocates pixel memory.
    if (spec.depth > 1)
        throw_io_error(path, "is a volume image (depth " + std::to_string(spec.depth) + "), not a 2-D image");
    check_claimed_size(path, spec.width, spec.height, file_size);
    if (spec.nchannels < 1) throw_io_error(path, "image has no channels");
    return {std::move(in), spec};
}

// Reads the first `nch` channels of the whole image as `type` into `data`, whose pixels are `out_nch` >= nch
// channels apart (the channels past nch are left as they are).
void read_channels(const std::string& path, OpenedImage& im, int nch, int out_nch, OIIO::TypeDesc type, void* data,
                   bool quiet) {
    const OIIO::ImageSpec& s = im.spec;
    const OIIO::stride_t out_pixel = OIIO::stride_t(out_nch) * OIIO::stride_t(type.size());
    const OIIO::stride_t out_row = out_pixel * OIIO::stride_t(s.width);
    bool ok = true;
    try {
        QuietStderr silenced(quiet);
        if (s.tile_width == 0 && s.channelformats.empty() && s.format.size() > 0) {
            // A scanline file: read in its own format a band of rows at a time, and converted here into place.
            // OpenImageIO 2.4's read_image would convert through a 64 MB scratch buffer per call, whatever the
            // image's size (ImageInput::read_scanlines allocates it for any requested format but the "native"
            // UNKNOWN): untouched and cheap normally, but AddressSanitizer poisons all of it, which made every read
            // of a small image cost milliseconds in the sanitizer suite and the fuzzers. Bands of about 4 MB.
            const size_t file_row = s.scanline_bytes(true);  // all channels: what the reader decodes
            const size_t in_row = size_t(s.width) * size_t(nch) * s.format.size();
            const int band = int(std::clamp<size_t>((size_t(1) << 22) / std::max<size_t>(file_row, 1), 1,
                                                    size_t(s.height)));
            std::vector<unsigned char> buf(size_t(band) * in_row);
            for (int y = 0; ok && y < s.height; y += band) {
                const int rows = std::min(band, s.height - y);
                ok = im.in->read_scanlines(0, 0, s.y + y, s.y + y + rows, s.z, 0, nch, OIIO::TypeDesc::UNKNOWN,
                                           buf.data()) &&
                     OIIO::convert_image(nch, s.width, rows, 1, buf.data(), s.format, OIIO::AutoStride,
                                         OIIO::AutoStride, OIIO::AutoStride,
                                         static_cast<unsigned char*>(data) + size_t(y) * size_t(out_row), type,
                                         out_pixel, out_row, OIIO::AutoStride);
            }
        } else {
            ok = im.in->read_image(0, 0, 0, nch, type, data, out_pixel, out_row);
        }
    } catch (...) {
        throw_io_error(path, "cannot read pixels: " + reader_exception());
    }
    if (!ok) {
        std::string msg = one_line(im.in->geterror());
        throw_io_error(path, "cannot read pixels" +
                                 (msg.empty() ? std::string(" (file truncated or corrupt?)") : ": " + msg));
    }
    if (im.in->has_error()) throw_io_error(path, "cannot read pixels: " + one_line(im.in->geterror()));
}

// Writes `nch` channels of `type` from `data` with the format given by `path`'s extension, atomically.
void write_atomic(const std::string& path, int width, int height, int nch, OIIO::TypeDesc file_type,
                  OIIO::TypeDesc data_type, const void* data, bool has_alpha, bool quiet) {
    check_write_target(path, width, height);

    // The plug-in is chosen by the destination's extension; the temporary file gets the same plug-in.
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        std::string msg = one_line(OIIO::geterror());
        throw_io_error(path, "cannot write: no image writer for this file name" +
                                 (msg.empty() ? std::string() : " (" + msg + ")"));
    }
    int channels = nch;
    OIIO::stride_t xstride = OIIO::stride_t(nch) * OIIO::stride_t(data_type.size());
    if (has_alpha && !out->supports("alpha")) channels = 3;  // e.g. JPEG: drop alpha, keep colour
    OIIO::ImageSpec spec(width, height, channels, file_type);
    if (has_alpha && channels == 4) {
        spec.alpha_channel = 3;
        spec.attribute("oiio:UnassociatedAlpha", 1);  // our data is not premultiplied; write it as is
    }
    AtomicFile file(path);  // the temporary file is removed on every failure
    bool ok = false;
    std::string msg;
    {
        QuietStderr silenced(quiet);
        if (!out->open(file.temp_path(), spec)) {
            msg = one_line(out->geterror());
        } else {
            ok = out->write_image(data_type, data, xstride);
            if (!ok) msg = one_line(out->geterror());
            if (!out->close() && ok) {
                ok = false;
                msg = one_line(out->geterror());
            }
        }
        out.reset();
    }
    if (!ok) throw_io_error(path, "cannot write: " + msg);
    file.commit();
}

ImageRGBA8 read_rgba8(const std::string& path, bool quiet) {
    OpenedImage im = open_checked(path, quiet);
    const int nch = std::min(im.spec.nchannels, 4);
    ImageRGBA8 img(im.spec.width, im.spec.height);
    // Straight into the RGBA pixels, then filled out in place: no second image-sized buffer.
    read_channels(path, im, nch, 4, OIIO::TypeDesc::UINT8, img.pixels.data(), quiet);
    if (nch < 4) {
        for (Rgba8& d : img.pixels) {
            if (nch == 1) {
                d = {d.r, d.r, d.r, 255};
            } else if (nch == 2) {  // grey + alpha
                d = {d.r, d.r, d.r, d.g};
            } else {
                d.a = 255;
            }
        }
    }
    return img;
}

ImageF read_gray(const std::string& path, bool quiet) {
    OpenedImage im = open_checked(path, quiet);
    ImageF img(im.spec.width, im.spec.height);
    read_channels(path, im, 1, 1, OIIO::TypeDesc::FLOAT, img.pixels.data(), quiet);
    return img;
}

void write_rgba8(const std::string& path, const ImageRGBA8& img, bool quiet) {
    check_pixel_count(path, img.width, img.height, img.pixels.size());
    write_atomic(path, img.width, img.height, 4, OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT8, img.pixels.data(), true,
                 quiet);
}

void write_gray(const std::string& path, const ImageF& img, bool quiet) {
    check_pixel_count(path, img.width, img.height, img.pixels.size());
    std::vector<float> clamped(img.pixels.size());
    for (size_t i = 0; i < clamped.size(); ++i) {
        float v = img.pixels[i];
        clamped[i] = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
    }
    // 16 bits per sample; a format without 16-bit support (JPEG, ...) falls back to what it supports.
    write_atomic(path, img.width, img.height, 1, OIIO::TypeDesc::UINT16, OIIO::TypeDesc::FLOAT, clamped.data(), false,
                 quiet);
}

constexpr ImageBackend kBackend{read_rgba8, read_gray, write_rgba8, write_gray};

}  // namespace
}  // namespace rtm

extern "C" const rtm::ImageBackend* rtm_image_backend_v1() { return &rtm::kBackend; }
