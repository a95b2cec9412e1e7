#include "objects/relief_quad.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "objects/bounds.h"
#include "objects/fast_displ.h"
#include "objects/level_choice.h"
#include "objects/micromesh_tiles.h"
#include "objects/shared_relief.h"
#include "truth/micromesh.h"
#include "warp/timing.h"
#include "objects/view_analysis.h"
#include "warp/pyramid.h"

namespace rtm {

ImageRGBA8 flat_texture(const ReliefTexture& t) {
    ImageRGBA8 img(t.width, t.height);
    for (size_t i = 0; i < t.texels.size(); ++i) {
        const ReliefTexel& x = t.texels[i];
        // Empty texels are (0, 0, 0, 0): the renderer divides filtered colour by alpha (no dark fringes).
        img.pixels[i] = x.q == kEmptyIndex ? Rgba8{} : Rgba8{x.r, x.g, x.b, 255};
    }
    return img;
}

void premultiply_alpha(ImageRGBA8& img) {
    for (Rgba8& p : img.pixels) {
        if (p.a == 255) continue;
        auto m = [&](uint8_t c) { return uint8_t((unsigned(c) * p.a + 127) / 255); };
        p = {m(p.r), m(p.g), m(p.b), p.a};
    }
}

ReliefQuad::ReliefQuad(ReliefTexture relief, std::shared_ptr<SharedRelief> shared)
    : relief_(std::move(relief)), shared_(std::move(shared)) {}
ReliefQuad::~ReliefQuad() = default;
ReliefQuad::ReliefQuad(ReliefQuad&&) noexcept = default;

std::array<glm::dvec3, 4> ReliefQuad::corners() const { return quad_corners(relief_); }

const MicroMesh& ReliefQuad::micromesh() {
    if (!micromesh_) micromesh_ = std::make_unique<MicroMesh>(build_micromesh(relief_));
    return *micromesh_;
}

void ReliefQuad::draw_micromesh(Renderer& renderer, const Camera& cam, bool tiles, DrawReport* report) {
    if (!tiles) {
        const MicroMesh& m = micromesh();
        draw_mesh(renderer, cam, m);
        if (report) report->micromesh_triangles = report->micromesh_triangles_total = (long long)(m.indices.size() / 3);
        return;
    }
    if (!micromesh_gl_) {
        // Built, uploaded, and only its tiles kept: the vertices and indices live on the GPU alone.
        TiledMicroMesh tm = build_tiled_micromesh(relief_);
        auto gl = std::make_unique<GlMesh>();
        gl->upload(tm.mesh.vertices, tm.mesh.indices);
        micromesh_gl_ = std::move(gl);
        micromesh_tiles_ = std::move(tm.tiles);
        micromesh_origin_ = tm.mesh.origin;
        micromesh_tiled_triangles_ = (long long)(tm.mesh.indices.size() / 3);
    }
    size_t drawn = 0;
    renderer.draw_mesh_ranges(cam, *micromesh_gl_, visible_tile_ranges(micromesh_tiles_, cam, &drawn),
                              micromesh_origin_);
    if (report) {
        report->micromesh_triangles = (long long)drawn;
        report->micromesh_triangles_total = micromesh_tiled_triangles_;
    }
}

bool ReliefQuad::faces(const glm::dvec3& eye) const {
    return compute_coefficients(relief_.geometry, eye).side == ViewSide::front;
}

PerPixelQuad& ReliefQuad::perpixel() {
    if (!perpixel_) perpixel_ = std::make_unique<PerPixelQuad>();
    return *perpixel_;
}

const ReliefTexture& ReliefQuad::level_texture(int i) {
    if (i <= 0) return relief_;
    while (int(pyramid_.size()) < i) {
        const ReliefTexture& prev = pyramid_.empty() ? relief_ : pyramid_.back();
        if (prev.width == 1 && prev.height == 1) break;
        pyramid_.push_back(shared_ ? shared_->level(relief_, int(pyramid_.size()) + 1) : downsample(prev, relief_));
    }
    return pyramid_[size_t(std::min<int>(i, int(pyramid_.size()))) - 1];
}

const ReliefTexture& ReliefQuad::level(int i) { return level_texture(i); }

long long ReliefQuad::still_texels(int i, bool exact) {
    if (int(still_texels_.size()) <= i) still_texels_.resize(size_t(i) + 1, {-1, -1});
    long long& n = still_texels_[size_t(i)][exact];
    if (n < 0) n = count_still_texels(level_texture(i), exact);
    return n;
}

const MovingTexels& ReliefQuad::moving(int i) {
    if (int(moving_.size()) <= i) moving_.resize(size_t(i) + 1);
    std::optional<MovingTexels>& m = moving_[size_t(i)];
    if (!m) m = moving_texels(level_texture(i));
    return *m;
}

int ReliefQuad::levels() { return pyramid_levels(relief_.width, relief_.height); }

int ReliefQuad::auto_level(const Camera& cam) { return rtm::auto_level(cam, relief_); }

const std::vector<double>& ReliefQuad::spreads() {
    if (shared_) return shared_->spreads(relief_);
    if (spreads_.empty()) spreads_ = level_displacement_spreads(relief_);
    return spreads_;
}

int ReliefQuad::choose_level(const Camera& cam, double max_error_px) {
    return rtm::choose_level(cam, relief_, spreads(), max_error_px);
}

double ReliefQuad::prewarp(const glm::dvec3& eye, const PrewarpOptions& options, bool with_displ) {
    const auto t0 = Clock::now();
    stats_ = rtm::prewarp(relief_, compute_coefficients(relief_.geometry, eye), options, workspace_, prewarped_,
                          with_displ ? &displ_ : nullptr);
    ++prewarp_version_;
    last_prewarp_.valid = false;
    return ms_since(t0);
}

void ReliefQuad::draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                      StageTimes& times, const DrawOptions& d, DrawReport* report) {
    const auto t_start = Clock::now();
    DrawOptions fitted = d;
    fitted.max_texture_size = renderer.max_texture_size();
    const FramePlan plan = plan_draw(cam, method, options, fitted);
    DrawReport rep;
    rep.level = plan.level;
    rep.skips = plan.skips;
    if (plan.action == FrameAction::prewarp) prewarp_planned(plan, d, times, rep);
    present(renderer, cam, plan, d, times, rep, true);
    times.total_ms += ms_since(t_start);
    if (report) *report = rep;
}

