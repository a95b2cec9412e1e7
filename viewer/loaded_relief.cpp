#include "viewer/loaded_relief.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "formats/image_io.h"
#include "formats/relief_manifest.h"
#include "truth/micromesh.h"
#include "truth/raycast.h"
#include "warp/prewarp_coefficients.h"
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
    return rs;
}

LoadedRelief::LoadedRelief(const std::string& manifest) : path_(manifest) { reload(-1); }

void LoadedRelief::reload(double discontinuity) {
    ReliefTexture t = load_relief(path_);
    if (discontinuity >= 0) mark_discontinuities(t, discontinuity);
    quad_ = std::make_unique<ReliefQuad>(std::move(t));
    discontinuity_ = discontinuity;
}

Bounds LoadedRelief::bounds() const { return relief_bounds(quad_->relief()); }

void LoadedRelief::draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) {
    if (s.discontinuity != discontinuity_) reload(s.discontinuity);
    const RenderSettings rs = render_settings(s);
    if (s.method == RenderMethod::micromesh) {
        const auto t0 = Clock::now();
        const MicroMesh& mesh = quad_->micromesh();
        renderer.draw_mesh(cam, mesh.vertices, mesh.indices);
        renderer.finish();
        report.times.texture_map_ms += ms_since(t0);
        report.times.total_ms += ms_since(t0);
        return;
    }
    if (s.method == RenderMethod::raycast) throw std::logic_error("LoadedRelief::draw: raycast is a still");
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

    // What was drawn: nothing when a skip left the quad out.
    auto fired = [&](const char* k) { return std::find(rep.skips.begin(), rep.skips.end(), k) != rep.skips.end(); };
    if (fired(kSkipOutsideFrustum) || fired(kSkipBackFacing) || fired(kSkipInsideSlab) || !quad_->texture()) return;
    if (!quad_->faces(cam.eye)) return;
    DrawnQuad q;
    q.name = path_;
    q.corners = quad_->corners();
    q.level = rep.level;
    const ReliefTexture& t = quad_->level(rep.level);
    q.width = t.width;
    q.height = t.height;
    q.texture = quad_->texture()->id();
    q.texture_width = quad_->texture()->width();
    q.texture_height = quad_->texture()->height();
    q.warped = (s.method == RenderMethod::two_pass || s.method == RenderMethod::pipelined) &&
               !fired(kSkipSubpixelParallax);
    const PrewarpCoefficients k = compute_coefficients(t.geometry, cam.eye);
    q.epipole = {k.epipole_u, k.epipole_v};
    if (q.warped) {
        q.margins = quad_->last_stats().extent;
        if (s.side_polygons) {
            // The side polygons along each border that has a margin, spanning [min(0, dmin), max(0, dmax)] along
            // f (texmap/renderer.h, ReliefSurface); drawn clipped to what can show a texel, outlined whole here.
            const glm::dvec3 f = glm::normalize(glm::cross(t.geometry.a, t.geometry.b));
            const double lo = std::min(0.0, t.quant.min), hi = std::max(0.0, t.quant.max);
            const auto& c = q.corners;
            const int margin[4] = {q.margins.bottom, q.margins.right, q.margins.top, q.margins.left};
            for (int e = 0; e < 4; ++e) {
                if (margin[e] <= 0 || !(hi > lo)) continue;
                const glm::dvec3 p0 = c[size_t(e)], p1 = c[size_t((e + 1) % 4)];
                q.side_polygons.push_back({p0 + f * lo, p1 + f * lo, p1 + f * hi, p0 + f * hi});
            }
        }
    }
    report.quads.push_back(std::move(q));
}

ImageRGBA8 LoadedRelief::raycast(const Camera& cam, const ViewSettings& s) {
    if (s.discontinuity != discontinuity_) reload(s.discontinuity);
    RaycastOptions ro;
    ro.threads = s.threads;
    return raycast_relief(quad_->relief(), cam, ro);
}

std::unique_ptr<Loaded> open_file(const std::string& path) {
    auto ends_with = [&](const std::string& suffix) {
        return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    if (ends_with(".relief.json")) return std::make_unique<LoadedRelief>(path);
    if (ends_with(".object.json") || ends_with(".scene.json"))
        throw IoError(path + ": six-face objects and scenes cannot be viewed by this build yet (reliefs only)");
    if (ends_with(".json")) throw IoError(path + ": unknown kind of file; expected NAME.relief.json");
    throw IoError(path +
                  ": meshes are baked into objects, which this build cannot view yet; expected "
                  "NAME.relief.json");
}

}  // namespace rtm::viewer
