// The page's step-by-step section: the pre-warp of one relief for one view, as the paper's Figure 9 shows it
// (with the epipole and the four occlusion-compatible quadrants of section 3.1, Figure 7, drawn on the source):
// (a) the source colour and its displacement as grey, (b) the image after the horizontal pass, (c) the pre-warped
// texture after the vertical pass, (d) the final frame, the pre-warped texture mapped onto the relief quad.
#pragma once

#include <optional>
#include <string>

#include "texmap/camera.h"
#include "warp/image.h"
#include "warp/relief_texture.h"

namespace rtm {

struct PrewarpFiguresInput {
    const ReliefTexture* relief = nullptr;
    Camera camera;
    std::string out_dir;  // the pictures go to out_dir/steps/, named in the returned HTML relative to out_dir
    // The final frame (two-pass, no side polygons) when the caller rendered it; else rendered here in an offscreen
    // OpenGL context of the section's own (if that fails, the section says why and shows no frame).
    std::optional<ImageRGBA8> frame;
};

// Writes the pictures and returns the section's HTML (a <section> element). Throws IoError naming a picture that
// cannot be written.
std::string prewarp_figures(const PrewarpFiguresInput& input);

}  // namespace rtm
