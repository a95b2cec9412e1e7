// PNG files through libpng (formats/png_io.h).
//
// libpng reports errors by calling an error function that must not return: here it records the message and longjmps
// back to the setjmp of the function that called libpng (ReadHeader, ReadRows, WriteRows). Those functions hold
// nothing that needs a destructor between their setjmp and the libpng calls, and everything the longjmp skips is
// libpng's own C frames. The structs, the file and the buffers belong to their callers (PngFile and vectors), freed
// however the calls end. Warnings are dropped (the module's reader prints none either when asked to be quiet; a
// warning never changes the pixels read).
#include "formats/png_io.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "formats/atomic_file.h"
#include "formats/image_checks.h"

namespace rtm::png {
namespace {

// libpng's error message, kept by the error function (which must not return: it longjmps).
struct ErrorSink {
    char message[256] = {};
};

[[noreturn]] void on_error(png_structp p, png_const_charp msg) {
    auto* sink = static_cast<ErrorSink*>(png_get_error_ptr(p));
    std::snprintf(sink->message, sizeof(sink->message), "%s", msg ? msg : "libpng error");
    png_longjmp(p, 1);
}

void on_warning(png_structp, png_const_charp) {}

std::string libpng_message(const ErrorSink& sink) {
    return sink.message[0] ? std::string(sink.message) : std::string("libpng error");
}

// A file and the libpng structs reading or writing it, freed however the calls end.
struct PngFile {
    explicit PngFile(bool writing) : writing(writing) {}
    ~PngFile() {
        if (png && writing) png_destroy_write_struct(&png, info ? &info : nullptr);
        if (png && !writing) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
        if (file) std::fclose(file);
    }
    PngFile(const PngFile&) = delete;
    PngFile& operator=(const PngFile&) = delete;

    const bool writing;
    std::FILE* file = nullptr;
    png_structp png = nullptr;
    png_infop info = nullptr;
    ErrorSink error;
};

struct Header {
    png_uint_32 width = 0, height = 0;
    int bit_depth = 0, color_type = 0, interlace = 0;
    bool trns = false;
};

// The header (after the 8-byte signature, already read). False on a libpng error (the message in r.error).
bool ReadHeader(PngFile& r, Header& h) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    png_init_io(r.png, r.file);
    png_set_sig_bytes(r.png, 8);
    png_read_info(r.png, r.info);
    png_get_IHDR(r.png, r.info, &h.width, &h.height, &h.bit_depth, &h.color_type, &h.interlace, nullptr, nullptr);
    h.trns = png_get_valid(r.png, r.info, PNG_INFO_tRNS) != 0;
    return true;
}

// Reads the rows one by one into `row` (the file's layout) and hands each to put(y, row). False on a libpng error.
template <class Put>
bool ReadRows(PngFile& r, png_uint_32 height, unsigned char* row, const Put& put) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    for (png_uint_32 y = 0; y < height; ++y) {
        png_read_row(r.png, row, nullptr);
        put(size_t(y), row);
    }
    return true;
}

// Opens `path` for reading and reads its header if it is a PNG of a kind read here (png_io.h); false otherwise. Throws
// IoError for a file that is missing, empty, oversized or corrupt.
bool open_png(const std::string& path, PngFile& r, Header& h) {
    const std::uintmax_t file_size = check_readable_file(path);
    r.file = std::fopen(path.c_str(), "rb");
    if (!r.file) return false;  // the module reports it
    unsigned char sig[8];
    if (std::fread(sig, 1, 8, r.file) != 8 || png_sig_cmp(sig, 0, 8) != 0) return false;
    check_container(path);
    r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r.error, on_error, on_warning);
    if (!r.png) throw_io_error(path, "cannot read as an image: libpng could not start (out of memory?)");
    r.info = png_create_info_struct(r.png);
    if (!r.info) throw_io_error(path, "cannot read as an image: libpng could not start (out of memory?)");
    if (!ReadHeader(r, h)) throw_io_error(path, "cannot read as an image: " + libpng_message(r.error));
    const bool kind = (h.bit_depth == 8 || h.bit_depth == 16) && h.interlace == PNG_INTERLACE_NONE && !h.trns &&
                      (h.color_type == PNG_COLOR_TYPE_GRAY || h.color_type == PNG_COLOR_TYPE_GRAY_ALPHA ||
                       h.color_type == PNG_COLOR_TYPE_RGB || h.color_type == PNG_COLOR_TYPE_RGB_ALPHA);
    if (!kind) return false;
    check_claimed_size(path, (long long)h.width, (long long)h.height, file_size);
    return true;
}

int channels_of(int color_type) {
    switch (color_type) {
        case PNG_COLOR_TYPE_GRAY: return 1;
        case PNG_COLOR_TYPE_GRAY_ALPHA: return 2;
        case PNG_COLOR_TYPE_RGB: return 3;
        default: return 4;
    }
}

// Sample i of a row of 16-bit big-endian samples.
inline unsigned sample16(const unsigned char* row, size_t i) { return unsigned(row[2 * i]) << 8 | row[2 * i + 1]; }

// Reads `path` into `out` if it is a PNG of a kind read here (open_png), each row converted into place by
// convert(image, y, row, channels, bytes a sample); false otherwise.
template <class Image, class Convert>
bool read_png(const std::string& path, Image& out, const Convert& convert) {
    PngFile r(false);
    Header h;
    if (!open_png(path, r, h)) return false;
    const int nch = channels_of(h.color_type), bytes = h.bit_depth / 8;
    std::vector<unsigned char> row(size_t(h.width) * size_t(nch) * size_t(bytes));
    Image img(int(h.width), int(h.height));
    auto put = [&](size_t y, const unsigned char* src) { convert(img, y, src, nch, bytes); };
    if (!ReadRows(r, h.height, row.data(), put)) throw_io_error(path, "cannot read pixels: " + libpng_message(r.error));
    out = std::move(img);
    return true;
}

