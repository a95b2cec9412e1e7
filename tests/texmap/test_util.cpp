#include "texmap/test_util.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "formats/image_io.h"

namespace rtm::test {
namespace fs = std::filesystem;

TempDir::TempDir() {
    static std::atomic<int> counter{0};
    std::random_device rd;
    for (int attempt = 0; attempt < 100; ++attempt) {
        fs::path p = fs::temp_directory_path() / ("rtm_texmap_test_" + std::to_string(::getpid()) + "_" +
                                                  std::to_string(counter++) + "_" + std::to_string(rd() % 100000));
        if (fs::create_directory(p)) {
            path_ = p;
            return;
        }
    }
    throw std::runtime_error("cannot create a temporary folder");
}

TempDir::~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

std::vector<std::string> TempDir::list() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream f(path, std::ios::binary);
    f.write(bytes.data(), std::streamsize(bytes.size()));
    if (!f) throw std::runtime_error("cannot write " + path);
}

std::string read_bytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream os;
    os << f.rdbuf();
    return os.str();
}

namespace {

uint32_t crc32(const std::string& data) {
    static uint32_t table[256];
    static bool ready = false;
    if (!ready) {
        for (uint32_t n = 0; n < 256; ++n) {
            uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            table[n] = c;
        }
        ready = true;
    }
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : data) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

uint32_t adler32(const std::string& data) {
    uint32_t a = 1, b = 0;
    for (unsigned char c : data) {
        a = (a + c) % 65521;
        b = (b + a) % 65521;
    }
    return (b << 16) | a;
}

void put_be32(std::string& s, uint32_t v) {
    s.push_back(char(v >> 24));
    s.push_back(char(v >> 16));
    s.push_back(char(v >> 8));
    s.push_back(char(v));
}

std::string chunk(const std::string& type, const std::string& data) {
    std::string out;
    put_be32(out, uint32_t(data.size()));
    std::string body = type + data;
    out += body;
    put_be32(out, crc32(body));
    return out;
}

std::string ihdr(uint32_t w, uint32_t h, int bit_depth, int channels) {
    static const int colour_type[5] = {0, 0, 4, 2, 6};
    std::string d;
    put_be32(d, w);
    put_be32(d, h);
    d.push_back(char(bit_depth));
    d.push_back(char(colour_type[channels]));
    d.push_back(0);  // deflate
    d.push_back(0);  // adaptive filtering
    d.push_back(0);  // not interlaced
    return chunk("IHDR", d);
}

const std::string kSignature("\x89PNG\r\n\x1a\n", 8);

}  // namespace

std::string encode_png(int width, int height, int channels, int bit_depth, const std::vector<uint16_t>& samples) {
    if (samples.size() != size_t(width) * size_t(height) * size_t(channels))
        throw std::invalid_argument("encode_png: wrong number of samples");
    std::string raw;
    size_t i = 0;
    for (int r = 0; r < height; ++r) {
        raw.push_back(0);  // filter: none
        for (int k = 0; k < width * channels; ++k, ++i) {
            if (bit_depth == 16) raw.push_back(char(samples[i] >> 8));
            raw.push_back(char(samples[i] & 0xFF));
        }
    }
    std::string z("\x78\x01", 2);  // zlib header, no preset dictionary
    for (size_t pos = 0; pos < raw.size() || pos == 0; pos += 65535) {
        size_t n = std::min<size_t>(65535, raw.size() - pos);
        bool last = pos + n >= raw.size();
        z.push_back(last ? 1 : 0);  // BFINAL, BTYPE = stored
        z.push_back(char(n & 0xFF));
        z.push_back(char(n >> 8));
        z.push_back(char(~n & 0xFF));
        z.push_back(char((~n >> 8) & 0xFF));
        z.append(raw, pos, n);
        if (last) break;
    }
    put_be32(z, adler32(raw));
    return kSignature + ihdr(uint32_t(width), uint32_t(height), bit_depth, channels) + chunk("IDAT", z) +
           chunk("IEND", "");
}

std::string png_chunk(const std::string& type, const std::string& data) { return chunk(type, data); }

std::string png_claiming_size(uint32_t width, uint32_t height) {
    // A few bytes of a zlib stream, so a reader gets past the header into the (absent) pixel data.
    std::string z("\x78\x01\x00\x00\x80\xff\x7f", 7);
    return kSignature + ihdr(width, height, 8, 4) + chunk("IDAT", z);
}

std::string compare_images(const ImageRGBA8& expected, const ImageRGBA8& actual, int tolerance,
                           const std::vector<uint8_t>& mask) {
    std::ostringstream os;
    if (expected.width != actual.width || expected.height != actual.height) {
        os << "size differs: expected " << expected.width << "x" << expected.height << ", got " << actual.width << "x"
           << actual.height;
        return os.str();
    }
    long long differing = 0, compared = 0;
    int max_diff = 0, first_x = -1, first_row = -1;
    for (int r = 0; r < expected.height; ++r) {
        for (int x = 0; x < expected.width; ++x) {
            size_t i = size_t(r) * size_t(expected.width) + size_t(x);
            if (!mask.empty() && !mask[i]) continue;
            ++compared;
            const Rgba8 &e = expected.pixels[i], &a = actual.pixels[i];
            int d = std::max({std::abs(e.r - a.r), std::abs(e.g - a.g), std::abs(e.b - a.b), std::abs(e.a - a.a)});
            max_diff = std::max(max_diff, d);
            if (d > tolerance) {
                if (differing++ == 0) {
                    first_x = x;
                    first_row = r;
                }
            }
        }
    }
    if (differing == 0) return {};
    size_t fi = size_t(first_row) * size_t(expected.width) + size_t(first_x);
    os << differing << " of " << compared << " compared pixels differ by more than " << tolerance
       << " (largest difference " << max_diff << "); first at x=" << first_x << " row=" << first_row << ": expected "
       << to_string(expected.pixels[fi]) << ", got " << to_string(actual.pixels[fi]);
    return os.str();
}

std::string check_golden(const std::string& name, const ImageRGBA8& actual, int tolerance) {
    const std::string path = std::string(RTM_SOURCE_DIR) + "/tests/texmap/golden/" + name + ".png";
    const char* update = std::getenv("RTM_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        fs::create_directories(fs::path(path).parent_path());
        write_rgba8(path, actual);
        return {};
    }
    ImageRGBA8 expected;
    try {
        expected = read_rgba8(path);
    } catch (const std::exception& e) {
        return std::string("cannot read the golden image (run with RTM_UPDATE_GOLDEN=1 to create it): ") + e.what();
    }
    std::string verdict = compare_images(expected, actual, tolerance);
    if (!verdict.empty()) verdict = path + ": " + verdict + " (RTM_UPDATE_GOLDEN=1 rewrites it)";
    return verdict;
}

}  // namespace rtm::test
