#include "mesh/ply_writer.h"

#include <cstring>
#include <string>

#include "formats/atomic_file.h"

namespace rtm {

namespace {

template <class T>
void put(std::string& out, T v) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));  // the machines we build for are little-endian
    out.append(bytes, sizeof(T));
}

}  // namespace

void write_ply(const std::string& path, const TriangleMesh& mesh) {
    static_assert(sizeof(float) == 4);
    const size_t triangles = mesh.indices.size() / 3;
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment rtm generated\nelement vertex " +
                      std::to_string(mesh.vertices.size()) +
                      "\nproperty float x\nproperty float y\nproperty float z\n"
                      "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face " +
                      std::to_string(triangles) + "\nproperty list uchar int vertex_indices\nend_header\n";
    out.reserve(out.size() + mesh.vertices.size() * 15 + triangles * 13);
    for (const MeshVertexAttribs& v : mesh.vertices) {
        put(out, v.position.x);
        put(out, v.position.y);
        put(out, v.position.z);
        put(out, v.color.r);
        put(out, v.color.g);
        put(out, v.color.b);
    }
    for (size_t t = 0; t < triangles; ++t) {
        put(out, uint8_t(3));
        for (int k = 0; k < 3; ++k) put(out, int32_t(mesh.indices[t * 3 + size_t(k)]));
    }
    write_text_atomically(path, out);
}

}  // namespace rtm
