#include "viewer/bake_mesh.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "formats/image_io.h"
#include "mesh/bake_object.h"

namespace rtm::viewer {

Bounds mesh_bake_bounds(const TriangleMesh& mesh, int n, const std::string& path) {
    try {
        const BakeBox box = bake_box(mesh.lo, mesh.hi, n, nullptr);
        return Bounds{box.lo, box.hi};
    } catch (const std::invalid_argument& e) {
        throw IoError(path + ": cannot bake: " + e.what());
    }
}

std::string bake_mesh_into(const TriangleMesh& mesh, int n, const std::string& path, const std::string& dir,
                           const std::function<void(int, int)>& progress) {
    const BakedObject baked = bake_object(mesh, n, progress);
    for (const std::string& w : baked.warnings) std::fprintf(stderr, "rtm: warning: %s: %s\n", path.c_str(), w.c_str());
    const std::filesystem::path p(path);
    return write_object(dir, p.stem().string(), baked, p.filename().string());
}

}  // namespace rtm::viewer
