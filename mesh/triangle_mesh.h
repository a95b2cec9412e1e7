// A flat triangle mesh read from any file assimp reads (OBJ, glTF 1 and 2, Collada, PLY, FBX, 3DS, ...), ready to
// draw with unlit colour: world positions (every node transform applied), texture coordinates, vertex colours,
// and per part a material with a base colour and an optional texture.
//
// Colour of a surface point (what rtm render --mesh shows and rtm bake records):
//   texture(uv) * base_color * vertex_color, the texture only where the part has UVs, the vertex colour only where
//   the part has vertex colours. base_color is the material's diffuse (or glTF base colour factor); a part with
//   vertex colours and no texture uses them alone (assimp gives such files a grey default material). Alpha is
//   coverage: points whose alpha is below one half are not drawn.
// Texture coordinates follow OpenGL: (0, 0) is the bottom left of the picture, (0, 1) its top left.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "warp/image.h"

namespace rtm {

struct MeshVertexAttribs {
    glm::vec3 position{0.0f};
    glm::vec2 uv{0.0f};                     // OpenGL convention (see above)
    glm::u8vec4 color{255, 255, 255, 255};  // vertex colour, white when the file has none
};

struct MeshMaterial {
    std::string name;
    glm::vec4 base_color{1.0f};  // linear 0..1, multiplies the texture
    ImageRGBA8 texture;          // empty: none (or it could not be read; see TriangleMesh::warnings)
};

// A run of triangles sharing one material.
struct MeshPart {
    uint32_t first_index = 0;  // into TriangleMesh::indices
    uint32_t index_count = 0;  // 3 per triangle
    int material = 0;          // into TriangleMesh::materials
    bool use_texture = false;  // the material has a texture and the part has UVs
    bool use_vertex_color = false;
};

struct TriangleMesh {
    std::vector<MeshVertexAttribs> vertices;
    std::vector<uint32_t> indices;
    std::vector<MeshPart> parts;
    std::vector<MeshMaterial> materials;
    glm::dvec3 lo{0.0}, hi{0.0};        // axis-aligned bounds of the vertices that triangles use
    std::vector<std::string> warnings;  // one line each: what was substituted and why (missing texture, no UVs)

    size_t triangle_count() const { return indices.size() / 3; }
    std::string to_string() const;
};

// Reads `path` with assimp. Throws rtm::IoError (formats/image_io.h) with one line naming the file when it cannot
// be read, holds no triangles, or has a non-finite position. Textures are looked up embedded first, then as files
// relative to the model (also by their bare file name, and case-insensitively); one that cannot be found or read
// leaves the material's colour and adds a warning.
TriangleMesh load_mesh(const std::string& path);

}  // namespace rtm
