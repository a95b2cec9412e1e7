// What a view needs of a relief quad, decided before any pre-warp (paper sections 4.3, 5, 6): is it seen at all,
// how large is it on screen, how far can its texels move, how far did they move since the last frame.
// Pure geometry, double precision.
#pragma once

#include <glm/mat4x4.hpp>

#include <array>

#include "objects/bounds.h"
#include "texmap/camera.h"
#include "warp/prewarp.h"
#include "warp/prewarp_coefficients.h"
#include "warp/relief_texture.h"

namespace rtm {

// True when the box lies entirely outside the camera's view frustum (all 8 corners outside one clip plane).
// Conservative: false means "may be visible".
bool outside_frustum(const Camera& cam, const Bounds& box);
// The same with the camera's clip-from-world matrix (projection * view), for many boxes in one view.
bool outside_frustum(const glm::dmat4& clip_from_world, const Bounds& box);

// The margins of a pre-warp with side polygons (paper section 4, Figure 12: samples that leave the quad) that the
// camera can see: each side of `full` (the margins the view's samples need) cut to the bounding box, in texels, of the
// part of the relief plane inside the camera's viewing cone, widened by `guard` texels; a margin wholly off screen
// becomes 0. A margin's texel shows only through a side polygon's fragment whose eye ray meets the relief plane at the
// texel (texmap/wall_clip.h), so a texel whose plane point projects outside the viewport is never seen. Only the cone's
// four side planes bound the region (not the near and far planes, which a side polygon may cross).
PrewarpExtent visible_margins(const Camera& cam, const ReliefTexture& t, const PrewarpExtent& full, double guard);

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
// The same over any point of [0, w] x [0, h] x [dmin, dmax] (texel units, world displacement): for a face of an
// object, every point of the box behind it (its adjacent faces' samples included).
double max_motion_texels(int w, int h, double dmin, double dmax, const PrewarpCoefficients& k0,
                         const PrewarpCoefficients& k1);

// The eye is inside the relief's bounding slab: its distance from the plane along f lies in [dmin, dmax] (and
// dmax > 0 or dmin < 0), so some texels are at or above the eye's plane and cannot be pre-warped.
bool eye_inside_slab(const ReliefTexture& t, const glm::dvec3& eye);

// The texels that can move in a pre-warp: non-empty texels not at zero displacement, in the lookup tables' sense
// (a level that decodes to 0) or in the exact sense (0.0), either of them. Their bounding box in storage
// coordinates and their displacement range (both senses). Does not depend on the view.
struct MovingTexels {
    bool any = false;
    int x0 = 0, x1 = -1, row0 = 0, row1 = -1;  // inclusive
    double dmin = 0.0, dmax = 0.0;
};
MovingTexels moving_texels(const ReliefTexture& t);

// A rectangle of image pixels, rows counted from the top; empty when w or h is 0.
struct PixelRect {
    int x = 0, row = 0, w = 0, h = 0;
    bool empty() const { return w <= 0 || h <= 0; }
    long long area() const { return empty() ? 0 : (long long)w * h; }
};
PixelRect united(const PixelRect& a, const PixelRect& b);

// The pixels of the pre-warp for view k (margins e around the quad) that moving texels can write: their own
// samples, and the spans that join them to their neighbours in either pass (which end on the neighbours' centres
// when those are still). A conservative box: every pixel outside it is written by still texels only, each on the
// centre of its own pixel, whatever the view, method, path or order (warp/reference/reference_prewarp.cpp,
// warp_line_still_to), so it is the same in every pre-warp of this relief with the same margins. Empty when nothing
// moves.
PixelRect moving_footprint(const ReliefTexture& t, const MovingTexels& m, const PrewarpCoefficients& k,
                           const PrewarpExtent& e);

}  // namespace rtm
