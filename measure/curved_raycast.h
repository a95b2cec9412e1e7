// A CPU ray caster of the relief bent over a cylinder or sphere patch (perpixel/curved_patch.h): the second truth
// of `rtm compare`'s curved base, beside curved_micromesh, built in another way so that the two check each other.
// The surface is the one curved_micromesh samples: the depth through the texel centres, here bilinear in the
// patch's (s, t) between them (the mesh joins the same points with flat triangles), displaced inwards along the
// radius. Each ray is clipped to the shell (outer cylinder or sphere, the cylinder's axial slab, the hollow inside
// the inner surface jumped) and marched in steps of a quarter texel, watching the sign of (depth - surface depth); a
// change is bisected. Both sides of the sheet count (the mesh is drawn without culling). Colour: bilinear of the
// four texels at the hit. Cells with an empty texel are holes; pixels that hit nothing are opaque black. Rows run in
// parallel; the output does not depend on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "perpixel/curved_patch.h"
#include "texmap/camera.h"
#include "warp/image.h"
#include "warp/relief_texture.h"

namespace rtm {

// threads: 0 = all available. Throws std::invalid_argument when the camera is unusable.
ImageRGBA8 raycast_curved_relief(const ReliefTexture& t, const CurvedPatch& p, const Camera& cam, int threads = 0);

// The relief's shadows on itself, per pixel (row 0 the top of the view): 0 where the ray meets nothing, 1 where the
// point seen is lit, 2 where it is in shadow: the ray from it towards `light` (world direction towards the light)
// meets the surface, or starts under it (the point faces away). The truth of quadric silhouettes' self-shadowing.
std::vector<uint8_t> curved_relief_shadows(const ReliefTexture& t, const CurvedPatch& p, const Camera& cam,
                                           const glm::dvec3& light, int threads = 0);

}  // namespace rtm