FramePlan ReliefQuad::plan_draw(const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                                const DrawOptions& d) {
    return plan_frame(
        cam, method, options, d, relief_, [this](int i) -> const ReliefTexture& { return level_texture(i); },
        last_prewarp_, d.level < 0 ? &spreads() : nullptr);
}

void ReliefQuad::prewarp_planned(const FramePlan& plan, const DrawOptions& d, StageTimes& times, DrawReport& rep) {
    if (plan.action != FrameAction::prewarp)
        throw std::logic_error("ReliefQuad::prewarp_planned: the plan is " + plan.to_string() + ", not a pre-warp");
    const int lvl = plan.level;
    const ReliefTexture& t = level_texture(lvl);
    const PrewarpOptions& o = plan.prewarp;
    const auto t0 = Clock::now();
    if (d.depth_correction && fast_displ_covers(t, plan.k, o)) {  // objects/fast_displ.h
        if (int(index_levels_.size()) <= lvl) index_levels_.resize(size_t(lvl) + 1);
        if (!index_levels_[size_t(lvl)]) index_levels_[size_t(lvl)] = index_relief(t);
        stats_ = prewarp_fast_displ(t, *index_levels_[size_t(lvl)], plan.k, o, workspace_, prewarped_, displ_,
                                    index_warp_);
    } else {
        stats_ = rtm::prewarp(t, plan.k, o, workspace_, prewarped_, d.depth_correction ? &displ_ : nullptr);
    }
    ++prewarp_version_;
    // Coverage alpha: the texture-mapping stage expects premultiplied colour (it divides the filtered colour by the
    // filtered alpha); point-sampled output has alpha 0 or 255 only.
    if (o.filter == Filter::coverage) premultiply_alpha(prewarped_);
    if (o.keep_outliers) {
        const PrewarpExtent& e = stats_.extent;
        wall_content_ = margin_content(prewarped_, e.left, e.right, e.bottom, e.top);
    }
    times.prewarp_ms += ms_since(t0);
    last_prewarp_ = {true, plan.setup, plan.k, stats_.extent};
    // The still texels are a property of the level, counted once.
    const long long still = o.copy_still_runs ? still_texels(lvl, o.exact) : 0;
    if (zero_runs_fired(stats_, still)) {
        rep.skips.push_back(kSkipZeroRuns);
        rep.still_texels = still;
        rep.still_copied = stats_.still_copied;
    }
}

