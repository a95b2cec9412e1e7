// A relief-textured quad: a relief texture, its pre-warp state and its texture on the GPU. draw() runs the two
// steps of relief texture mapping for one view: pre-warp for the camera's centre of projection, then ordinary
// texture mapping of the result onto the quad. Stage times are measured as the paper's Table 1 splits them.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "texmap/camera.h"
#include "texmap/renderer.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm {

struct MicroMesh;

enum class RenderMethod { flat, two_pass, pipelined, micromesh, raycast };

RenderMethod parse_render_method(const std::string& s);  // throws std::invalid_argument naming s
std::string to_string(RenderMethod m);

struct StageTimes {
    double prewarp_ms = 0.0;      // pre-warping and resampling
    double upload_ms = 0.0;       // loading the pre-warped texture into texture memory
    double texture_map_ms = 0.0;  // the texture-mapping draw (glFinish-bounded)
    double total_ms = 0.0;
};

class ReliefQuad {
public:
    explicit ReliefQuad(ReliefTexture relief);
    ~ReliefQuad();
    ReliefQuad(ReliefQuad&&) noexcept;

    const ReliefTexture& relief() const { return relief_; }
    std::array<glm::dvec3, 4> corners() const;  // (0,0), (w,0), (w,h), (0,h) in texel units
    // True when the camera sees the front (+f) side of the quad.
    bool faces(const glm::dvec3& eye) const;

    // Pre-warps for `eye` into the CPU image returned by prewarped(). Returns the time in milliseconds.
    double prewarp(const glm::dvec3& eye, const PrewarpOptions& options, bool with_displ = false);
    const ImageRGBA8& prewarped() const { return prewarped_; }
    const PrewarpStats& last_stats() const { return stats_; }
    // The micro-polygon mesh of this relief (ground truth), built on first use.
    const MicroMesh& micromesh();

    // Draws with `method` (flat, two_pass or pipelined) into the current frame. Requires a current GL context.
    // options.keep_outliers draws the side polygons (paper section 4, Figure 12); depth_correction sets each
    // fragment's depth from the perceived displacement (section 4.2) so interpenetrating polygons are hidden
    // where they should be.
    void draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
              StageTimes& times, bool depth_correction = false);

private:
    ReliefTexture relief_;
    PrewarpWorkspace workspace_;
    ImageRGBA8 prewarped_;
    PrewarpStats stats_;
    Image2D<uint8_t> displ_;  // quantized displacement seen at each pre-warped pixel (depth correction)
    std::unique_ptr<GlTexture> texture_, displ_texture_;
    ImageRGBA8 flat_;  // source colours as an ordinary texture (alpha 0 where empty)
    std::unique_ptr<MicroMesh> micromesh_;
};

// The relief's colours as an ordinary texture (the conventional texture mapping of Figure 1).
ImageRGBA8 flat_texture(const ReliefTexture& t);

}  // namespace rtm