// Writes the header and the rows (get(y, row) fills row y in the file's layout). False on a libpng error.
template <class Get>
bool WriteRows(PngFile& w, int width, int height, int bit_depth, int color_type, unsigned char* row, const Get& get) {
    if (setjmp(png_jmpbuf(w.png))) return false;
    png_init_io(w.png, w.file);
    png_set_IHDR(w.png, w.info, png_uint_32(width), png_uint_32(height), bit_depth, color_type, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(w.png, w.info);
    for (int y = 0; y < height; ++y) {
        get(size_t(y), row);
        png_write_row(w.png, row);
    }
    png_write_end(w.png, nullptr);
    return true;
}

// Writes `path` atomically (a temporary file renamed on success), rows from get(y, row).
template <class Get>
void write_png(const std::string& path, int width, int height, int bit_depth, int color_type, int channels,
               const Get& get) {
    AtomicFile atomic(path);  // the temporary file is removed on every failure
    std::vector<unsigned char> row(size_t(width) * size_t(channels) * size_t(bit_depth / 8));
    {
        PngFile w(true);
        w.file = std::fopen(atomic.temp_path().c_str(), "wb");
        if (!w.file) throw_io_error(path, std::string("cannot write: ") + std::strerror(errno));
        w.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &w.error, on_error, on_warning);
        if (w.png) w.info = png_create_info_struct(w.png);
        if (!w.png || !w.info) throw_io_error(path, "cannot write: libpng could not start (out of memory?)");
        if (!WriteRows(w, width, height, bit_depth, color_type, row.data(), get))
            throw_io_error(path, "cannot write: " + libpng_message(w.error));
        // A short write already failed above (libpng's writer checks each fwrite); fclose reports the last flush.
        std::FILE* f = w.file;
        w.file = nullptr;
        if (std::fclose(f) != 0) throw_io_error(path, std::string("cannot write: ") + std::strerror(errno));
    }
    atomic.commit();
}

}  // namespace

bool read_rgba8(const std::string& path, ImageRGBA8& out) {
    return read_png(path, out, [](ImageRGBA8& img, size_t y, const unsigned char* src, int nch, int bytes) {
        Rgba8* d = img.pixels.data() + y * size_t(img.width);
        // Sample c of pixel x, 8 bits: as stored, or a 16-bit one as OpenImageIO converts it, (v + 128) / 257.
        auto at = [&](size_t x, int c) -> uint8_t {
            const size_t i = x * size_t(nch) + size_t(c);
            return bytes == 1 ? src[i] : uint8_t((sample16(src, i) + 128) / 257);
        };
        for (size_t x = 0; x < size_t(img.width); ++x) {
            if (nch == 1) {
                const uint8_t g = at(x, 0);
                d[x] = {g, g, g, 255};
            } else if (nch == 2) {
                const uint8_t g = at(x, 0);
                d[x] = {g, g, g, at(x, 1)};
            } else {
                d[x] = {at(x, 0), at(x, 1), at(x, 2), nch == 4 ? at(x, 3) : uint8_t(255)};
            }
        }
    });
}

bool read_gray(const std::string& path, ImageF& out) {
    return read_png(path, out, [](ImageF& img, size_t y, const unsigned char* src, int nch, int bytes) {
        float* d = img.pixels.data() + y * size_t(img.width);
        // The first channel, as OpenImageIO converts it to float: v * (1 / 255) or v * (1 / 65535).
        const size_t w = size_t(img.width), step = size_t(nch);
        if (bytes == 1)
            for (size_t x = 0; x < w; ++x) d[x] = float(src[x * step]) * (1.0f / 255.0f);
        else
            for (size_t x = 0; x < w; ++x) d[x] = float(sample16(src, x * step)) * (1.0f / 65535.0f);
    });
}

bool writes(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    if (name.size() < 5) return false;  // at least one character before ".png"
    std::string ext = name.substr(name.size() - 4);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".png";
}

void write_rgba8(const std::string& path, const ImageRGBA8& img) {
    check_pixel_count(path, img.width, img.height, img.pixels.size());
    check_write_target(path, img.width, img.height);
    const size_t w = size_t(img.width);
    write_png(path, img.width, img.height, 8, PNG_COLOR_TYPE_RGB_ALPHA, 4,
              [&](size_t y, unsigned char* row) { std::memcpy(row, img.pixels.data() + y * w, w * 4); });
}

void write_gray(const std::string& path, const ImageF& img) {
    check_pixel_count(path, img.width, img.height, img.pixels.size());
    check_write_target(path, img.width, img.height);
    const size_t w = size_t(img.width);
    // Clamped to 0..1 (not finite: 0), then as OpenImageIO converts float to 16 bits: (uint16)(v * 65535 + 0.5).
    write_png(path, img.width, img.height, 16, PNG_COLOR_TYPE_GRAY, 1, [&](size_t y, unsigned char* row) {
        const float* s = img.pixels.data() + y * w;
        for (size_t x = 0; x < w; ++x) {
            const float v = std::isfinite(s[x]) ? std::clamp(s[x], 0.0f, 1.0f) : 0.0f;
            const unsigned q = unsigned(v * 65535.0f + 0.5f);
            row[2 * x] = (unsigned char)(q >> 8);
            row[2 * x + 1] = (unsigned char)(q & 0xFF);
        }
    });
}

}  // namespace rtm::png
