// Checks, before assimp reads a file, that the element counts its header declares fit in the file. assimp 5.2's
// PLY and OFF readers reserve memory for the declared counts: a 309-byte OFF file claiming 353535235358 vertices
// (assimp-testmodels' invalid/OutOfMemory.off) made it grow past 2 GB and run for minutes. Every declared element
// takes at least one byte of the file, so a count larger than the file's size is a lie. A PLY header must also end
// (an "end_header" line): the PLY reader loops without end on one cut short.
#pragma once

#include <cstdint>
#include <string>

namespace rtm {

// Returns "" when the file is not PLY or OFF or its declared counts fit in `file_size` bytes (and a PLY header ends
// within the first 64 KiB); otherwise what is wrong ("header declares 353535235358 vertices in a file of 309
// bytes"). Reads at most the first 64 KiB.
std::string check_declared_counts(const std::string& path, std::uintmax_t file_size);

}  // namespace rtm
