// A relief-textured quad: a relief texture, its pre-warp state and its texture on the GPU. draw() runs the two
// steps of relief texture mapping for one view: pre-warp for the camera's centre of projection, then ordinary
// texture mapping of the result onto the quad. Stage times are measured as the paper's Table 1 splits them.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "objects/frame_plan.h"
#include "objects/view_analysis.h"
#include "perpixel/perpixel_quad.h"
#include "texmap/camera.h"
#include "texmap/renderer.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm {

struct MicroMesh;
struct MicroMeshTile;
class SharedRelief;

struct StageTimes {
    double prewarp_ms = 0.0;      // pre-warping and resampling
    double upload_ms = 0.0;       // loading the pre-warped texture into texture memory
    double texture_map_ms = 0.0;  // the texture-mapping draw (glFinish-bounded)
    double total_ms = 0.0;
};

struct DrawReport {
    int level = 0;
    std::vector<std::string> skips;
    long long uploaded_texels = 0;
    // zero-displacement-runs: the level's texels at zero displacement (view-independent, count_still_texels), and
    // how many of them the reference kernels copied this frame (0 from the fast kernels: they copy without counting).
    long long still_texels = 0;
    long long still_copied = 0;
    // inside-slab-micromesh: the micro-polygons drawn (with DrawOptions::micromesh_tiles, those of the tiles the
    // frustum can hold) and the mesh's whole count.
    long long micromesh_triangles = 0, micromesh_triangles_total = 0;
};

class ReliefQuad {
public:
    // With `shared`, the pyramid levels and their spreads come from it (shared with other quads holding copies of the
    // same relief in other places: objects/shared_relief.h); without, the quad makes its own.
    explicit ReliefQuad(ReliefTexture relief, std::shared_ptr<SharedRelief> shared = nullptr);
    ~ReliefQuad();
    ReliefQuad(ReliefQuad&&) noexcept;

    const ReliefTexture& relief() const { return relief_; }
    std::array<glm::dvec3, 4> corners() const;  // (0,0), (w,0), (w,h), (0,h) in texel units
    // True when the camera sees the front (+f) side of the quad.
    bool faces(const glm::dvec3& eye) const;
    // Pyramid level i (0 = the relief itself); built on first use.
    const ReliefTexture& level(int i);
    int levels();
    // The level `auto` picks for this camera: texel density roughly matching pixel density.
    int auto_level(const Camera& cam);
    // The level `auto` picks when this quad is drawn (plan_draw): the coarsest level the density allows whose
    // displacement spread keeps the parallax error within `max_error_px` (objects/level_choice.h).
    int choose_level(const Camera& cam, double max_error_px);
    // level_displacement_spreads of the relief (objects/level_choice.h), computed on first use: what choose_level
    // reads, for callers that plan a frame of this quad themselves (a six-face object's faces).
    const std::vector<double>& spreads();

    // Pre-warps level 0 for `eye` into prewarped(). Returns the time in milliseconds.
    double prewarp(const glm::dvec3& eye, const PrewarpOptions& options, bool with_displ = false);
    const ImageRGBA8& prewarped() const { return prewarped_; }
    const PrewarpStats& last_stats() const { return stats_; }
    // The texture the last draw() mapped on the quad (pre-warp or flat); null before the first draw.
    const GlTexture* texture() const { return texture_.get(); }
    // The micro-polygon mesh of this relief (ground truth), built on first use.
    const MicroMesh& micromesh();
    // Draws the micro-polygon mesh for the eye inside the slab: with `tiles`, from a copy kept on the GPU, only the
    // tiles not wholly outside the frustum; else the whole mesh, uploaded for this draw. Counts into `report`.
    void draw_micromesh(Renderer& renderer, const Camera& cam, bool tiles, DrawReport* report = nullptr);
    // The per-pixel methods' textures and programs for this relief (level 0), made on first use.
    PerPixelQuad& perpixel();

