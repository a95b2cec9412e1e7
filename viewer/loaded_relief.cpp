#include "viewer/loaded_relief.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "formats/image_io.h"
#include "formats/relief_manifest.h"
#include "truth/micromesh.h"
#include "truth/raycast.h"
#include "viewer/drawn_quad.h"
#include "warp/timing.h"

namespace rtm::viewer {

void parse_split(const std::string& text, ViewSettings& s) {
    if (text == "truth") {
        s.split = SplitMode::truth;
        return;
    }
    const RenderMethod m = parse_render_method(text);  // throws naming the value
    if (m == RenderMethod::raycast)
        throw std::invalid_argument(
            "raycast is a still, it cannot be one side of the split view; use micromesh or "
            "truth");
    s.split = SplitMode::method;
    s.split_method = m;
}

RenderSettings render_settings(const ViewSettings& s) {
    RenderSettings rs;
    rs.method = s.method;
    rs.prewarp.keep_outliers = s.side_polygons;
    rs.prewarp.threads = s.threads;
    // The coverage filter exists for the two-pass reconstruction only.
    rs.prewarp.filter = s.coverage && s.method == RenderMethod::two_pass ? Filter::coverage : Filter::point;
    rs.draw.depth_correction = s.depth_correction;
    rs.draw.skips = s.skips;
    rs.draw.level = s.level;
    rs.perpixel = s.perpixel;
    return rs;
}

LoadedRelief::LoadedRelief(const std::string& manifest) : path_(manifest) { reload(-1); }

void LoadedRelief::reload(double discontinuity) {
    ReliefTexture t = load_relief(path_);
    if (discontinuity >= 0) mark_discontinuities(t, discontinuity);
    quad_ = std::make_unique<ReliefQuad>(std::move(t));
    if (steep_) quad_->perpixel().set_steep_texture(*steep_);
    discontinuity_ = discontinuity;
}

void LoadedRelief::set_steep_texture(const ImageRGBA8& img) {
    quad_->perpixel().set_steep_texture(img);  // checks the image first
    steep_ = std::make_unique<ImageRGBA8>(img);
}

Bounds LoadedRelief::bounds() const { return relief_bounds(quad_->relief()); }

void LoadedRelief::draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) {
    if (s.discontinuity != discontinuity_) reload(s.discontinuity);
    const RenderSettings rs = render_settings(s);
    if (s.method == RenderMethod::micromesh) {
        const auto t0 = Clock::now();
        const MicroMesh& mesh = quad_->micromesh();
        draw_mesh(renderer, cam, mesh);
        renderer.finish();
        report.times.texture_map_ms += ms_since(t0);
        report.times.total_ms += ms_since(t0);
        return;
    }
    if (s.method == RenderMethod::raycast) throw std::logic_error("LoadedRelief::draw: raycast is a still");
    if (const auto pp = perpixel_method(s.method)) {  // with the panel's settings (the defaults, as rtm render)
        const auto t0 = Clock::now();
        quad_->perpixel().draw(renderer, cam, quad_->relief(), *pp, rs.perpixel);
        renderer.finish();
        report.times.texture_map_ms += ms_since(t0);
        report.times.total_ms += ms_since(t0);
        return;
    }
    StageTimes st;
    DrawReport rep;
    quad_->draw(renderer, cam, rs.method, rs.prewarp, st, rs.draw, &rep);
    report.times.prewarp_ms += st.prewarp_ms;
    report.times.upload_ms += st.upload_ms;
    report.times.texture_map_ms += st.texture_map_ms;
    report.times.total_ms += st.total_ms;
    report.level = rep.level;
    for (const std::string& k : rep.skips)
        if (std::find(report.skips.begin(), report.skips.end(), k) == report.skips.end()) report.skips.push_back(k);
    if (st.prewarp_ms > 0) report.texels_warped += quad_->last_stats().texels;

    DrawnQuad q;
    if (describe_drawn_quad(*quad_, path_, cam, s, rep.skips, rep.level, q)) report.quads.push_back(std::move(q));
}

ImageRGBA8 LoadedRelief::raycast(const Camera& cam, const ViewSettings& s) {
    if (s.discontinuity != discontinuity_) reload(s.discontinuity);
    RaycastOptions ro;
    ro.threads = s.threads;
    return raycast_relief(quad_->relief(), cam, ro);
}

}  // namespace rtm::viewer
