// The checks before any image read or write (formats/image_checks.h).
#include "formats/image_checks.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>
#include <utility>
#include <vector>

#include "formats/image_io.h"

namespace rtm {
namespace {

namespace fs = std::filesystem;

// Some decoders allocate, and clear, whatever a length field in the file claims before reading that many bytes:
// libpng for an ancillary chunk (OpenImageIO 2.4 lets it go up to 2 GB), OpenEXR 3.1 for a header attribute. A
// 348-byte PNG whose tEXt chunk claims 2016634473 bytes, and a 594-byte EXR whose string attribute claims 1.9 GB,
// each made rtm touch 2 GB of memory (found by fuzz/fuzz_relief_loader). So, for these two formats (recognized by
// their signature, whatever the file's extension), no such field may claim more bytes than the file has left.
// PNG's IDAT is left to libpng, which streams it and says more about a file cut short in its pixel data.
//
// OpenEXR's header walk must follow the library's own: OpenEXR 3.1 reads a value of a known type by its type (a
// "compression" is one byte, a channel list runs to its empty name) whatever the attribute's size field says, so a
// walk that trusted the size fields lost step with the library and missed a string attribute claiming 1.9 GB behind a
// channel list whose size field was short (found by the fuzzer after the first check). Here every known type's value
// must take exactly the bytes its size field says (which every file OpenEXR writes does), so the two walks agree;
// the data window, tile size and chunk count, from which the library sizes its tables, are held to the image limits.
//
// SGI, GIF and JPEG files have fields OpenImageIO's readers trust at open in the same way (each found by the fuzzer):
// their checks are with their walks below.
class ContainerCheck {
public:
    explicit ContainerCheck(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "rb"), &std::fclose) {
        std::error_code ec;
        size_ = fs::file_size(path, ec);
        if (ec) f_.reset();
    }
    void run() {
        unsigned char magic[8];
        if (!f_ || !read_at(0, magic, 8)) return;  // the reader reports what is wrong
        if (std::memcmp(magic, "\x89PNG\r\n\x1a\n", 8) == 0) png();
        if (std::memcmp(magic, "\x76\x2f\x31\x01", 4) == 0) exr(magic[5] & 0x10);  // flags: bit 12 = multi-part
        if (magic[0] == 0x01 && magic[1] == 0xda) sgi();
        if (std::memcmp(magic, "GIF", 3) == 0) gif();      // giflib takes any version after "GIF"
        if (magic[0] == 0xff && magic[1] == 0xd8) jpeg();  // libjpeg's SOI
    }

private:
    bool read_at(std::uintmax_t pos, unsigned char* out, size_t n) {
        if (pos + n > size_) return false;
        if (pos != at_ && ::fseeko(f_.get(), off_t(pos), SEEK_SET) != 0) return false;
        at_ = pos + n;
        return std::fread(out, 1, n, f_.get()) == n;
    }
    static std::string printable(const std::string& name) {
        std::string out;
        for (char c : name) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
        return out;
    }
    void check(const char* format, const char* what, const std::string& name, std::uintmax_t pos,
               std::uintmax_t claimed, std::uintmax_t from) {
        if (claimed <= size_ - std::min(size_, from)) return;
        throw_io_error(path_, std::string("cannot read as an image: ") + format + " " + what + " \"" + printable(name) +
                                  "\" at byte " + std::to_string(pos) + " claims " + std::to_string(claimed) +
                                  " bytes, more than the " + std::to_string(size_ - std::min(size_, from)) +
                                  " left in the file (truncated or corrupt)");
    }
    // A field the container's walk finds wrong: "cannot read as an image: <what> (corrupt)".
    [[noreturn]] void corrupt(const std::string& what) {
        throw_io_error(path_, "cannot read as an image: " + what + " (corrupt)");
    }
    void png() {
        unsigned char h[8];
        for (std::uintmax_t pos = 8; read_at(pos, h, 8);) {
            const std::uintmax_t length = std::uintmax_t(h[0]) << 24 | std::uintmax_t(h[1]) << 16 |
                                          std::uintmax_t(h[2]) << 8 | std::uintmax_t(h[3]);
            const std::string type(reinterpret_cast<const char*>(h + 4), 4);
            if (type == "IEND") return;
            if (type != "IDAT") check("PNG", "chunk", type, pos, length, pos + 8);
            pos += 12 + length;
        }
    }