void ReliefQuad::present(Renderer& renderer, const Camera& cam, const FramePlan& plan, const DrawOptions& d,
                         StageTimes& times, DrawReport& rep, bool finish_each) {
    if (!texture_) texture_ = std::make_unique<GlTexture>();
    if (plan.action == FrameAction::nothing) return;
    if (plan.action == FrameAction::micromesh) {
        const auto t0 = Clock::now();
        draw_micromesh(renderer, cam, d.micromesh_tiles, &rep);
        if (finish_each) renderer.finish();
        times.texture_map_ms += ms_since(t0);
        return;
    }

    const int lvl = plan.level;
    const ReliefTexture& t = level_texture(lvl);
    ReliefSurface rs;
    rs.origin = t.geometry.origin;
    rs.a = t.geometry.a;
    rs.b = t.geometry.b;
    rs.width = t.width;
    rs.height = t.height;

    const bool warped = plan.action == FrameAction::prewarp || plan.action == FrameAction::reuse;
    if (warped) {
        const PrewarpExtent& e = stats_.extent;
        rs.margin_left = e.left;
        rs.margin_right = e.right;
        rs.margin_bottom = e.bottom;
        rs.margin_top = e.top;
        if (plan.setup.keep_outliers) {
            rs.wall_low = std::min(0.0, t.quant.min);
            rs.wall_high = std::max(0.0, t.quant.max);
            rs.wall_content = &wall_content_;
        }
    } else if (flat_level_ != lvl) {
        flat_ = flat_texture(t);
        flat_level_ = lvl;
    }
    const ImageRGBA8& img = warped ? prewarped_ : flat_;
    if (!plan.draw) return;  // skips disabled: the work was done to be measured, nothing is drawn

    auto t0 = Clock::now();
    // Upload only the pixels that can differ from the texture already on the GPU (plan_upload): eight corner warps
    // per frame, nothing read or kept.
    // Comparing the new image with a copy of the last upload, as this skip first did, cannot pay with llvmpipe
    // (OSMesa), where an upload is a memcpy: measured on the 2-core development machine, median ms, n^2 texels,
    //       n   full upload   find the changed rectangle (memcmp)   keep a copy   upload a 1.6% / 25% / 50% rectangle
    //     256     0.009              0.006                             0.007        0.0004 / 0.002 / 0.003
    //    1024     0.135              0.094 (0.33 in a frame, cold)     0.103        0.003  / 0.030 / 0.066
    //    2048     1.098              0.810                             0.914        0.009  / 0.178 / 0.429
    // (comparing pixel by pixel with Rgba8's operator== instead of memcmp: 0.056 ms at 256^2; that and the copy on
    // every frame whose margins changed the texture's size made bench-skips measure 1.0 -> 1.9 ms at 256^2). A
    // rectangle's upload costs in proportion to its area, so any rectangle smaller than the texture pays.
    UploadedTexture now;
    now.content = {warped ? TextureContent::Source::prewarp : TextureContent::Source::flat, lvl};
    now.version = prewarp_version_;
    now.width = img.width;
    now.height = img.height;
    now.setup = last_prewarp_.setup;
    now.extent = stats_.extent;
    if (warped) now.moving = moving_footprint(t, moving(lvl), last_prewarp_.k, stats_.extent);
    const UploadPlan up = plan_upload(now, uploaded_, d.skips && d.partial_upload);
    if (up.partial) {
        rep.skips.push_back(kSkipPartialUpload);
        if (!up.rect.empty()) texture_->upload_rect(img, up.rect.x, up.rect.row, up.rect.w, up.rect.h);
    } else {
        texture_->upload(img);
    }
    rep.uploaded_texels = up.rect.area();
    uploaded_ = up.next;
    if (warped && d.depth_correction) {
        if (!displ_texture_) displ_texture_ = std::make_unique<GlTexture>();
        // A reused pre-warp's displacements are on the GPU already (skips off: uploaded every frame, to measure).
        if (displ_version_ != prewarp_version_ || !d.skips) displ_texture_->upload_gray(displ_);
        displ_version_ = prewarp_version_;
        rs.displ = displ_texture_.get();
        rs.k3 = plan.k.k3;
        rs.dmin = t.quant.min;
        rs.dmax = t.quant.max;
        rs.qs = t.quant.qs;
    }
    if (finish_each) renderer.finish();
    times.upload_ms += ms_since(t0);
    t0 = Clock::now();
    renderer.draw_relief(cam, rs, *texture_);
    if (finish_each) renderer.finish();
    times.texture_map_ms += ms_since(t0);
}

}  // namespace rtm
