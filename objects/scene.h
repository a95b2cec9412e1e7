// A scene: relief quads, plain polygons, six-face objects and meshes (objects/scene_items.h) in one world and one
// depth buffer (paper sections 1 and 4.4). Each relief quad is drawn by ReliefQuad::draw with its own skips
// (back-facing, outside the frustum, sub-pixel parallax, reuse of the last pre-warp, ...), so a frame costs what the
// view needs; depth correction (section 4.2) is on by default, so reliefs and polygons occlude each other where their
// perceived surfaces do.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "formats/scene_manifest.h"
#include "objects/bounds.h"
#include "objects/quad_frame.h"
#include "objects/relief_quad.h"
#include "objects/scene_items.h"
#include "texmap/renderer.h"

namespace rtm {

// A relief texture placed by a similarity transform: origin, a and b move with it, displacements scale with it.
// Throws std::invalid_argument when the transform does not keep the relief's shape (shear or unequal scale).
ReliefTexture transform_relief(ReliefTexture t, const glm::dmat4& m);
// transform_relief in its two steps: the displacements (quantizer, discontinuity threshold) scaled by s > 0, and
// the geometry moved by m, whose scale is s (similarity_scale). The scene does the first once per file and scale and
// the second per placement, so the placements of one file at one scale share its texels and pyramid.
void scale_relief_displacements(ReliefTexture& t, double s);
void place_relief_geometry(ReliefTexture& t, const glm::dmat4& m);

// The camera of a scene's key (its default camera or a frame of its path) with the image size and clip planes of
// `base`.
Camera key_camera(const SceneCameraKey& key, const Camera& base);

class Scene;
// Frame k of the scene's camera path (0 <= k < path_frames) with the image size of `base` and clip planes fitted
// to the scene's bounds, as rtm render --scene --camera-path K draws it.
Camera scene_path_camera(const Scene& scene, int k, const Camera& base);

struct ScenePolygon {
    std::vector<glm::dvec3> vertices;  // 3 or 4, convex, planar
    glm::dvec3 color{0.5};
};

// What one frame of a scene did, for --json and the benchmarks.
struct SceneFrameReport {
    int quads = 0;                      // relief quads in the scene
    int drawn = 0;                      // relief quads drawn (as relief or as a plain texture)
    int prewarped = 0;                  // relief quads pre-warped this frame
    long long texels_warped = 0;        // texels of the levels pre-warped this frame
    long long micromesh_triangles = 0;  // inside-slab-micromesh: micro-polygons drawn (the tiles in view)
    std::map<std::string, int> skips;   // skip name -> quads it fired for
    std::vector<std::vector<std::string>> quad_skips;  // per relief quad, in manifest order: the skips that fired
    int object_faces_drawn = 0;                        // faces of six-face objects drawn (objects/scene_items.h)
    // Of those, the faces pre-warped this frame (not reused, not flat), the texels their pre-warps visited (each
    // face's level and its adjacent faces', ObjectFacePrewarp::texels), and skip name -> the faces it fired for
    // (ObjectReport::skip_faces, summed over the objects).
    int object_faces_prewarped = 0;
    long long object_texels_warped = 0;
    std::map<std::string, int> object_face_skips;
    std::vector<int> quad_levels;        // per relief quad: the pyramid level drawn
    std::vector<StageTimes> quad_times;  // per relief quad: its stage times (draw_quad_frame)
    StageTimes times;                    // the frame's (draw_quad_frame's frame times, polygons too)
};

class Scene {
public:
    // Reads the manifest and every relief it names (each relief file read once, however many items share it).
    static Scene load(const std::string& manifest_path);
    explicit Scene(SceneManifest manifest);

    const SceneManifest& manifest() const { return manifest_; }
    Bounds bounds() const;
    std::vector<ReliefQuad>& quads() { return quads_; }
    const std::vector<ScenePolygon>& polygons() const { return polygons_; }
    std::vector<PlacedObject>& objects() { return objects_; }
    std::vector<PlacedMesh>& meshes() { return meshes_; }

    // One frame into the current framebuffer (begin_frame included). `method`: flat, two_pass, pipelined,
    // micromesh (every relief replaced by its micro-polygon mesh: the ground truth) or a per-pixel method (each
    // relief quad drawn by it with `perpixel`, the defaults unless given; six-face objects by two_pass). raycast is
    // refused
    // (std::invalid_argument): the ray caster traces one height field, not a scene.
    // The relief quads are drawn by draw_quad_frame (objects/quad_frame.h): plans first, the pre-warps concurrently,
    // one finish per frame; `frame` chooses serial pre-warps or a finish per quad (to measure).
    void draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
              const DrawOptions& draw, SceneFrameReport& report, const QuadFrameOptions& frame = {},
              const PerPixelSettings& perpixel = PerPixelSettings{});

private:
    // An object file as read, and what its placements share of its faces (objects/shared_relief.h; each placement
    // keeps the object in its own frame: the faces are the same, only the matrix differs).
    struct LoadedObject {
        SixFaceObject object;
        ReliefObject::FaceShares shared;
    };
    // Item i, an object or a mesh: each file read once (the maps hold what was read).
    void load_placed_item(size_t i, std::map<std::string, LoadedObject>& objects,
                          std::map<std::string, TriangleMesh>& meshes);
    // The meshes and the objects of a frame, after the polygons and before the relief quads.
    void draw_placed_items(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                           const DrawOptions& draw, SceneFrameReport& report);

    SceneManifest manifest_;
    std::vector<ReliefQuad> quads_;
    std::vector<ScenePolygon> polygons_;
    std::vector<PlacedObject> objects_;
    std::vector<PlacedMesh> meshes_;
    std::vector<MeshVertex> polygon_vertices_;
    std::vector<uint32_t> polygon_indices_;
};

}  // namespace rtm
