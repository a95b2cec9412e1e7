#include "viewer/loaded_object.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "formats/image_io.h"
#include "formats/object_manifest.h"
#include "viewer/bake_mesh.h"
#include "viewer/drawn_quad.h"
#include "viewer/loaded_relief.h"
#include "warp/timing.h"

namespace rtm::viewer {

std::unique_ptr<LoadedObject> LoadedObject::from_manifest(const std::string& manifest) {
    std::unique_ptr<LoadedObject> o(new LoadedObject);
    o->path_ = manifest;
    o->source_ = load_object(manifest);
    o->rebuild(-1);
    o->bounds_ = o->object_->bounds();
    return o;
}

std::unique_ptr<LoadedObject> LoadedObject::from_mesh(const std::string& mesh, int bake_size) {
    std::unique_ptr<LoadedObject> o(new LoadedObject);
    o->path_ = mesh;
    o->bake_size_ = bake_size;
    o->mesh_ = load_mesh(mesh);
    for (const std::string& w : o->mesh_->warnings) std::fprintf(stderr, "rtm: warning: %s\n", w.c_str());
    o->bounds_ = mesh_bake_bounds(*o->mesh_, bake_size, mesh);
    return o;
}

void LoadedObject::prepare(const std::function<void(const std::string&)>& progress) {
    if (!mesh_) return;
    // The bake as rtm bake writes it, read back as rtm render --object reads it (the same quantization), through a
    // private folder removed afterwards. The bake needs a GL context: the window's, current here.
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path dir = fs::temp_directory_path(ec) / ("rtm-view-bake-" + std::to_string(getpid()));
    fs::create_directories(dir, ec);
    if (ec) throw IoError(path_ + ": cannot bake: cannot create " + dir.string() + ": " + ec.message());
    try {
        const std::string manifest = bake_mesh_into(*mesh_, bake_size_, path_, dir.string(), [&](int done, int total) {
            if (progress)
                progress("baking " + path_ + ": " + std::to_string(done) + " of " + std::to_string(total) + " faces");
        });
        source_ = load_object(manifest);
    } catch (...) {
        fs::remove_all(dir, ec);
        throw;
    }
    fs::remove_all(dir, ec);
    mesh_.reset();
    rebuild(-1);
}

void LoadedObject::rebuild(double discontinuity) {
    SixFaceObject o = source_;
    if (discontinuity >= 0)
        for (ReliefTexture& t : o.faces) mark_discontinuities(t, discontinuity);
    object_ = std::make_unique<ReliefObject>(std::move(o));
    discontinuity_ = discontinuity;
}

void LoadedObject::draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) {
    if (!object_) {
        report.note = path_ + ": not baked yet";
        return;
    }
    if (s.discontinuity != discontinuity_) rebuild(s.discontinuity);
    const auto t0 = Clock::now();
    if (s.method == RenderMethod::micromesh) {
        object_->draw_micromesh(renderer, cam);
        report.times.texture_map_ms += ms_since(t0);
        report.times.total_ms += ms_since(t0);
        return;
    }
    if (s.method != RenderMethod::flat && s.method != RenderMethod::two_pass && s.method != RenderMethod::pipelined) {
        report.note = to_string(s.method) + " draws single reliefs; objects: flat, two-pass, pipelined, micromesh";
        return;
    }
    const RenderSettings rs = render_settings(s);
    StageTimes st;
    ObjectReport rep;
    object_->draw(renderer, cam, s.method, rs.prewarp, st, rs.draw, &rep);
    report.times.prewarp_ms += st.prewarp_ms;
    report.times.upload_ms += st.upload_ms;
    report.times.texture_map_ms += st.texture_map_ms;
    report.times.total_ms += st.total_ms;
    for (const std::string& k : rep.skips)
        if (std::find(report.skips.begin(), report.skips.end(), k) == report.skips.end()) report.skips.push_back(k);
    if (!rep.faces.empty()) report.level = rep.faces.front().level;
    for (const ObjectFaceReport& fr : rep.faces) {
        const GlTexture* tex = object_->face_texture(fr.face);
        if (!tex) continue;
        const bool warped = maps_prewarp(s.method, fr.skips);
        // No margins, no side polygons: an object needs none.
        DrawnQuad q = fill_drawn_quad(object_->face(fr.face), kFaceKeys[size_t(fr.face)], cam, fr.level, *tex, warped);
        // Texels pre-warped this frame: none for a reused pre-warp (the reuse skip), as for a relief.
        const bool reused = std::find(fr.skips.begin(), fr.skips.end(), kSkipReuse) != fr.skips.end();
        if (warped && !reused) report.texels_warped += object_->face_prewarp(fr.face).texels;
        report.quads.push_back(std::move(q));
    }
}

std::string LoadedObject::raycast_unavailable() const {
    return "no ray caster for a six-face object: its truth is micromesh (4)";
}

ImageRGBA8 LoadedObject::raycast(const Camera&, const ViewSettings&) {
    throw std::logic_error("LoadedObject::raycast: " + raycast_unavailable());
}

}  // namespace rtm::viewer
