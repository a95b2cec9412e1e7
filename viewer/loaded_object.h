// A six-face object loaded in the viewer (NAME.object.json, docs/OBJECTS.md), or a mesh file (any format assimp
// reads) baked on the fly into one, as `rtm bake --mesh FILE` would (mesh/bake_object.h). The mesh is read when
// opened; the bake needs GL, so it runs in prepare(), in the window's context, with progress.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "mesh/triangle_mesh.h"
#include "objects/relief_object.h"
#include "viewer/loaded.h"

namespace rtm::viewer {

class LoadedObject : public Loaded {
public:
    // NAME.object.json; throws IoError naming the file.
    static std::unique_ptr<LoadedObject> from_manifest(const std::string& manifest);
    // A mesh, baked at `bake_size` texels along its box's longest side (rtm bake's default) when prepared; throws
    // IoError naming the file when it cannot be read or baked.
    static std::unique_ptr<LoadedObject> from_mesh(const std::string& mesh, int bake_size = 256);

    std::string name() const override { return path_; }
    std::string kind() const override { return mesh_ ? "mesh" : "object"; }
    Bounds bounds() const override { return bounds_; }
    void prepare(const std::function<void(const std::string&)>& progress) override;
    void draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) override;
    std::string raycast_unavailable() const override;
    ImageRGBA8 raycast(const Camera& cam, const ViewSettings& s) override;

private:
    LoadedObject() = default;
    std::string path_;
    std::optional<TriangleMesh> mesh_;  // a mesh not baked yet
    int bake_size_ = 256;
    Bounds bounds_;
    SixFaceObject source_;       // as read (or baked): discontinuities re-marked from it
    double discontinuity_ = -1;  // the threshold object_ was made with (-1: the manifest's own)
    std::unique_ptr<ReliefObject> object_;
    void rebuild(double discontinuity);
};

}  // namespace rtm::viewer