    // SGI: a 512-byte big-endian header (magic 474, storage, bytes per channel, dimension, xsize, ysize, zsize, ...).
    // A run-length encoded file (storage 1) follows it with two tables of ysize x zsize 32-bit entries (where each
    // row of each channel starts, and its length), which OpenImageIO 2.4 allocates and clears at open, from the
    // header's ysize and zsize whatever the dimension: a 577-byte file claiming 16384 rows of 16384 channels made rtm
    // touch 2.4 GB (found by fuzz/fuzz_relief_loader). The tables must fit in the file; and its reader trusts them
    // when it reads a row: an empty table (zsize 0) made it read through a null pointer, a length above 2^31 (negative
    // as the reader's int) made it ask for 16 EB (later finds). So the bytes per channel are 1 or 2 (as the format has
    // them), and with run-length encoding there is at least one row and one channel, and every row of every channel
    // lies in the file.
    void sgi() {
        unsigned char h[12];
        if (!read_at(0, h, 12)) return;
        const unsigned storage = h[2], bpc = h[3];
        const std::uintmax_t ysize = std::uintmax_t(h[8]) << 8 | h[9], zsize = std::uintmax_t(h[10]) << 8 | h[11];
        auto fail = [&](const std::string& what) { corrupt("SGI " + what); };
        if (bpc != 1 && bpc != 2) fail("header claims " + std::to_string(bpc) + " bytes per channel, expected 1 or 2");
        if (storage != 1) return;
        if (ysize == 0 || zsize == 0)
            fail("run-length file claims " + std::to_string(ysize) + " rows x " + std::to_string(zsize) + " channels");
        const std::uintmax_t n = ysize * zsize;
        check("SGI", "run-length tables for", std::to_string(ysize) + " rows x " + std::to_string(zsize) + " channels",
              512, 8 * n, 512);
        std::vector<unsigned char> tables(size_t(8 * n));
        if (!read_at(512, tables.data(), tables.size())) return;
        auto be32 = [](const unsigned char* b) {
            return std::uintmax_t(b[0]) << 24 | std::uintmax_t(b[1]) << 16 | std::uintmax_t(b[2]) << 8 | b[3];
        };
        const std::uintmax_t width = std::uintmax_t(h[6]) << 8 | h[7];
        std::vector<unsigned char> row;
        for (std::uintmax_t i = 0; i < n; ++i) {
            const std::uintmax_t start = be32(&tables[size_t(4 * i)]), length = be32(&tables[size_t(4 * (n + i))]);
            auto which = [&] {
                return "run-length row " + std::to_string(i % ysize) + " of channel " + std::to_string(i / ysize);
            };
            if (start > size_ || length > size_ - start)
                fail(which() + " claims " + std::to_string(length) + " bytes from byte " + std::to_string(start) +
                     ", past the end of the " + std::to_string(size_) + "-byte file");
            row.resize(size_t(length));
            if (!read_at(start, row.data(), row.size())) return;
            const std::string runs = sgi_runs(row, bpc, width);
            if (!runs.empty()) fail(which() + " (byte " + std::to_string(start) + ") " + runs);
        }
    }
    // Walks one row's runs as OpenImageIO 2.4's decoder does (a count byte, or 16-bit word with bpc 2, of which the
    // low 7 bits count: with the high bit set that many values follow, else one value repeated; a count of 0 ends the
    // row) and says what would make it read past the row or write past the `width` values of its output; "" if
    // nothing. Debian's build of the library checks both with assertions that abort the program (a row of 127 values
    // in an image 6 wide made `rtm` abort).
    static std::string sgi_runs(const std::vector<unsigned char>& row, unsigned bpc, std::uintmax_t width) {
        const size_t len = row.size();
        std::uintmax_t left = width;
        for (size_t i = 0; i < len;) {
            if (i + bpc > len) return "ends inside a run's count";
            const unsigned count = row[i + bpc - 1] & 0x7f;
            const bool literal = row[i + bpc - 1] & 0x80;
            i += bpc;
            if (count == 0) break;
            const size_t reads = literal ? size_t(count) * bpc : bpc;
            if (reads > len - i) return "has a run reading past the row's end";
            if (count > left)
                return "has " + std::to_string(count) + " values where " + std::to_string(left) + " of its " +
                       std::to_string(width) + " remain";
            left -= count;
            i += reads;
        }
        return "";
    }

