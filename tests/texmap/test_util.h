// Helpers for the texmap tests: a temporary folder, a minimal PNG encoder (to craft exact, odd and broken files
// without depending on the code under test), image comparison with a tolerance, and golden images.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "warp/image.h"

namespace rtm::test {

// A fresh folder under the system temporary folder, removed with everything in it on destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    std::vector<std::string> list() const;  // names of the entries, sorted

private:
    std::filesystem::path path_;
};

void write_bytes(const std::string& path, const std::string& bytes);
std::string read_bytes(const std::string& path);

// PNG chunks and files, written by hand: zlib "stored" (uncompressed) blocks, so any byte layout can be made.
// `samples` holds width*height*channels values, row 0 first (the top row), each < 2^bit_depth.
// colour type from channels: 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA; bit_depth 8 or 16.
std::string encode_png(int width, int height, int channels, int bit_depth, const std::vector<uint16_t>& samples);
// One PNG chunk: length, type, data and CRC.
std::string png_chunk(const std::string& type, const std::string& data);
// A PNG whose header claims width x height (RGBA8) followed by the start of an IDAT chunk and nothing else.
std::string png_claiming_size(uint32_t width, uint32_t height);

// Compares two images channel by channel. Returns "" when every pixel with mask[i] != 0 (all pixels when `mask`
// is empty) differs by at most `tolerance` in every channel, else a description: how many pixels differ, the
// largest difference, and the first differing pixel with both values.
std::string compare_images(const ImageRGBA8& expected, const ImageRGBA8& actual, int tolerance,
                           const std::vector<uint8_t>& mask = {});

// Golden images live in tests/texmap/golden/NAME.png. With RTM_UPDATE_GOLDEN=1 in the environment the image is
// (re)written instead of compared and the function returns "". Otherwise returns compare_images' verdict, or why
// the golden could not be read.
std::string check_golden(const std::string& name, const ImageRGBA8& actual, int tolerance);

}  // namespace rtm::test
