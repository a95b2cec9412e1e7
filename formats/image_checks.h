// The checks every image reader and writer makes before the library does anything (docs/DESIGN.md, "Input limits"):
// the file exists and is a non-empty regular file, no length field of a PNG, OpenEXR, SGI or JPEG container claims more
// bytes than the file holds, a GIF's screen is within the image limits, the image's claimed size is within
// kMaxImagePixels, and a write has somewhere to go. Shared by the PNG reader and writer (formats/png_io.cpp) and the
// image module over OpenImageIO (formats/image_io_oiio.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace rtm {

// Throws IoError unless `path` is a non-empty regular file; returns its size.
std::uintmax_t check_readable_file(const std::string& path);

// The claimed size of an image (from its header, or an OpenEXR data window) against the limits, before anything
// allocates pixel memory.
void check_claimed_size(const std::string& path, long long width, long long height, std::uintmax_t file_size);

// For PNG, OpenEXR, SGI, GIF and JPEG files (recognized by their signature, whatever the file's extension): throws
// IoError where a length field claims more bytes than the file (or a JPEG segment) has left, or a size the image limits
// refuse (see image_checks.cpp). Other files pass.
void check_container(const std::string& path);

// Before a write: an image of at least one pixel whose pixel count matches its size, and a destination that is not a
// folder, in a folder that exists.
void check_pixel_count(const std::string& path, int width, int height, size_t pixels);
void check_write_target(const std::string& path, int width, int height);

}  // namespace rtm