    // GIF: OpenImageIO 2.4 allocates and clears a canvas of the logical screen's size (little-endian 16-bit width and
    // height after the signature) at open, before the image's size can be checked: a 127-byte file claiming a
    // 19789x19789 screen made rtm touch 1.7 GB (found by fuzz/fuzz_relief_loader). The screen is held to the limits,
    // in any file that starts with "GIF" as giflib reads it (it checks no version: "GIFa89" passed, a later find).
    void gif() {
        unsigned char h[10];
        if (read_at(0, h, 10)) check_claimed_size(path_, h[6] | h[7] << 8, h[8] | h[9] << 8, size_);
    }

    // JPEG: OpenImageIO 2.4 decodes the metadata segments libjpeg saves (APP1 Exif and XMP, APP2 ICC profile, APP13
    // Photoshop IPTC) by fields it trusts: it compares each segment's start with a signature by strcmp (reading past a
    // segment that ends inside the signature), takes "Exif" data as 6 bytes shorter and ICC data as 14 bytes shorter
    // than the segment (a shorter one wraps around), and hands the IPTC block to its decoder with the size the block
    // claims: a 1171-byte file whose IPTC block claims 113 of the 20 bytes left in its segment made the reader read
    // past the segment's buffer (AddressSanitizer; found by fuzz/fuzz_relief_loader). The segments before the image
    // data are walked as libjpeg finds them (it skips bytes that are not a marker): each such segment must lie in the
    // file, hold the whole signature and header the reader reads, and the IPTC block must fit in its segment.
    void jpeg() {
        std::uintmax_t pos = 2;
        unsigned char b[2];
        for (;;) {
            while (read_at(pos, b, 1) && b[0] != 0xff) ++pos;  // libjpeg's next_marker: skip to a 0xff,
            while (read_at(pos, b, 1) && b[0] == 0xff) ++pos;  // past the fill bytes,
            if (!read_at(pos, b, 1)) return;
            const unsigned code = b[0];
            const std::uintmax_t at = pos - 1;
            ++pos;
            if (code == 0) continue;                                       // and past a stuffed zero
            if (code == 0xda || code == 0xd9) return;                      // the image data, or the end
            if (code == 0x01 || (code >= 0xd0 && code <= 0xd8)) continue;  // markers without a length
            if (!read_at(pos, b, 2)) return;
            const std::uintmax_t length = std::uintmax_t(b[0]) << 8 | b[1];
            if (length < 2) return;  // libjpeg refuses that itself
            if (code == 0xe1 || code == 0xe2 || code == 0xed) jpeg_segment(code - 0xe0, at, pos + 2, length - 2);
            pos += length;
        }
    }
    void jpeg_segment(unsigned app, std::uintmax_t at, std::uintmax_t from, std::uintmax_t n) {
        const std::string name = "APP" + std::to_string(app);
        check("JPEG", "segment", name, at, n, from);
        unsigned char d[32] = {};
        if (!read_at(from, d, std::min<std::uintmax_t>(n, sizeof d))) return;
        // The signatures the reader compares with strcmp: a segment that ends inside one (every byte it has
        // matching) makes strcmp read past it.
        static const std::pair<unsigned, const char*> kSignatures[] = {{1, "Exif"},
                                                                       {1, "http://ns.adobe.com/xap/1.0/"},
                                                                       {2, "ICC_PROFILE"},
                                                                       {13, "Photoshop 3.0"}};
        auto fail = [&](const std::string& what) {
            corrupt("JPEG " + name + " segment at byte " + std::to_string(at) + " " + what);
        };
        for (const auto& [a, sig] : kSignatures) {
            const size_t len = std::strlen(sig) + 1;  // with its \0
            if (a == app && n < len && std::memcmp(d, sig, std::min<size_t>(n, sizeof d)) == 0)
                fail("ends inside its \"" + std::string(sig) + "\" signature (" + std::to_string(n) + " bytes)");
        }
        auto is = [&](const char* sig) {
            return n >= std::strlen(sig) + 1 && std::memcmp(d, sig, std::strlen(sig) + 1) == 0;
        };
        if (app == 1 && is("Exif") && n < 6)
            fail("holds " + std::to_string(n) + " bytes, fewer than the 6 of its Exif header");
        if (app == 2 && is("ICC_PROFILE") && n < 14)
            fail("holds " + std::to_string(n) + " bytes, fewer than the 14 of its ICC profile header");
        if (app == 13 && is("Photoshop 3.0")) {
            // "8BIM", the resource type (0x0404: IPTC), 4 bytes the reader skips, the block's 16-bit size, the block.
            const size_t sig = n < 18 ? size_t(n) - 14 : 4;  // what strncmp reads of "8BIM" (to a mismatch)
            if (n < 18 && std::memcmp(d + 14, "8BIM", sig) == 0)
                fail("ends inside its \"8BIM\" resource signature (" + std::to_string(n) + " bytes)");
            if (std::memcmp(d + 14, "8BIM", 4) != 0) return;
            if (n < 20) fail("ends inside its Photoshop resource type (" + std::to_string(n) + " bytes)");
            if ((d[18] << 8 | d[19]) != 0x0404) return;
            if (n < 26) fail("ends inside its IPTC block's header (" + std::to_string(n) + " bytes)");
            const std::uintmax_t block = std::uintmax_t(d[24]) << 8 | d[25];
            if (26 + block > n)
                fail("has an IPTC block claiming " + std::to_string(block) + " bytes, more than the " +
                     std::to_string(n - 26) + " left in the segment");
        }
    }

