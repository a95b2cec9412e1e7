// The pyramid level of a relief quad for a view (`--level auto`, paper section 4.3): the level whose texel density
// matches the pixel density (level_for_density, warp/pyramid.h), but no coarser than the parallax allows. A level-L
// texel averages the displacements of its 2^L x 2^L level-0 texels, so where they differ (a window frame standing
// out of a wall, a tile's edge) the averaged texel lands where none of them would: off by the parallax of the
// displacements' spread. The density rule alone ignored that, and at 320x240 it cost the town's relief half its
// accuracy margin over flat texture mapping (+6.4 and +6.9 dB at path frames 42 and 0, against +12.5 and +12.4 at
// level 0; docs/SCENES.md, "--level"); smooth reliefs (bumps) and quads whose parallax is a fraction of a pixel
// still go coarse.
#pragma once

#include <vector>

#include "texmap/camera.h"
#include "warp/relief_texture.h"

namespace rtm {

// spreads[L] for L = 0 .. levels - 1: the largest range (max - min, world units) of the exact displacements of the
// non-empty level-0 texels inside one level-L texel (blocks of 2^L x 2^L aligned with the bottom-left corner, as
// warp/pyramid.h builds the levels). spreads[0] = 0; non-decreasing. Does not depend on the view.
std::vector<double> level_displacement_spreads(const ReliefTexture& level0);

// Pixels of screen parallax per world unit of displacement for this view: the largest parallax of the relief
// (max_parallax_texels) in pixels (the quad's mean pixels per texel, from its projected area) over the largest
// |displacement|. 0 for a relief without displacement; +infinity when some displacement cannot be pre-warped or the
// quad reaches behind the eye.
double parallax_pixels_per_unit(const Camera& cam, const ReliefTexture& level0);

// The level `auto` draws: the density level, or the coarsest finer one whose spread's parallax,
// spreads[L] * parallax_pixels_per_unit, is at most max_error_px pixels; level 0 when the quad reaches behind the eye.
int choose_level(const Camera& cam, const ReliefTexture& level0, const std::vector<double>& spreads,
                 double max_error_px);

}  // namespace rtm
