// What the insets and outlines are told about one relief quad after ReliefQuad::draw: its corners, level, the
// texture it mapped with its margins, the epipole and the side polygons. Shared by the relief and the scene.
#pragma once

#include <string>
#include <vector>

#include "viewer/loaded.h"

namespace rtm::viewer {

// Whether a quad drawn with `method` maps a pre-warp (else its flat texture), given the skips that fired for it.
bool maps_prewarp(RenderMethod method, const std::vector<std::string>& skips);

// The fields every drawn quad has, filled the same way for a relief, a scene's quad and an object's face: `name`,
// the quad's corners, `level` and its size there, the texture mapped (`texture`), whether it is a pre-warp, and the
// epipole for eye `cam.eye`. Margins and side polygons are left empty (an object's faces have none).
DrawnQuad fill_drawn_quad(ReliefQuad& quad, const std::string& name, const Camera& cam, int level,
                          const GlTexture& texture, bool warped);

// Describes `quad` as drawn this frame with the settings `s` at pyramid `level`, `skips` being the skips that
// fired for it. False (and `out` untouched) when the quad was not drawn: left out by a skip, seen from behind, or
// never given a texture.
bool describe_drawn_quad(ReliefQuad& quad, const std::string& name, const Camera& cam, const ViewSettings& s,
                         const std::vector<std::string>& skips, int level, DrawnQuad& out);

}  // namespace rtm::viewer