    // OpenEXR: little-endian 32-bit integers; strings end in \0 and hold at most 255 characters (Name::MAX_LENGTH).
    static int32_t le32(const unsigned char* b) {
        return int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
    }
    // Reads a string at `pos` (moved past it); false at the end of the file. A string without its \0 within 256
    // bytes is refused: OpenEXR refuses it too, and the walk could not follow it.
    bool read_string(std::uintmax_t& pos, std::string& out, const char* what) {
        out.clear();
        const std::uintmax_t start = pos;
        for (unsigned char c; read_at(pos++, &c, 1);) {
            if (c == 0) return true;
            if (out.size() == 255)
                corrupt(std::string("OpenEXR ") + what + " at byte " + std::to_string(start) +
                        " is longer than 255 characters");
            out += char(c);
        }
        return false;
    }
    // The bytes OpenEXR 3.1 reads for a value of a fixed-size type, whatever the size field says; 0 for the others.
    static int exr_fixed_size(const std::string& type) {
        static const std::pair<const char*, int> kFixed[] = {{"box2i", 16},
                                                             {"box2f", 16},
                                                             {"chromaticities", 32},
                                                             {"compression", 1},
                                                             {"deepImageState", 1},
                                                             {"double", 8},
                                                             {"envmap", 1},
                                                             {"float", 4},
                                                             {"int", 4},
                                                             {"keycode", 28},
                                                             {"lineOrder", 1},
                                                             {"m33d", 72},
                                                             {"m33f", 36},
                                                             {"m44d", 128},
                                                             {"m44f", 64},
                                                             {"rational", 8},
                                                             {"tiledesc", 9},
                                                             {"timecode", 8},
                                                             {"v2d", 16},
                                                             {"v2f", 8},
                                                             {"v2i", 8},
                                                             {"v3d", 24},
                                                             {"v3f", 12},
                                                             {"v3i", 12}};
        for (const auto& [name, bytes] : kFixed)
            if (type == name) return bytes;
        return 0;
    }
    [[noreturn]] void exr_mismatch(const std::string& name, const std::string& type, std::uintmax_t at,
                                   std::uintmax_t claimed, const std::string& takes) {
        corrupt("OpenEXR attribute \"" + printable(name) + "\" (" + printable(type) + ") at byte " +
                std::to_string(at) + " has a size field of " + std::to_string(claimed) + " but its value takes " +
                takes);
    }
    // The bytes a value of a variable-size type takes as OpenEXR reads it, from `pos`; each length inside is held
    // to the file. Returns the size field itself for types read by it (string, opaque, ...).
    std::uintmax_t exr_value_bytes(const std::string& name, const std::string& type, std::uintmax_t at,
                                   std::uintmax_t pos, std::uintmax_t claimed) {
        const std::uintmax_t start = pos;
        unsigned char b[16];
        if (type == "chlist") {  // channels up to an empty name: name, then type, pLinear, 3 reserved, x and y sampling
            for (std::string channel;;) {
                if (!read_string(pos, channel, "channel name")) return pos - start;  // cut short: the reader says
                if (channel.empty()) return pos - start;
                pos += 16;
            }
        }
        if (type == "preview") {  // width, height, then width x height RGBA bytes the library allocates
            if (!read_at(pos, b, 8)) return claimed;
            const std::uintmax_t w = uint32_t(le32(b)), h = uint32_t(le32(b + 4));
            if ((w != 0 && h > size_ / w) || 8 + 4 * w * h != claimed)  // (the product is checked before it is taken)
                exr_mismatch(name, type, at, claimed,
                             "8 + 4 x " + std::to_string(w) + " x " + std::to_string(h) + " bytes (its pixels)");
            return claimed;
        }
        if (type == "floatvector") return claimed / 4 * 4;  // whole floats only
        if (type == "stringvector") {                       // (length, characters) pairs while the size field lasts
            while (pos - start < claimed) {
                if (!read_at(pos, b, 4)) return pos - start;
                const int32_t n = le32(b);
                if (n < 0) exr_mismatch(name, type, at, claimed, "a string of negative length " + std::to_string(n));
                check("OpenEXR", "string in attribute", name, pos, std::uintmax_t(n), pos + 4);
                pos += 4 + std::uintmax_t(n);
            }
            return pos - start;
        }
        return claimed;
    }
    // A header is a list of attributes (name\0 type\0 int32 size, then the value) ended by an empty name; a
    // multi-part file has several headers, the list ended by an empty header.
    void exr(bool multi_part) {
        std::uintmax_t pos = 8;
        std::string name, type;
        do {
            if (!read_string(pos, name, "attribute name") || name.empty()) return;
            while (!name.empty()) {
                const std::uintmax_t at = pos - name.size() - 1;
                unsigned char n[4];
                if (!read_string(pos, type, "attribute type") || !read_at(pos, n, 4)) return;
                pos += 4;
                const int32_t size_field = le32(n);
                if (size_field < 0) return;  // OpenEXR refuses that itself
                const std::uintmax_t claimed = std::uintmax_t(size_field);
                check("OpenEXR", "attribute", name, at, claimed, pos);
                const int fixed = exr_fixed_size(type);
                const std::uintmax_t takes = fixed ? std::uintmax_t(fixed)
                                                   : exr_value_bytes(name, type, at, pos, claimed);
                if (takes != claimed) exr_mismatch(name, type, at, claimed, std::to_string(takes) + " bytes");
                exr_limits(name, type, pos);
                pos += claimed;
                if (!read_string(pos, name, "attribute name")) return;
            }
        } while (multi_part);
    }
    // The attributes from which OpenEXR sizes its tables and buffers when the file is opened.
    void exr_limits(const std::string& name, const std::string& type, std::uintmax_t pos) {
        unsigned char b[16];
        if (name == "dataWindow" && type == "box2i" && read_at(pos, b, 16)) {
            const long long x0 = le32(b), y0 = le32(b + 4), x1 = le32(b + 8), y1 = le32(b + 12);
            check_claimed_size(path_, x1 - x0 + 1, y1 - y0 + 1, size_);
        } else if (name == "tiles" && type == "tiledesc" && read_at(pos, b, 8)) {
            const long long tw = uint32_t(le32(b)), th = uint32_t(le32(b + 4));
            if (tw > kMaxImagePixels || th > kMaxImagePixels || tw * th > kMaxImagePixels)
                throw_io_error(path_, "cannot read as an image: OpenEXR tiles of " + std::to_string(tw) + "x" +
                                          std::to_string(th) + " pixels, more than the limit of 16384x16384");
        } else if (name == "chunkCount" && type == "int" && read_at(pos, b, 4)) {
            const int32_t chunks = le32(b);
            if (chunks < 0 || std::uintmax_t(chunks) > size_ / 8)  // an 8-byte offset per chunk at least
                corrupt("OpenEXR chunkCount " + std::to_string(chunks) + " does not fit in a " + std::to_string(size_) +
                        "-byte file");
        }
    }

