// Exact CPU ray caster of the bilinearly interpolated height field of a relief texture: the surface through the
// texel centres X(u, v), bilinear in each cell between four texel centres. Rays are clipped to the relief's
// bounding slab, cells are walked with a 2-D DDA (accelerated by a min/max mipmap), and the intersection inside
// a cell is solved exactly (a quadratic along the ray). Colour: bilinear interpolation of the four texels.
// Cells with an empty texel are holes. Multi-threaded over rows of pixels; the output does not depend on the
// number of threads. Pixels that hit nothing are opaque black (the background).
#pragma once

#include <functional>
#include <limits>
#include <memory>

#include "texmap/camera.h"
#include "warp/image.h"
#include "warp/relief_texture.h"

namespace rtm {

struct RaycastOptions {
    int threads = 0;                                // 0 = all available
    std::function<void(double fraction)> progress;  // called now and then from the calling thread; may be empty
    // Reference mode for tests: every ray is intersected with every cell (no DDA, no min/max mipmap), the nearest
    // hit wins. O(cells) per ray: only for small reliefs.
    bool brute_force = false;
};

// Returns the image (row 0 = top) and, if depth is not null, the eye-space distance along each ray (infinity
// where nothing was hit). Throws std::invalid_argument when the camera is unusable (Camera::validate).
ImageRGBA8 raycast_relief(const ReliefTexture& t, const Camera& cam, const RaycastOptions& options = {},
                          ImageF* depth = nullptr);

// One ray against the surface, in double precision (what raycast_relief does per pixel).
struct ReliefRayHit {
    bool hit = false;
    double t = std::numeric_limits<double>::infinity();  // ray parameter: the distance when dir is a unit vector
    double u = 0.0, v = 0.0;                             // texture coordinates of the hit (texel units)
    Rgba8 color{0, 0, 0, 255};                           // bilinear colour at (u, v); background on a miss
};

// Builds the min/max mipmap once; cast() is const and safe to call from many threads.
class ReliefRaycaster {
public:
    explicit ReliefRaycaster(const ReliefTexture& t);  // keeps a reference to t
    ~ReliefRaycaster();
    ReliefRaycaster(const ReliefRaycaster&) = delete;
    ReliefRaycaster& operator=(const ReliefRaycaster&) = delete;
    // The first intersection with t >= 0 of origin + t*dir (dir need not be normalized; t is then in units of
    // |dir|). A zero or non-finite ray is a miss. brute_force: the reference path (RaycastOptions::brute_force).
    ReliefRayHit cast(const glm::dvec3& origin, const glm::dvec3& dir, bool brute_force = false) const;
    bool has_surface() const;  // false when no cell has four non-empty texels (nothing can be hit)

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace rtm
