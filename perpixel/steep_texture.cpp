#include "perpixel/steep_texture.h"

namespace rtm {

ImageRGBA8 builtin_steep_texture() {
    constexpr int kSize = 64, kCourse = 16, kBrick = 32, kMortar = 2;
    ImageRGBA8 img(kSize, kSize, Rgba8{0, 0, 0, 255});
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const int course = y / kCourse;
            const int bx = (x + (course % 2) * (kBrick / 2)) % kBrick;  // running bond: every other course shifted
            const bool mortar = y % kCourse < kMortar || bx < kMortar;
            // A little variation from brick to brick, repeatable: the brick's index hashed to a shade.
            const int brick = course * 4 + (x + (course % 2) * (kBrick / 2)) / kBrick;
            const int shade = (brick * 37) % 23;
            img.at(x, y) = mortar ? Rgba8{170, 165, 155, 255}
                                  : Rgba8{uint8_t(150 + shade), uint8_t(62 + shade / 2), uint8_t(45 + shade / 3), 255};
        }
    return img;
}

}  // namespace rtm