    std::string path_;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f_;
    std::uintmax_t size_ = 0;
    std::uintmax_t at_ = 0;  // the stream's position
};

}  // namespace

std::uintmax_t check_readable_file(const std::string& path) {
    std::error_code ec;
    fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) {
        int err = ec ? ec.value() : ENOENT;
        throw_io_error(path, std::string("cannot open: ") + std::strerror(err));
    }
    if (fs::is_directory(st)) throw_io_error(path, "is a directory");
    if (!fs::is_regular_file(st)) throw_io_error(path, "is not a regular file");
    auto size = fs::file_size(path, ec);
    if (ec) throw_io_error(path, "cannot open: " + ec.message());
    if (size == 0) throw_io_error(path, "file is empty");
    return size;
}

void check_claimed_size(const std::string& path, long long width, long long height, std::uintmax_t file_size) {
    if (width <= 0 || height <= 0)
        throw_io_error(path, "image header claims " + std::to_string(width) + "x" + std::to_string(height) +
                                 " pixels, expected a width and height of at least 1");
    // Each side is below 2^33 here (a header's int, or an OpenEXR window's difference of two), so the product fits
    // once both are within the limit.
    if (width > kMaxImagePixels || height > kMaxImagePixels || width * height > kMaxImagePixels)
        throw_io_error(path, "image claims " + std::to_string(width) + "x" + std::to_string(height) +
                                 " pixels, more than the limit of 16384x16384");
    if (std::uintmax_t(width * height / kMaxPixelsPerFileByte) > file_size)
        throw_io_error(path, "image claims " + std::to_string(width) + "x" + std::to_string(height) +
                                 " pixels, more than " + std::to_string(kMaxPixelsPerFileByte) + " per byte of a " +
                                 std::to_string(file_size) + "-byte file (truncated or corrupt)");
}

void check_container(const std::string& path) { ContainerCheck(path).run(); }

void check_pixel_count(const std::string& path, int width, int height, size_t pixels) {
    if (pixels != size_t(std::max(width, 0)) * size_t(std::max(height, 0)))
        throw_io_error(path, "cannot write: image claims " + std::to_string(width) + "x" + std::to_string(height) +
                                 " but holds " + std::to_string(pixels) + " pixels");
}

void check_write_target(const std::string& path, int width, int height) {
    if (width <= 0 || height <= 0)
        throw_io_error(path,
                       "cannot write an empty image (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw_io_error(path, "is a directory");
    fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec))
        throw_io_error(path, "cannot write: folder " + parent.string() + " does not exist");
}

}  // namespace rtm
