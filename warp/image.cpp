#include "warp/image.h"

#include <cstdio>

namespace rtm {

std::string to_string(const Rgba8& c) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "(%d, %d, %d, %d)", c.r, c.g, c.b, c.a);
    return buf;
}

}  // namespace rtm
