// prewarp_relief: pre-warps a relief texture for one eye and writes the pre-warped texture, the way another renderer
// would before mapping it onto the relief's quad with its own texture mapping. Built against the installed rtm
// package (find_package(rtm), rtm::warp and rtm::formats); same output as `rtm prewarp --relief M --eye X,Y,Z`.
//   prewarp_relief NAME.relief.json X,Y,Z OUT.png
#include <cstdio>
#include <exception>
#include <sstream>
#include <string>

#include "formats/image_io.h"
#include "formats/relief_manifest.h"
#include "rtm_version.h"
#include "warp/prewarp.h"

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: prewarp_relief NAME.relief.json X,Y,Z OUT.png (rtm %s)\n", RTM_VERSION);
        return 2;
    }
    glm::dvec3 eye;
    char comma1 = 0, comma2 = 0;
    std::istringstream in(argv[2]);
    if (!(in >> eye.x >> comma1 >> eye.y >> comma2 >> eye.z) || comma1 != ',' || comma2 != ',' || !in.eof()) {
        std::fprintf(stderr, "prewarp_relief: eye: expected X,Y,Z, found \"%s\"\n", argv[2]);
        return 2;
    }
    try {
        // The relief texture: color, quantized displacement and the quad's geometry, from its manifest.
        const rtm::ReliefTexture relief = rtm::load_relief(argv[1]);
        // Pre-warp for the eye (two-pass, lookup tables, all threads): same size and orientation as the source,
        // alpha 0 where nothing landed. Map it onto the quad origin, origin + a*w, origin + a*w + b*h, origin + b*h.
        const rtm::ImageRGBA8 prewarped = rtm::prewarp(relief, eye);
        rtm::write_rgba8(argv[3], prewarped);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "prewarp_relief: %s\n", e.what());
        return 1;
    }
    return 0;
}
