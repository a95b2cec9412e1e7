// The built-in texture of protruded displacement mapping's steep slopes (Yoo 2011, section 4: the paper applies a
// wall texture to the steep sides of protruding buildings): courses of bricks in running bond, 64 x 64 texels,
// four courses high and two bricks wide, so that it repeats seamlessly.
#pragma once

#include "warp/image.h"

namespace rtm {

ImageRGBA8 builtin_steep_texture();

}  // namespace rtm
