// Screenshots of the viewer's window: the framebuffer as shown (image, panel and overlays), top row first.
#pragma once

#include <string>

#include "warp/image.h"

namespace rtm::viewer {

// Reads the current framebuffer's back buffer (requires a current context).
ImageRGBA8 read_framebuffer(int width, int height);
// "rtm-view-YYYYMMDD-HHMMSS-mmm.png", local time: the screenshot key's file name.
std::string timestamped_name();

}  // namespace rtm::viewer
