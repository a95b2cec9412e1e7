// Image files through OpenImageIO 2.4.
//
// Reading checks the file itself (exists, is a regular file, is not empty) and then the header's claimed size
// against kMaxImagePixels before any pixel buffer is allocated. Alpha stays unassociated ("oiio:UnassociatedAlpha"),
// so a PNG round trip is bit-exact and the colour of a texel with alpha 0 survives.
//
// Writing goes to a temporary file in the destination folder (same file system, so std::rename is atomic) and is
// renamed over `path` only when the writer reports success; on any failure the temporary file is removed.
#include "texmap/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace rtm {
namespace {

namespace fs = std::filesystem;

static_assert(sizeof(Rgba8) == 4, "Rgba8 must be 4 tightly packed bytes");

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw IoError(path + ": " + what); }

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
// then prints the same text as "libpng error: ..." on stderr itself, because OpenImageIO's handler returns. The
// command line promises one line on stderr per failure, so file reads and writes run with stderr pointed at
// /dev/null. The mutex keeps concurrent readers from restoring each other's descriptor out of order.
class QuietStderr {
public:
    QuietStderr() : lock_(mutex()) {
        std::fflush(stderr);
        saved_ = ::dup(STDERR_FILENO);
        int devnull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (saved_ >= 0 && devnull >= 0) ::dup2(devnull, STDERR_FILENO);
        if (devnull >= 0) ::close(devnull);
    }
    ~QuietStderr() {
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
    std::lock_guard<std::mutex> lock_;
    int saved_ = -1;
};

void check_readable_file(const std::string& path) {
    std::error_code ec;
    fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) {
        int err = ec ? ec.value() : ENOENT;
        fail(path, std::string("cannot open: ") + std::strerror(err));
    }
    if (fs::is_directory(st)) fail(path, "is a directory");
    if (!fs::is_regular_file(st)) fail(path, "is not a regular file");
    auto size = fs::file_size(path, ec);
    if (ec) fail(path, "cannot open: " + ec.message());
    if (size == 0) fail(path, "file is empty");
}

// An opened image whose size has been checked; `spec` describes subimage 0, mip level 0.
struct OpenedImage {
    std::unique_ptr<OIIO::ImageInput> in;
    OIIO::ImageSpec spec;
};

