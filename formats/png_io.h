// PNG files through libpng, without the image module: the images rtm writes and reads most (its own pre-warps,
// pictures and 16-bit displacement maps) cost a process no load of OpenImageIO's 260 shared libraries (0.43 s of a
// 0.57 s `rtm render` on a Zen 5 guest; docs/BENCHMARKS.md, "Start-up"). formats/image_io.cpp tries these first.
//
// The pixels are OpenImageIO's to the bit (tests/formats/png_io_test.cpp reads and writes every kind of PNG both ways):
// channels as stored (alpha unassociated), 16-bit samples to 8 bits as (v + 128) / 257, to float v * (1 / 65535),
// 8-bit ones v * (1 / 255), float to 16 bits (uint16)(v * 65535 + 0.5). Errors throw IoError with the messages of
// the module's reader ("cannot read as an image: ...", "cannot read pixels: ...", "cannot write: ...").
#pragma once

#include <string>

#include "formats/image_io.h"

namespace rtm::png {

// Reads `path` if it is a PNG file of a kind read here: 8 or 16 bits a sample, grey, grey and alpha, RGB or RGBA,
// not interlaced, without a tRNS chunk. Returns false for any other file (not a PNG, or a palette, low bit depth,
// tRNS or interlaced PNG), which the image module reads; throws IoError for a missing, empty, oversized or corrupt
// file. read_rgba8 as image_io.h's; read_gray the first channel.
bool read_rgba8(const std::string& path, ImageRGBA8& out);
bool read_gray(const std::string& path, ImageF& out);

// Whether `path` names a PNG file (its extension, in any case): the writers below take it.
bool writes(const std::string& path);
// As image_io.h's writers, for a path that writes() takes: RGBA, 8 bits; grey, 16 bits.
void write_rgba8(const std::string& path, const ImageRGBA8& img);
void write_gray(const std::string& path, const ImageF& img);

}  // namespace rtm::png
