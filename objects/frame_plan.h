// What a relief quad does for one frame, decided without OpenGL: which skips fire, which pyramid level, whether to
// pre-warp, reuse the last pre-warp or draw a plain texture, and which pixels of the texture to upload. Pure
// functions from the view, the relief and the state the last frame left to a plan; ReliefQuad::draw carries the
// plan out (pre-warp, upload, draw). Objects and scenes with several quads call the same functions per quad.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "objects/render_method.h"
#include "objects/view_analysis.h"
#include "texmap/camera.h"
#include "warp/prewarp.h"
#include "warp/prewarp_coefficients.h"
#include "warp/relief_texture.h"

namespace rtm {

// How draw() chooses what to do for a frame. Each "skip" keeps the cost proportional to what the viewer sees;
// `skips` in the report lists those that fired (names as in kSkipNames).
struct DrawOptions {
    bool depth_correction = false;  // section 4.2
    int level = 0;  // relief texture pyramid level; -1 = auto (texel density ~ pixel density, within level_error_px)
    // auto: a level coarser than 0 only where the parallax of its texels' displacement spread is at most this many
    // pixels (objects/level_choice.h); infinity = the density alone.
    double level_error_px = 0.5;
    bool skips = true;                // enable the skips below (off: always pre-warp and upload everything)
    double subpixel_parallax = 0.25;  // pixels: below this largest parallax, draw as a plain texture (far away)
    double reuse_tolerance = 0.05;    // texels: below this largest motion since the last pre-warp, reuse it
    // With skips, each of these may be switched off alone (to measure what it saves, rtm bench-skips): cull is
    // outside-frustum, back-facing and offscreen-margins, partial_upload the partial-upload skip (plan_upload).
    bool cull = true;
    bool partial_upload = true;
    // inside-slab-micromesh draws the relief's micro-polygons from a copy kept on the GPU, only the 16x16-cell tiles
    // not wholly outside the frustum (objects/micromesh_tiles.h); off: the whole mesh, uploaded every frame.
    bool micromesh_tiles = true;
    // Objects: warp the adjacent faces only where the face's own pre-warp left holes (the same image; off: whole, to
    // measure what it saves).
    bool adjacent_holes_only = true;
    // The largest texture the texture-mapping stage takes (GL_MAX_TEXTURE_SIZE; 0: no limit). The margins that hold
    // the side polygons' samples are cut so that the pre-warped texture fits: a 16384x1 relief, or a 4096^2 one seen
    // at a grazing angle, asks for margins past it (every frame failed at the upload). Set by ReliefQuad::draw and
    // draw_quad_frame from the renderer; not a skip (it always applies, and changes the picture only past the limit).
    int max_texture_size = 0;
};

// Skip names, reported in --json "skips".
inline constexpr const char* kSkipBackFacing = "back-facing";
inline constexpr const char* kSkipOutsideFrustum = "outside-frustum";
inline constexpr const char* kSkipSubpixelParallax = "subpixel-parallax";
inline constexpr const char* kSkipReuse = "reuse-prewarp";
inline constexpr const char* kSkipPartialUpload = "partial-upload";
inline constexpr const char* kSkipInsideSlab = "inside-slab-micromesh";
inline constexpr const char* kSkipZeroRuns = "zero-displacement-runs";
inline constexpr const char* kSkipOffscreenMargins = "offscreen-margins";

// What a pre-warp was made for: two pre-warps of the same setup differ only through the eye.
struct PrewarpSetup {
    int level = -1;
    RenderMethod method = RenderMethod::flat;
    bool exact = false, keep_outliers = false, displ = false;
    Filter filter = Filter::point;
    friend bool operator==(const PrewarpSetup&, const PrewarpSetup&) = default;
};

// The pre-warp a quad holds: for which setup and view (coefficients k); none when !valid.
struct LastPrewarp {
    bool valid = false;
    PrewarpSetup setup;
    PrewarpCoefficients k;
    PrewarpExtent extent;  // its margins (offscreen-margins may have cut them to what that view could see)
};

// What a texture holds: nothing, a pre-warp, or the plain colours of a pyramid level (flat_texture).
struct TextureContent {
    enum class Source { none, prewarp, flat };
    Source source = Source::none;
    int level = 0;  // the pyramid level of the pre-warp or of the plain colours
    friend bool operator==(const TextureContent&, const TextureContent&) = default;
};
std::string to_string(const TextureContent& c);

// What the texture on the GPU holds, for the partial upload: which image (a pre-warp is also named by its version,
// counting the quad's pre-warps), its size, the setup and margins of the pre-warp, where its moving texels wrote.
struct UploadedTexture {
    TextureContent content;
    long long version = -1;
    int width = 0, height = 0;
    PrewarpSetup setup;
    PrewarpExtent extent;
    PixelRect moving;
};

// What the frame does with the relief.
enum class FrameAction {
    nothing,    // a skip fired before any work (outside the frustum, back-facing)
    micromesh,  // draw the micro-polygons (the eye is inside the relief's slab)
    flat,       // draw the level's colours as a plain texture (method flat, or subpixel parallax)
    prewarp,    // pre-warp the level for this eye, then texture-map it
    reuse,      // texture-map the last pre-warp again (the eye barely moved)
};
std::string to_string(FrameAction a);

struct FramePlan {
    FrameAction action = FrameAction::nothing;
    std::vector<std::string> skips;  // the skips decided before any work, in the order they fired
    int level = 0;                   // the pyramid level drawn (0 for nothing and micromesh)
    bool draw = true;                // false: back-facing with skips off; the work is done (to measure), not drawn
    PrewarpOptions prewarp;          // prewarp: the options to pre-warp with (method and still-run copies set)
    PrewarpSetup setup;              // prewarp and reuse: the setup of the pre-warp drawn
    PrewarpCoefficients k;           // flat, prewarp and reuse: the level's coefficients for this eye
    std::string to_string() const;
};

// The relief's pyramid level i (0 = the relief itself), as the quad builds them.
using LevelSource = std::function<const ReliefTexture&(int)>;

// The number of pyramid levels of a w x h relief (down to 1x1).
int pyramid_levels(int width, int height);
// The level `auto` picks for this camera: texel density roughly matching pixel density (level 0 when the quad
// reaches behind the eye).
int auto_level(const Camera& cam, const ReliefTexture& relief);

// The margins `e` of a width x height pre-warp cut (each axis in proportion) so that the texture is at most
// max_size texels a side: DrawOptions::max_texture_size.
PrewarpExtent fit_texture_size(const PrewarpExtent& e, int width, int height, int max_size);

// The frame's plan. `relief` is level 0; `method` is flat, two_pass or pipelined (else std::invalid_argument).
// The rules, in order (each only with d.skips, except the level choice; the first and third also with d.cull):
//   outside-frustum: the relief's bounds lie outside the view frustum -> nothing.
//   inside-slab-micromesh: a warping method and the eye inside the relief's slab -> micromesh.
//   back-facing: the eye sees the back of the quad -> nothing (skips off: the work is done, draw = false).
//   level: d.level < 0 -> choose_level (objects/level_choice.h) with `spreads` (level_displacement_spreads of
//          `relief`; computed here when null), else d.level clamped to the pyramid.
//   subpixel-parallax: a warping method whose largest parallax on screen is below d.subpixel_parallax pixels -> flat.
//   reuse-prewarp: the last pre-warp has the same setup and no texel moved by d.reuse_tolerance texels since -> reuse.
// With side polygons, the margins are cut to d.max_texture_size (fit_texture_size) whatever d.skips says.
FramePlan plan_frame(const Camera& cam, RenderMethod method, const PrewarpOptions& options, const DrawOptions& d,
                     const ReliefTexture& relief, const LevelSource& level, const LastPrewarp& last,
                     const std::vector<double>* spreads = nullptr);

// Which pixels of a texture to upload. `now` is what the new image holds (`version`: its pre-warp's; size w x h;
// for a pre-warp its setup, margins and moving_footprint). Pixels that moving texels cannot reach are written by
// still texels only and are the same in every pre-warp of this level and setup (moving_footprint), so after a
// pre-warp of the same setup and margins only the union of the two moving footprints can differ; the same image
// again needs no upload. With skips off everything is uploaded and nothing remembered.
struct UploadPlan {
    PixelRect rect;        // the pixels to upload (may be empty)
    bool partial = false;  // smaller than the whole image: the partial-upload skip fired
    UploadedTexture next;  // what the texture holds afterwards
};
UploadPlan plan_upload(const UploadedTexture& now, const UploadedTexture& last, bool skips);

// The zero-displacement-runs skip of a pre-warp made with options `o` (paper section 5, the brick wall): texels at
// zero displacement were copied, not warped. The reference kernels count their copies (stats.still_copied); the SIMD
// kernels (every target but generic) copy one-pixel spans on pixel centres and still column steps without counting.
// `still` = count_still_texels of the relief when the options' copy_still_runs is on, else 0. Returns true when the
// skip fired.
bool zero_runs_fired(const PrewarpStats& stats, long long still);

}  // namespace rtm
