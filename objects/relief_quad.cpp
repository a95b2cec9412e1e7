#include "objects/relief_quad.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "objects/micromesh.h"

namespace rtm {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
}  // namespace

RenderMethod parse_render_method(const std::string& s) {
    if (s == "flat") return RenderMethod::flat;
    if (s == "two-pass") return RenderMethod::two_pass;
    if (s == "pipelined") return RenderMethod::pipelined;
    if (s == "micromesh") return RenderMethod::micromesh;
    if (s == "raycast") return RenderMethod::raycast;
    throw std::invalid_argument("unknown method \"" + s + "\"; known: flat, two-pass, pipelined, micromesh, raycast");
}

std::string to_string(RenderMethod m) {
    switch (m) {
        case RenderMethod::flat: return "flat";
        case RenderMethod::two_pass: return "two-pass";
        case RenderMethod::pipelined: return "pipelined";
        case RenderMethod::micromesh: return "micromesh";
        case RenderMethod::raycast: return "raycast";
    }
    return "?";
}

ImageRGBA8 flat_texture(const ReliefTexture& t) {
    ImageRGBA8 img(t.width, t.height);
    for (size_t i = 0; i < t.texels.size(); ++i) {
        const ReliefTexel& x = t.texels[i];
        // Empty texels are (0, 0, 0, 0): the renderer divides filtered colour by alpha (no dark fringes).
        img.pixels[i] = x.q == kEmptyIndex ? Rgba8{} : Rgba8{x.r, x.g, x.b, 255};
    }
    return img;
}

ReliefQuad::ReliefQuad(ReliefTexture relief) : relief_(std::move(relief)) {}
ReliefQuad::~ReliefQuad() = default;
ReliefQuad::ReliefQuad(ReliefQuad&&) noexcept = default;

std::array<glm::dvec3, 4> ReliefQuad::corners() const {
    const ReliefGeometry& g = relief_.geometry;
    const glm::dvec3 aw = g.a * double(relief_.width), bh = g.b * double(relief_.height);
    return {g.origin, g.origin + aw, g.origin + aw + bh, g.origin + bh};
}

const MicroMesh& ReliefQuad::micromesh() {
    if (!micromesh_) micromesh_ = std::make_unique<MicroMesh>(build_micromesh(relief_));
    return *micromesh_;
}

bool ReliefQuad::faces(const glm::dvec3& eye) const {
    return compute_coefficients(relief_.geometry, eye).side == ViewSide::front;
}

double ReliefQuad::prewarp(const glm::dvec3& eye, const PrewarpOptions& options, bool with_displ) {
    const auto t0 = Clock::now();
    stats_ = rtm::prewarp(relief_, compute_coefficients(relief_.geometry, eye), options, workspace_, prewarped_,
                          with_displ ? &displ_ : nullptr);
    return ms_since(t0);
}

void ReliefQuad::draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                      StageTimes& times, bool depth_correction) {
    const auto t_start = Clock::now();
    if (!texture_) texture_ = std::make_unique<GlTexture>();
    const ImageRGBA8* img = nullptr;
    ReliefSurface rs;
    const ReliefGeometry& g = relief_.geometry;
    rs.origin = g.origin;
    rs.a = g.a;
    rs.b = g.b;
    rs.width = relief_.width;
    rs.height = relief_.height;
    bool warped = false;
    if (method == RenderMethod::flat) {
        if (flat_.empty()) flat_ = flat_texture(relief_);
        img = &flat_;
    } else if (method == RenderMethod::two_pass || method == RenderMethod::pipelined) {
        PrewarpOptions o = options;
        o.method = method == RenderMethod::two_pass ? Reconstruction::two_pass : Reconstruction::pipelined;
        times.prewarp_ms += prewarp(cam.eye, o, depth_correction);
        img = &prewarped_;
        warped = true;
        const PrewarpExtent& e = stats_.extent;
        rs.margin_left = e.left;
        rs.margin_right = e.right;
        rs.margin_bottom = e.bottom;
        rs.margin_top = e.top;
        if (options.keep_outliers) {
            rs.wall_low = std::min(0.0, relief_.quant.min);
            rs.wall_high = std::max(0.0, relief_.quant.max);
        }
    } else {
        throw std::invalid_argument("ReliefQuad::draw: method " + to_string(method) + " is not a texture method");
    }
    if (!faces(cam.eye)) {  // the quad faces away (or the eye is in its plane): not drawn (paper section 6)
        times.total_ms += ms_since(t_start);
        return;
    }
    auto t0 = Clock::now();
    texture_->upload(*img);
    if (warped && depth_correction) {
        if (!displ_texture_) displ_texture_ = std::make_unique<GlTexture>();
        displ_texture_->upload_gray(displ_);
        rs.displ = displ_texture_.get();
        rs.k3 = compute_coefficients(g, cam.eye).k3;
        rs.dmin = relief_.quant.min;
        rs.dmax = relief_.quant.max;
        rs.qs = relief_.quant.qs;
    }
    renderer.finish();
    times.upload_ms += ms_since(t0);
    t0 = Clock::now();
    renderer.draw_relief(cam, rs, *texture_);
    renderer.finish();
    times.texture_map_ms += ms_since(t0);
    times.total_ms += ms_since(t_start);
}

}  // namespace rtm
