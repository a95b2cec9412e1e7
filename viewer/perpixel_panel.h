// The panel's section for the per-pixel methods: each method's parameters (named as its paper names them), the
// settings they share (shading, self-shadowing and the light, the papers' 8-bit textures, iteration counts), and for
// quadric silhouettes the curved base, the quadrics and the ray-quadric distance, for protruded displacement mapping
// the texture of steep slopes (the built-in one, or the image of `rtm view --steep-texture`).
// Drawn while a per-pixel method is shown; the settings go to the draw as they are (RenderSettings::perpixel), the same
// as `rtm render` would use.
#pragma once

#include "perpixel/perpixel_method.h"

namespace rtm::viewer {

// ImGui widgets for `m`'s settings in `p` (inside the panel's window); ui_scale as the panel's.
void perpixel_settings_panel(PerPixelMethod m, PerPixelSettings& p, float ui_scale);

}  // namespace rtm::viewer
