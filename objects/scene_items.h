// The scene items that are not single relief quads (objects/scene.h): six-face objects and meshes, each placed by
// its item transform and sharing the scene's depth buffer.
//
// A six-face object (objects/relief_object.h) is drawn in its own frame: for a similarity M = T * R * s, drawing
// the object with the camera moved by M^-1 (eye, look-at and up transformed, near and far planes divided by s)
// gives the same clip-space positions and the same depth values as drawing the transformed object with the
// camera itself, so its corrected depth (paper section 4.2) lands in the shared depth buffer unchanged. Its truth
// is its six faces' micro-polygon meshes, drawn the same way.
// A mesh (any file assimp reads, mesh/triangle_mesh.h) is drawn conventionally by mesh/mesh_renderer with its
// vertices transformed (any T * R * S); a mesh is its own truth, so every method draws it the same.
#pragma once

#include <glm/mat4x4.hpp>

#include <memory>

#include "mesh/triangle_mesh.h"
#include "objects/bounds.h"
#include "objects/relief_object.h"

namespace rtm {

class MeshRenderer;

// The uniform scale of a similarity (rotation, translation and uniform scale > 0, no mirror); throws
// std::invalid_argument when `m` changes shapes (shear, unequal scale, a mirror).
double similarity_scale(const glm::dmat4& m);

// The camera that sees the object in its own frame as `cam` sees it placed by the similarity `world_from_object`.
Camera object_frame_camera(const Camera& cam, const glm::dmat4& world_from_object);

class PlacedObject {
public:
    // Throws std::invalid_argument when the transform is not a similarity.
    // `shared`: as ReliefObject's (shared by the placements of one object file).
    PlacedObject(SixFaceObject object, const glm::dmat4& world_from_object,
                 const ReliefObject::FaceShares& shared = {});
    Bounds bounds() const;  // world bounds of the transformed box
    ReliefObject& object() { return object_; }
    // flat, two_pass or pipelined (ReliefObject::draw), micromesh (its faces' micro-polygon meshes).
    void draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
              const DrawOptions& draw, StageTimes& times, ObjectReport* report = nullptr);

private:
    ReliefObject object_;
    glm::dmat4 world_from_object_;
};

class PlacedMesh {
public:
    PlacedMesh(TriangleMesh mesh, const glm::dmat4& world_from_mesh);  // transforms the vertices
    ~PlacedMesh();
    PlacedMesh(PlacedMesh&&) noexcept;
    const TriangleMesh& mesh() const { return mesh_; }
    Bounds bounds() const;
    // Into the renderer's frame (its pending clear issued first). The GL buffers are made at the first draw, in
    // the GL context current then.
    void draw(Renderer& renderer, const Camera& cam);

private:
    TriangleMesh mesh_;
    std::unique_ptr<MeshRenderer> gl_;
};

}  // namespace rtm