OpenedImage open_checked(const std::string& path) {
    check_readable_file(path);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> in;
    {
        QuietStderr quiet;
        in = OIIO::ImageInput::open(path, &config);
    }
    if (!in) {
        std::string msg = one_line(OIIO::geterror());
        fail(path, "cannot read as an image" + (msg.empty() ? std::string() : ": " + msg));
    }
    OIIO::ImageSpec spec = in->spec();
    // Check the claimed size before anything allocates pixel memory.
    if (spec.width <= 0 || spec.height <= 0)
        fail(path, "image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height));
    if (spec.depth > 1) fail(path, "is a volume image (depth " + std::to_string(spec.depth) + "), not a 2-D image");
    if ((long long)spec.width * (long long)spec.height > kMaxImagePixels)
        fail(path, "image claims " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                       " pixels, more than the limit of 16384x16384");
    if (spec.nchannels < 1) fail(path, "image has no channels");
    return {std::move(in), spec};
}

void read_channels(const std::string& path, OpenedImage& im, int nch, OIIO::TypeDesc type, void* data) {
    bool ok;
    {
        QuietStderr quiet;
        ok = im.in->read_image(0, 0, 0, nch, type, data);
    }
    if (!ok) {
        std::string msg = one_line(im.in->geterror());
        fail(path, "cannot read pixels" + (msg.empty() ? std::string(" (file truncated or corrupt?)") : ": " + msg));
    }
    if (im.in->has_error()) fail(path, "cannot read pixels: " + one_line(im.in->geterror()));
}

// Temporary file beside `path`, unique per process and call.
std::string temp_name_for(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    fs::path p(path);
    fs::path dir = p.parent_path();
    // Built with += : GCC 12 gives a false -Wrestrict warning for "." + std::string&&.
    std::string name = ".";
    name += p.filename().string();
    name += ".tmp";
    name += std::to_string(::getpid());
    name += "-";
    name += std::to_string(counter.fetch_add(1));
    return (dir / name).string();
}

// Writes `nch` channels of `type` from `data` with the format given by `path`'s extension, atomically.
void write_atomic(const std::string& path, int width, int height, int nch, OIIO::TypeDesc file_type,
                  OIIO::TypeDesc data_type, const void* data, bool has_alpha) {
    if (width <= 0 || height <= 0)
        fail(path, "cannot write an empty image (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    std::error_code ec;
    if (fs::is_directory(path, ec)) fail(path, "is a directory");
    fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec))
        fail(path, "cannot write: folder " + parent.string() + " does not exist");

    // The plug-in is chosen by the destination's extension; the temporary file gets the same plug-in.
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        std::string msg = one_line(OIIO::geterror());
        fail(path, "cannot write: no image writer for this file name" +
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
    const std::string tmp = temp_name_for(path);
    auto remove_tmp = [&] {
        std::error_code ignore;
        fs::remove(tmp, ignore);
    };
    bool ok = false;
    std::string msg;
    {
        QuietStderr quiet;
        if (!out->open(tmp, spec)) {
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
    if (!ok) {
        remove_tmp();
        fail(path, "cannot write: " + msg);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        int err = errno;
        remove_tmp();
        fail(path, std::string("cannot write: rename from temporary file failed: ") + std::strerror(err));
    }
}

}  // namespace

ImageRGBA8 read_rgba8(const std::string& path) {
    OpenedImage im = open_checked(path);
    const int w = im.spec.width, h = im.spec.height, nch = im.spec.nchannels;
    ImageRGBA8 img(w, h);
    if (nch >= 4) {
        read_channels(path, im, 4, OIIO::TypeDesc::UINT8, img.pixels.data());
    } else {
        const size_t n = size_t(w) * size_t(h);
        std::vector<uint8_t> buf(n * size_t(nch));
        read_channels(path, im, nch, OIIO::TypeDesc::UINT8, buf.data());
        for (size_t i = 0; i < n; ++i) {
            const uint8_t* s = &buf[i * size_t(nch)];
            Rgba8& d = img.pixels[i];
            if (nch == 1) {
                d = {s[0], s[0], s[0], 255};
            } else if (nch == 2) {  // grey + alpha
                d = {s[0], s[0], s[0], s[1]};
            } else {
                d = {s[0], s[1], s[2], 255};
            }
        }
    }
    return img;
}

ImageF read_gray(const std::string& path) {
    OpenedImage im = open_checked(path);
    ImageF img(im.spec.width, im.spec.height);
    read_channels(path, im, 1, OIIO::TypeDesc::FLOAT, img.pixels.data());
    return img;
}

void write_rgba8(const std::string& path, const ImageRGBA8& img) {
    if (img.pixels.size() != size_t(std::max(img.width, 0)) * size_t(std::max(img.height, 0)))
        fail(path, "cannot write: image claims " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                       " but holds " + std::to_string(img.pixels.size()) + " pixels");
    write_atomic(path, img.width, img.height, 4, OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT8, img.pixels.data(),
                 true);
}

void write_gray(const std::string& path, const ImageF& img) {
    if (img.pixels.size() != size_t(std::max(img.width, 0)) * size_t(std::max(img.height, 0)))
        fail(path, "cannot write: image claims " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                       " but holds " + std::to_string(img.pixels.size()) + " pixels");
    std::vector<float> clamped(img.pixels.size());
    for (size_t i = 0; i < clamped.size(); ++i) {
        float v = img.pixels[i];
        clamped[i] = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
    }
    // 16 bits per sample; a format without 16-bit support (JPEG, ...) falls back to what it supports.
    write_atomic(path, img.width, img.height, 1, OIIO::TypeDesc::UINT16, OIIO::TypeDesc::FLOAT, clamped.data(),
                 false);
}

}  // namespace rtm
