#include "objects/scene.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>

#include "formats/image_io.h"
#include "formats/object_manifest.h"
#include "formats/relief_manifest.h"
#include "perpixel/perpixel_quad.h"
#include "truth/micromesh.h"
#include "objects/shared_relief.h"
#include "warp/timing.h"

namespace rtm {

void scale_relief_displacements(ReliefTexture& t, double s) {
    if (s == 1.0) return;
    t.quant = Quantizer::from_range(t.quant.min * s, t.quant.max * s);
    for (float& d : t.displacement.edit()) d = float(double(d) * s);
    t.discontinuity_threshold *= s;
}

void place_relief_geometry(ReliefTexture& t, const glm::dmat4& m) {
    const glm::dmat3 l(m);
    t.geometry.origin = glm::dvec3(m * glm::dvec4(t.geometry.origin, 1.0));
    t.geometry.a = l * t.geometry.a;
    t.geometry.b = l * t.geometry.b;
}

ReliefTexture transform_relief(ReliefTexture t, const glm::dmat4& m) {
    scale_relief_displacements(t, similarity_scale(m));  // throws where m does not keep the relief's shape
    place_relief_geometry(t, m);
    return t;
}

Camera key_camera(const SceneCameraKey& key, const Camera& base) {
    Camera c = base;
    c.eye = key.eye;
    c.look_at = key.look_at;
    c.up = key.up;
    c.fov_deg = key.fov_deg;
    return c;
}

Camera scene_path_camera(const Scene& scene, int k, const Camera& base) {
    const SceneManifest& m = scene.manifest();
    Camera c = key_camera(camera_path_frame(m.path_keys, k, m.path_frames), base);
    const Bounds b = scene.bounds();
    c.fit_clip_planes(b.centre(), b.radius());
    return c;
}

Scene Scene::load(const std::string& manifest_path) { return Scene(parse_scene_manifest(manifest_path)); }

Scene::Scene(SceneManifest manifest) : manifest_(std::move(manifest)) {
    // Each relief file read once; its displacements scaled once per scale its placements use, and the placements of
    // one file at one scale share its texels, pyramid levels and spreads (each quad keeps its own geometry).
    struct Scaled {
        ReliefTexture relief;
        std::shared_ptr<SharedRelief> shared;
    };
    std::map<std::string, ReliefTexture> loaded;
    std::map<std::pair<std::string, double>, Scaled> scaled;
    std::map<std::string, LoadedObject> objects;
    std::map<std::string, TriangleMesh> meshes;
    for (size_t i = 0; i < manifest_.items.size(); ++i) {
        const SceneItem& item = manifest_.items[i];
        if (item.kind == SceneItem::Kind::polygon) {
            polygons_.push_back({item.vertices, item.color});
            continue;
        }
        if (item.kind == SceneItem::Kind::object || item.kind == SceneItem::Kind::mesh) {
            load_placed_item(i, objects, meshes);
            continue;
        }
        auto it = loaded.find(item.relief_path);
        try {  // a relief that cannot be read: the line names the scene and the item too
            if (it == loaded.end()) it = loaded.emplace(item.relief_path, load_relief(item.relief_path)).first;
        } catch (const IoError& e) {
            throw IoError(manifest_.path + ": item " + std::to_string(i) + ": " + e.what());
        }
        try {
            const glm::dmat4 m = item.transform.matrix();
            const double s = similarity_scale(m);
            auto sc = scaled.find({item.relief_path, s});
            if (sc == scaled.end()) {
                Scaled fresh{it->second, std::make_shared<SharedRelief>()};
                scale_relief_displacements(fresh.relief, s);
                sc = scaled.emplace(std::pair{item.relief_path, s}, std::move(fresh)).first;
            }
            ReliefTexture placed = sc->second.relief;
            place_relief_geometry(placed, m);
            quads_.emplace_back(std::move(placed), sc->second.shared);
        } catch (const std::invalid_argument& e) {
            throw IoError(manifest_.path + ": item " + std::to_string(i) + ": " + e.what());
        }
    }
    for (const ScenePolygon& p : polygons_) {
        const auto base = uint32_t(polygon_vertices_.size());
        const glm::u8vec4 c(glm::u8vec4(glm::round(glm::clamp(p.color, 0.0, 1.0) * 255.0), 255));
        for (const glm::dvec3& v : p.vertices) polygon_vertices_.push_back({glm::vec3(v), c});
        for (uint32_t k = 1; k + 1 < p.vertices.size(); ++k)
            polygon_indices_.insert(polygon_indices_.end(), {base, base + k, base + k + 1});
    }
}

void Scene::load_placed_item(size_t i, std::map<std::string, LoadedObject>& objects,
                             std::map<std::string, TriangleMesh>& meshes) {
    const SceneItem& item = manifest_.items[i];
    try {
        if (item.kind == SceneItem::Kind::object) {
            auto it = objects.find(item.file_path);
            if (it == objects.end()) {
                LoadedObject fresh{load_object(item.file_path), {}};
                for (auto& s : fresh.shared) s = std::make_shared<SharedRelief>();
                it = objects.emplace(item.file_path, std::move(fresh)).first;
            }
            objects_.emplace_back(it->second.object, item.transform.matrix(), it->second.shared);
        } else {
            auto it = meshes.find(item.file_path);
            if (it == meshes.end()) it = meshes.emplace(item.file_path, load_mesh(item.file_path)).first;
            for (const std::string& w : it->second.warnings) std::fprintf(stderr, "rtm: warning: %s\n", w.c_str());
            it->second.warnings.clear();  // once per file
            meshes_.emplace_back(it->second, item.transform.matrix());
        }
    } catch (const std::invalid_argument& e) {
        throw IoError(manifest_.path + ": item " + std::to_string(i) + ": " + e.what());
    } catch (const IoError& e) {  // a file that cannot be read: the line names the scene and the item too
        throw IoError(manifest_.path + ": item " + std::to_string(i) + ": " + e.what());
    }
}

void Scene::draw_placed_items(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                              const DrawOptions& draw, SceneFrameReport& report) {
    for (PlacedMesh& m : meshes_) {
        const auto tm = Clock::now();
        m.draw(renderer, cam);
        report.times.texture_map_ms += ms_since(tm);
    }
    for (PlacedObject& o : objects_) {
        StageTimes st;
        ObjectReport orep;
        const auto tm = Clock::now();
        o.draw(renderer, cam, method, options, draw, st, &orep);
        if (method == RenderMethod::micromesh) st.texture_map_ms = ms_since(tm);
        report.times.prewarp_ms += st.prewarp_ms;
        report.times.upload_ms += st.upload_ms;
        report.times.texture_map_ms += st.texture_map_ms;
        report.object_faces_drawn += method == RenderMethod::micromesh ? kFaceCount : int(orep.faces.size());
        for (const auto& [name, faces] : orep.skip_faces) report.object_face_skips[name] += faces;
        for (const ObjectFaceReport& fr : orep.faces) {
            // A face pre-warped this frame: neither reused nor drawn flat (method flat or subpixel-parallax).
            bool warped = method != RenderMethod::flat && method != RenderMethod::micromesh;
            for (const std::string& s : fr.skips) warped &= s != kSkipReuse && s != kSkipSubpixelParallax;
            if (!warped) continue;
            ++report.object_faces_prewarped;
            report.object_texels_warped += o.object().face_prewarp(fr.face).texels;
        }
    }
}

Bounds Scene::bounds() const {
    Bounds b;
    for (const PlacedObject& o : objects_) b.extend(o.bounds());
    for (const PlacedMesh& m : meshes_) b.extend(m.bounds());
    for (const ReliefQuad& q : quads_) b.extend(relief_bounds(q.relief()));
    for (const ScenePolygon& p : polygons_)
        for (const glm::dvec3& v : p.vertices) b.extend(v);
    return b;
}

void Scene::draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                 const DrawOptions& draw, SceneFrameReport& report, const QuadFrameOptions& frame,
                 const PerPixelSettings& perpixel) {
    if (method == RenderMethod::raycast)
        throw std::invalid_argument("method raycast traces one relief, not a scene: use micromesh as the truth");
    const auto t0 = Clock::now();
    report.quads = int(quads_.size());
    report.quad_skips.assign(quads_.size(), {});
    report.quad_levels.assign(quads_.size(), 0);
    renderer.begin_frame(cam);
    if (!polygon_indices_.empty()) {
        const auto tp = Clock::now();
        renderer.draw_mesh(cam, polygon_vertices_, polygon_indices_);
        report.times.texture_map_ms += ms_since(tp);
    }
    draw_placed_items(renderer, cam, method, options, draw, report);
    if (method == RenderMethod::micromesh) {
        const auto tm = Clock::now();
        for (ReliefQuad& quad : quads_) {
            const MicroMesh& mesh = quad.micromesh();
            draw_mesh(renderer, cam, mesh);
            ++report.drawn;
        }
        renderer.finish();
        report.times.texture_map_ms += ms_since(tm);
        report.times.total_ms += ms_since(t0);
        return;
    }
    if (const auto pp = perpixel_method(method)) {  // the comparison's per-pixel methods
        const auto tm = Clock::now();
        for (ReliefQuad& quad : quads_) {
            quad.perpixel().draw(renderer, cam, quad.relief(), *pp, perpixel);
            ++report.drawn;
        }
        renderer.finish();
        report.times.texture_map_ms += ms_since(tm);
        report.times.total_ms += ms_since(t0);
        return;
    }
    std::vector<DrawReport> reps;
    StageTimes ft;
    draw_quad_frame(quads_, renderer, cam, method, options, draw, frame, reps, report.quad_times, ft);
    report.times.prewarp_ms += ft.prewarp_ms;
    report.times.upload_ms += ft.upload_ms;
    report.times.texture_map_ms += ft.texture_map_ms;
    for (size_t qi = 0; qi < quads_.size(); ++qi) {
        const DrawReport& dr = reps[qi];
        report.quad_skips[qi] = dr.skips;
        report.quad_levels[qi] = dr.level;
        report.micromesh_triangles += dr.micromesh_triangles;
        bool hidden = false, not_warped = method == RenderMethod::flat;
        for (const std::string& s : dr.skips) {
            ++report.skips[s];
            if (s == kSkipBackFacing || s == kSkipOutsideFrustum) hidden = true;
            if (s == kSkipSubpixelParallax || s == kSkipReuse || s == kSkipInsideSlab) not_warped = true;
        }
        if (hidden) continue;
        ++report.drawn;
        if (!not_warped) {
            ++report.prewarped;
            const ReliefTexture& lv = quads_[qi].level(dr.level);
            report.texels_warped += (long long)lv.width * lv.height;
        }
    }
    report.times.total_ms += ms_since(t0);
}

}  // namespace rtm
