// The four occlusion-compatible quadrants about the epipole (paper section 3.1, Figure 7), as drawn over a picture
// of a texture: the lines through the epipole split the texture into four parts, each warped from the borders
// towards the epipole. Geometry only (x right, y down, in the picture's units); the viewer's insets
// (viewer/overlays) and the comparison page's step-by-step figures (measure/prewarp_figures) draw it.
#pragma once

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>

namespace rtm {

using Rgba = std::array<uint8_t, 4>;

struct QuadrantOverlay {
    struct Box {
        glm::dvec2 p0, p1;  // top-left and bottom-right corners
        Rgba colour;        // translucent fill
    };
    // Above-left, above-right, below-left and below-right of the epipole (empty boxes where the epipole lies beyond
    // that side of the picture).
    std::array<Box, 4> quadrants;
    glm::dvec2 epipole{0.0};  // clamped to the picture: where the two lines cross
    bool inside = false;      // the epipole lies within the picture (else it is drawn as a ring on the border)
};

inline constexpr Rgba kQuadrantLineColour{255, 255, 255, 160};  // the two lines through the epipole
inline constexpr Rgba kEpipoleColour{255, 0, 255, 255};         // the epipole: a dot, or a ring when clamped

// The quadrants of the picture [p0, p1] (top-left, bottom-right) about `epipole`, given in the same coordinates.
// The epipole must be finite (not finite: the eye is in the relief's plane and there is nothing to draw).
QuadrantOverlay quadrant_overlay(const glm::dvec2& p0, const glm::dvec2& p1, const glm::dvec2& epipole);

}  // namespace rtm
