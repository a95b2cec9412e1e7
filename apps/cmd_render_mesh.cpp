// rtm render --mesh FILE CAMERA: conventional OpenGL rendering of any mesh assimp reads (mesh/), unlit colour as
// in the bake, with the camera conventions of every render (--orbit around the mesh's bounds). The ground truth
// for baked objects.
#include "render_mesh.h"

#include <cstdio>
#include <memory>

#include "formats/image_io.h"
#include "mesh/mesh_renderer.h"
#include "mesh/triangle_mesh.h"
#include "objects/bounds.h"
#include "texmap/gl_context.h"
#include "warp/timing.h"

namespace rtm::cli {

void run_render_mesh(const std::string& mesh_path, const CameraArgs& camera, const std::string& out,
                     const std::string& json, int repeat) {
    if (!camera.has_eye()) throw UsageError("render needs --eye X,Y,Z or --orbit AZ,EL,D");
    (void)camera.resolve(Bounds{glm::dvec3(-1), glm::dvec3(1)});  // the camera's syntax, before any file is read
    if (out.empty() && json.empty()) throw UsageError("render --mesh needs --out or --json");
    if (!out.empty()) check_output_file(out, "--out");
    if (!json.empty()) check_output_file(json, "--json");

    const TriangleMesh mesh = load_mesh(mesh_path);
    for (const std::string& w : mesh.warnings) std::fprintf(stderr, "rtm: warning: %s\n", w.c_str());
    const Camera cam = camera.resolve(Bounds{mesh.lo, mesh.hi});
    auto ctx = GlContext::create_offscreen(cam.width, cam.height);
    const auto t0 = Clock::now();
    MeshRenderer renderer(mesh);
    const double up = ms_since(t0);
    ImageRGBA8 image;
    // Each timed frame's stages, as render --relief reports them: the upload is the first frame's, before the
    // warm-up's when there is one (then no timed frame uploads).
    std::vector<double> ups, draws, totals;
    const int warm = repeat > 1 ? 1 : 0;
    for (int i = 0; i < repeat + warm; ++i) {
        const auto t1 = Clock::now();
        image = renderer.render(cam);
        if (i < warm) continue;
        ups.push_back(i == 0 ? up : 0.0);
        draws.push_back(ms_since(t1));
        totals.push_back(ups.back() + draws.back());
    }
    if (!out.empty()) write_rgba8(out, image);
    if (!json.empty()) {
        write_json(json, {{"command", "render"},
                          {"mesh", mesh_path},
                          {"method", "mesh"},
                          {"triangles", mesh.triangle_count()},
                          {"prewarp_ms", timing_json(std::vector<double>(draws.size(), 0.0))},
                          {"upload_ms", timing_json(ups)},
                          {"texture_map_ms", timing_json(draws)},
                          {"total_ms", timing_json(totals)},
                          {"texels", 0},
                          {"level", 0},
                          {"skips", nlohmann::json::array()},
                          {"bounds",
                           {{"min", {mesh.lo.x, mesh.lo.y, mesh.lo.z}}, {"max", {mesh.hi.x, mesh.hi.y, mesh.hi.z}}}},
                          {"eye", {cam.eye.x, cam.eye.y, cam.eye.z}},
                          {"size", {cam.width, cam.height}}});
    }
}

}  // namespace rtm::cli
