#include "viewer/screenshot.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>

#include "texmap/gl_context.h"

namespace rtm::viewer {

ImageRGBA8 read_framebuffer(int width, int height) {
    ImageRGBA8 flipped(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, flipped.pixels.data());
    check_gl("screenshot: glReadPixels");
    ImageRGBA8 img(width, height);  // GL returns the bottom row first
    for (int r = 0; r < height; ++r)
        std::copy(flipped.row(height - 1 - r), flipped.row(height - 1 - r) + width, img.row(r));
    return img;
}

std::string timestamped_name() {
    const auto now = std::chrono::system_clock::now();
    const std::time_t t = std::chrono::system_clock::to_time_t(now);
    const long ms = long(std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000);
    std::tm tm{};
    localtime_r(&t, &tm);
    char buf[64];
    std::snprintf(buf, sizeof buf, "rtm-view-%04d%02d%02d-%02d%02d%02d-%03ld.png", tm.tm_year + 1900, tm.tm_mon + 1,
                  tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, ms);
    return buf;
}

}  // namespace rtm::viewer
