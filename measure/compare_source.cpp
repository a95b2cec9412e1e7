#include "measure/compare_source.h"

#include "formats/object_manifest.h"
#include "formats/relief_manifest.h"
#include "objects/relief_object.h"
#include "objects/render_relief.h"
#include "objects/scene.h"
#include "warp/timing.h"
#include "warp/upsample.h"

#include <map>
#include <utility>
#include <stdexcept>
#include <vector>

#include "measure/curved_raycast.h"
#include "perpixel/curved_patch.h"

namespace rtm {

namespace {

bool is_textured(const CompareEntry& e) {
    const RenderMethod m = e.render.method;
    return !e.curved() && e.output_scale == 1 &&
           (m == RenderMethod::flat || m == RenderMethod::two_pass || m == RenderMethod::pipelined ||
            m == RenderMethod::micromesh);
}

class ReliefSource final : public CompareSource {
public:
    explicit ReliefSource(ReliefQuad quad) : quad_(std::move(quad)) {}
    Bounds bounds() const override { return relief_bounds(quad_.relief()); }
    bool renders(const CompareEntry&) const override { return true; }
    ImageRGBA8 render(Renderer& renderer, const Camera& cam, const RenderSettings& s, int output_scale,
                      StageTimes& times) override {
        if (output_scale == 1) return render_relief_frame(quad_, &renderer, cam, s, times);
        auto it = scaled_.find(output_scale);
        if (it == scaled_.end())
            it = scaled_.emplace(output_scale, ReliefQuad(upsample(quad_.relief(), output_scale))).first;
        return render_relief_frame(it->second, &renderer, cam, s, times);
    }
    ImageRGBA8 render_curved_truth(Renderer& renderer, const Camera& cam, RenderMethod method, CurvedShape shape,
                                   double angle, int threads, StageTimes& times) override {
        if (method == RenderMethod::raycast) {
            const auto t0 = Clock::now();
            ImageRGBA8 img = raycast_curved_relief(quad_.relief(), curved_patch_for(quad_.relief(), shape, angle), cam,
                                                   threads);
            times.total_ms += ms_since(t0);
            return img;
        }
        CurvedMesh& m = curved_[{shape, angle}];
        if (m.vertices.empty()) {
            m.origin = quad_.relief().geometry.origin;  // positions relative to it: far from 0 they keep their digits
            curved_micromesh(quad_.relief(), curved_patch_for(quad_.relief(), shape, angle), m.vertices, m.indices,
                             m.origin);
        }
        const auto t0 = Clock::now();
        renderer.begin_frame(cam);
        renderer.draw_mesh(cam, m.vertices, m.indices, m.origin);
        renderer.finish();
        times.texture_map_ms += ms_since(t0);
        times.total_ms += ms_since(t0);
        return renderer.read_pixels(cam.width, cam.height);
    }
    ReliefQuad* relief() override { return &quad_; }

private:
    struct CurvedMesh {
        std::vector<MeshVertex> vertices;
        std::vector<uint32_t> indices;
        glm::dvec3 origin{0.0};
    };
    ReliefQuad quad_;
    std::map<int, ReliefQuad> scaled_;  // the relief at each output scale asked for, built once
    // The curved micro-polygon mesh of each patch and bend asked for, built once.
    std::map<std::pair<CurvedShape, double>, CurvedMesh> curved_;
};

class ObjectSource final : public CompareSource {
public:
    explicit ObjectSource(SixFaceObject o) : object_(std::move(o)) {}
    Bounds bounds() const override { return object_.bounds(); }
    bool renders(const CompareEntry& e) const override { return is_textured(e); }
    ImageRGBA8 render(Renderer& renderer, const Camera& cam, const RenderSettings& s, int, StageTimes& times) override {
        return render_object_frame(object_, renderer, cam, s.method, s.prewarp, s.draw, times);
    }
    ReliefObject& object() { return object_; }

private:
    ReliefObject object_;
};

class SceneSource final : public CompareSource {
public:
    explicit SceneSource(Scene s) : scene_(std::move(s)) {}
    Bounds bounds() const override { return scene_.bounds(); }
    bool renders(const CompareEntry& e) const override { return is_textured(e); }
    ImageRGBA8 render(Renderer& renderer, const Camera& cam, const RenderSettings& s, int, StageTimes& times) override {
        DrawOptions draw = s.draw;
        draw.depth_correction = true;  // as rtm render --scene: reliefs and polygons occlude each other
        SceneFrameReport rep;
        scene_.draw(renderer, cam, s.method, s.prewarp, draw, rep);
        times.prewarp_ms += rep.times.prewarp_ms;
        times.upload_ms += rep.times.upload_ms;
        times.texture_map_ms += rep.times.texture_map_ms;
        times.total_ms += rep.times.total_ms;
        return renderer.read_pixels(cam.width, cam.height);
    }

private:
    Scene scene_;
};

}  // namespace

ImageRGBA8 CompareSource::render_curved_truth(Renderer&, const Camera&, RenderMethod, CurvedShape, double, int,
                                              StageTimes&) {
    throw std::logic_error(name + ": only a relief renders the curved base");
}

std::unique_ptr<CompareSource> load_relief_source(const std::string& path) {
    ReliefManifest m;
    auto s = std::make_unique<ReliefSource>(ReliefQuad(load_relief(path, &m)));
    s->name = m.name;
    s->kind = "relief";
    s->path = path;
    s->width = s->relief()->relief().width;
    s->height = s->relief()->relief().height;
    return s;
}

std::unique_ptr<CompareSource> load_object_source(const std::string& path) {
    SixFaceObject o = load_object(path);
    const int w = o.faces[0].width, h = o.faces[0].height;
    auto s = std::make_unique<ObjectSource>(std::move(o));
    s->name = s->object().name();
    s->kind = "object";
    s->path = path;
    s->width = w;
    s->height = h;
    return s;
}

std::unique_ptr<CompareSource> load_scene_source(const std::string& path) {
    Scene scene = Scene::load(path);
    const std::string name = scene.manifest().name;
    int w = 0, h = 0;
    if (!scene.quads().empty()) {
        w = scene.quads()[0].relief().width;
        h = scene.quads()[0].relief().height;
    }
    auto s = std::make_unique<SceneSource>(std::move(scene));
    s->name = name;
    s->kind = "scene";
    s->path = path;
    s->width = w;
    s->height = h;
    return s;
}

}  // namespace rtm
