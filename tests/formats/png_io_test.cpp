// The PNG reader and writer over libpng (formats/png_io.h) against the image module over OpenImageIO, which they
// stand in for: the same pixels to the bit for every kind of PNG they read, the same decoded pixels for what they
// write, and every other kind of PNG left to the module.
#include "formats/png_io.h"

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "formats/image_backend.h"
#include "texmap/test_util.h"

namespace rtm {
namespace {

using test::TempDir;

// The image module the build made (formats/CMakeLists.txt), loaded as rtm loads it.
const ImageBackend& module_backend() {
    static const ImageBackend* api = [] {
        const std::string path = std::string(RTM_BINARY_DIR) + "/lib/rtm/" + kImageModuleName;
        void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) return static_cast<const ImageBackend*>(nullptr);
        auto entry = reinterpret_cast<const ImageBackend* (*)()>(::dlsym(handle, "rtm_image_backend_v1"));
        return entry ? entry() : nullptr;
    }();
    if (!api) throw std::runtime_error("cannot load the image module from " RTM_BINARY_DIR "/lib/rtm");
    return *api;
}

// Bitwise, so that -0 and +0 or two NaNs would not pass for each other.
bool same_bits(const ImageF& a, const ImageF& b) {
    return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

std::vector<uint16_t> random_samples(size_t n, int bit_depth, std::mt19937& rng) {
    std::vector<uint16_t> s(n);
    const uint32_t mask = bit_depth == 16 ? 0xFFFFu : 0xFFu;
    for (size_t i = 0; i < n; ++i) s[i] = uint16_t(rng() & mask);
    // The extremes and the values next to them, where a rounding would show.
    const uint16_t edges[] = {0, 1, uint16_t(mask / 2), uint16_t(mask / 2 + 1), uint16_t(mask - 1), uint16_t(mask)};
    for (size_t i = 0; i < n && i < 6; ++i) s[i] = edges[i];
    return s;
}

// `png` with `chunks` put right after its IHDR chunk (8-byte signature, then 25 bytes of IHDR).
std::string with_chunks(const std::string& png, const std::string& chunks) {
    std::string out = png;
    out.insert(33, chunks);
    return out;
}

std::string be32(uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

TEST(PngIo, ReadsTheUsualKindsAsTheModuleDoes) {
    TempDir dir;
    const uint32_t seed = 20261206;
    std::mt19937 rng(seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    // gAMA and sRGB chunks change nothing either reader returns (neither converts colour).
    const std::string colour_chunks = test::png_chunk("gAMA", be32(45455)) + test::png_chunk("sRGB", std::string(1, 0));
    int kinds = 0;
    for (int channels = 1; channels <= 4; ++channels)
        for (int bit_depth : {8, 16})
            for (bool extra : {false, true}) {
                const int w = 1 + int(rng() % 37), h = 1 + int(rng() % 23);
                const std::string path = dir.file(std::to_string(kinds++) + "_kind.png");
                std::string bytes = test::encode_png(w, h, channels, bit_depth,
                                                     random_samples(size_t(w * h * channels), bit_depth, rng));
                test::write_bytes(path, extra ? with_chunks(bytes, colour_chunks) : bytes);
                SCOPED_TRACE(std::to_string(channels) + " channels, " + std::to_string(bit_depth) + " bits" +
                             (extra ? ", gAMA and sRGB" : ""));
                ImageRGBA8 rgba;
                ASSERT_TRUE(png::read_rgba8(path, rgba));
                EXPECT_EQ(test::compare_images(module_backend().read_rgba8(path, true), rgba, 0), "");
                ImageF gray;
                ASSERT_TRUE(png::read_gray(path, gray));
                EXPECT_TRUE(same_bits(module_backend().read_gray(path, true), gray));
                // And through image_io.h, which takes this path.
                EXPECT_EQ(test::compare_images(rgba, read_rgba8(path), 0), "");
            }
}

TEST(PngIo, WritesWhatTheModuleWrites) {
    TempDir dir;
    const uint32_t seed = 61202;
    std::mt19937 rng(seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    ImageRGBA8 rgba(29, 17);
    for (Rgba8& p : rgba.pixels) {
        const uint32_t v = rng();
        p = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
    }
    png::write_rgba8(dir.file("ours.png"), rgba);
    module_backend().write_rgba8(dir.file("theirs.png"), rgba, true);
    EXPECT_EQ(test::compare_images(module_backend().read_rgba8(dir.file("theirs.png"), true),
                                   module_backend().read_rgba8(dir.file("ours.png"), true), 0),
              "");
    EXPECT_EQ(test::compare_images(rgba, module_backend().read_rgba8(dir.file("ours.png"), true), 0), "");

    // Grey: every 16-bit step's rounding edge (k +- 0.5) / 65535 and its neighbours, the ends, and values to clamp.
    std::vector<float> values;
    for (int k = 0; k < 65536; k += 97)
        for (float e : {-0.5f, 0.0f, 0.5f}) {
            const float v = (float(k) + e) / 65535.0f;
            values.push_back(v);
            values.push_back(std::nextafter(v, 2.0f));
            values.push_back(std::nextafter(v, -1.0f));
        }
    for (float v : {0.0f, 1.0f, -0.0f, -1e-9f, -3.0f, 1.0000001f, 7.0f, std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()})
        values.push_back(v);
    ImageF gray(int(values.size()), 1);
    gray.pixels = values;
    png::write_gray(dir.file("g_ours.png"), gray);
    module_backend().write_gray(dir.file("g_theirs.png"), gray, true);
    EXPECT_TRUE(same_bits(module_backend().read_gray(dir.file("g_theirs.png"), true),
                          module_backend().read_gray(dir.file("g_ours.png"), true)));
}

TEST(PngIo, LeavesOtherKindsToTheModule) {
    TempDir dir;
    auto ihdr = [](uint32_t w, uint32_t h, int bit_depth, int colour_type, int interlace) {
        return test::png_chunk("IHDR", be32(w) + be32(h) +
                                           std::string{char(bit_depth), char(colour_type), 0, 0, char(interlace)});
    };
    // A 2x1 palette image, a 4-bit grey one, an RGB one with a tRNS colour, and a 1x1 interlaced one (Adam7's first
    // pass is its only pixel), each with the IDAT of encode_png's matching layout.
    struct Case {
        std::string name, header, extra;
        std::vector<uint16_t> samples;
        int channels, encode_depth;
    };
    const std::string sig("\x89PNG\r\n\x1a\n", 8);
    const Case cases[] = {
        {"palette",
         ihdr(2, 1, 8, 3, 0),
         test::png_chunk("PLTE", std::string("\xff\x00\x00\x00\x00\xff", 6)),
         {1, 0},
         1,
         8},
        {"grey4", ihdr(2, 1, 4, 0, 0), "", {0x5A}, 1, 8},  // one byte holds both 4-bit samples
        {"trns",
         ihdr(1, 1, 8, 2, 0),
         test::png_chunk("tRNS", std::string("\x00\x01\x00\x02\x00\x03", 6)),
         {1, 2, 3},
         3,
         8},
        {"interlaced", ihdr(1, 1, 8, 6, 1), "", {10, 20, 30, 40}, 4, 8},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const int w = int(c.samples.size()) / c.channels;
        const std::string body = test::encode_png(w, 1, c.channels, c.encode_depth, c.samples);
        const std::string path = dir.file(c.name + ".png");
        test::write_bytes(path, sig + c.header + c.extra + body.substr(33));
        ImageRGBA8 rgba;
        ImageF gray;
        EXPECT_FALSE(png::read_rgba8(path, rgba));
        EXPECT_FALSE(png::read_gray(path, gray));
        // image_io.h reads them through the module, as before.
        EXPECT_EQ(test::compare_images(module_backend().read_rgba8(path, true), read_rgba8(path), 0), "");
        EXPECT_TRUE(same_bits(module_backend().read_gray(path, true), read_gray(path)));
    }
    // Not a PNG at all (whatever the name says): the module's to read, and to refuse.
    test::write_bytes(dir.file("text.png"), "These are notes, not an image.\n");
    ImageRGBA8 rgba;
    EXPECT_FALSE(png::read_rgba8(dir.file("text.png"), rgba));
}

TEST(PngIo, WritesByTheNamesExtension) {
    EXPECT_TRUE(png::writes("a.png"));
    EXPECT_TRUE(png::writes("dir.x/b.PNG"));
    EXPECT_TRUE(png::writes("/tmp/c.Png"));
    EXPECT_FALSE(png::writes("a.png.exr"));
    EXPECT_FALSE(png::writes("png"));
    EXPECT_FALSE(png::writes("dir.png/"));
    EXPECT_FALSE(png::writes("a.tif"));
}

}  // namespace
}  // namespace rtm
