// Image files: the usual PNG files through libpng (formats/png_io.h), every other image through OpenImageIO
// (formats/image_backend.h: loaded on first use), with the same pixels either way. Errors throw rtm::IoError whose
// message names the file and what is wrong.
#pragma once

#include <stdexcept>
#include <string>

#include "warp/image.h"

namespace rtm {

struct IoError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// `s` with its control characters shown as '?': one line whatever it quotes (a newline in a file name, which a
// manifest can ask for: found by fuzz/fuzz_relief_manifest; or in a flag's value).
inline std::string printable_one_line(std::string s) {
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return s;
}

// Throws IoError "<path>: <what>", one line (printable_one_line) whatever the path holds.
[[noreturn]] inline void throw_io_error(const std::string& path, const std::string& what) {
    throw IoError(printable_one_line(path + ": " + what));
}

// Largest image a reader accepts (width*height), so a header claiming absurd sizes cannot make us allocate
// tens of gigabytes: 16384 x 16384 texels.
inline constexpr long long kMaxImagePixels = 16384LL * 16384LL;
// Most pixels a header may claim per byte of its file: a 21-byte TGA claiming 13856 x 15834 pixels made the reader
// allocate 2 GB before finding no data. The densest real encoding (a constant 1-bit PNG) stays near 8200 per byte.
inline constexpr long long kMaxPixelsPerFileByte = 16384;

// Reads RGB or RGBA (any format OpenImageIO reads); RGB gets alpha 255, grey is replicated.
ImageRGBA8 read_rgba8(const std::string& path);
// Reads one channel (the first), normalized to 0..1 as OpenImageIO converts to float.
ImageF read_gray(const std::string& path);
// Writes atomically: to a temporary file beside `path`, renamed on success, so no partial file is left.
void write_rgba8(const std::string& path, const ImageRGBA8& img);
void write_gray(const std::string& path, const ImageF& img);  // values 0..1, 16-bit PNG where supported

// Opt-in, off by default: libpng reports a corrupt file through OpenImageIO (the IoError message says it) and then
// prints the same text as "libpng error: ..." on stderr itself. On, the reads and writes above run with file
// descriptor 2 pointed at /dev/null for the length of each OpenImageIO call: that silences the WHOLE PROCESS's stderr
// meanwhile (other threads' messages are lost), and concurrent calls take turns. For programs that promise one line
// on stderr per failure (the rtm command line turns it on at start).
void set_quiet_image_library_stderr(bool on);
bool quiet_image_library_stderr();

}  // namespace rtm
