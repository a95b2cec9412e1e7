// What a view needs of a relief quad, decided before any pre-warp (paper sections 4.3, 5, 6): is it seen at all,
// how large is it on screen, how far can its texels move, how far did they move since the last frame.
// Pure geometry, double precision.
#pragma once

#include <array>

#include "objects/bounds.h"
#include "texmap/camera.h"
#include "warp/prewarp_coefficients.h"
#include "warp/relief_texture.h"

namespace rtm {

// True when the box lies entirely outside the camera's view frustum (all 8 corners outside one clip plane).
// Conservative: false means "may be visible".
bool outside_frustum(const Camera& cam, const Bounds& box);

// Area in pixels of the quad's projection, or -1 when a corner is at or behind the eye's plane (then the area is
// unbounded and the caller should assume the quad is large).
double projected_area_pixels(const Camera& cam, const std::array<glm::dvec3, 4>& quad);

// Largest distance (in texels) any texel moves in the pre-warp for this view: u_i - u_s = (u_s - e)(1/(1+k3 d) - 1)
// is linear in u_s and monotonic in d, so the maximum is at a corner of [0, w] x [dmin, dmax] (per axis).
// Returns +infinity when some displacement cannot be pre-warped (1 + k3*d <= 0).
double max_parallax_texels(const ReliefTexture& t, const PrewarpCoefficients& k);

// Largest change (in texels) of any texel's pre-warped position between two views. The change is linear in
// u_s (so the extremes are at u_s = 0 and w) and smooth in d, which is sampled at 33 levels across the range.
double max_texel_motion(const ReliefTexture& t, const PrewarpCoefficients& k0, const PrewarpCoefficients& k1);

// The eye is inside the relief's bounding slab: its distance from the plane along f lies in [dmin, dmax] (and
// dmax > 0 or dmin < 0), so some texels are at or above the eye's plane and cannot be pre-warped.
bool eye_inside_slab(const ReliefTexture& t, const glm::dvec3& eye);

}  // namespace rtm