    // Draws with `method` (flat, two_pass or pipelined) into the current frame. Requires a current GL context,
    // the same one for the life of the quad. options.keep_outliers draws the side polygons (paper section 4,
    // Figure 12). What the frame does (skips, level, pre-warp or reuse, which pixels to upload) is decided by
    // plan_frame and plan_upload (objects/frame_plan.h); draw() carries the plan out.
    void draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
              StageTimes& times, const DrawOptions& draw = {}, DrawReport* report = nullptr);

    // draw() in its three steps, for a frame of many quads (objects/quad_frame.h): plan_draw decides (pure but for
    // building the pyramid level it needs), prewarp_planned does the CPU work of a FrameAction::prewarp plan and
    // touches nothing but this quad (so different quads may run it at the same time, on any thread), present
    // uploads and texture-maps (OpenGL, the context's thread). `report` starts as the plan's level and skips and
    // gains those that fire later (zero-displacement-runs, partial-upload), in draw()'s order. With `finish_each`
    // present forces a finish after the upload and after the draw so each stage's time is its own (draw() does);
    // without it the stage times are what issuing the calls took, and the caller's one finish holds the rest.
    FramePlan plan_draw(const Camera& cam, RenderMethod method, const PrewarpOptions& options, const DrawOptions& d);
    void prewarp_planned(const FramePlan& plan, const DrawOptions& d, StageTimes& times, DrawReport& report);
    void present(Renderer& renderer, const Camera& cam, const FramePlan& plan, const DrawOptions& d, StageTimes& times,
                 DrawReport& report, bool finish_each);

private:
    ReliefTexture relief_;
    std::vector<ReliefTexture> pyramid_;    // levels 1.. (level 0 is relief_), built on first use
    std::shared_ptr<SharedRelief> shared_;  // where pyramid_'s texels and the spreads come from; null: made here
    PrewarpWorkspace workspace_;
    ImageRGBA8 prewarped_;
    long long prewarp_version_ = 0;  // counts the pre-warps into prewarped_
    Image2D<uint8_t> displ_;         // quantized displacement seen at each pre-warped pixel (depth correction)
    PrewarpStats stats_;
    std::vector<PlaneRect> wall_content_;  // margin_content of prewarped_ (side polygons on), made with it
    std::unique_ptr<GlTexture> texture_, displ_texture_;
    long long displ_version_ = -1;  // the pre-warp whose displacements displ_texture_ holds
    ImageRGBA8 flat_;               // source colours of level flat_level_ as an ordinary texture (alpha 0 where empty)
    int flat_level_ = -1;
    std::unique_ptr<MicroMesh> micromesh_;
    // The micro-polygon mesh ordered by 16x16-cell tiles (objects/micromesh_tiles.h) on the GPU, uploaded on first
    // use; on the CPU only its tiles' index ranges and bounds (and its triangle count) stay.
    std::unique_ptr<GlMesh> micromesh_gl_;
    std::vector<MicroMeshTile> micromesh_tiles_;
    glm::dvec3 micromesh_origin_{0.0};  // the GPU copy's positions are relative to it (MicroMesh::origin)
    long long micromesh_tiled_triangles_ = 0;
    LastPrewarp last_prewarp_;                // what prewarped_ was made for (reuse when the eye barely moved)
    UploadedTexture uploaded_;                // what texture_ holds (partial upload)
    std::unique_ptr<PerPixelQuad> perpixel_;  // the per-pixel methods' textures and programs, made on first use
    // count_still_texels per pyramid level, [level][exact]; -1 = not counted yet (they do not depend on the view).
    std::vector<std::array<long long, 2>> still_texels_;
    std::vector<std::optional<MovingTexels>> moving_;  // moving_texels per pyramid level, computed on first use
    // Depth correction on the fast kernels (objects/fast_displ.h): index_relief per pyramid level, made on first use,
    // and the image of the index pre-warp.
    std::vector<std::optional<ReliefTexture>> index_levels_;
    ImageRGBA8 index_warp_;
    std::vector<double> spreads_;  // level_displacement_spreads (objects/level_choice.h), computed on first use

    const ReliefTexture& level_texture(int i);
    long long still_texels(int level, bool exact);
    const MovingTexels& moving(int level);
};

// The relief's colours as an ordinary texture (the conventional texture mapping of Figure 1).
ImageRGBA8 flat_texture(const ReliefTexture& t);

// Straight colour to premultiplied (colour * alpha / 255, rounded), in place: what the texture-mapping stage
// expects of a texture whose alpha is fractional coverage (the coverage filter's output).
void premultiply_alpha(ImageRGBA8& img);

}  // namespace rtm
