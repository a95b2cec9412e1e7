// load_mesh: assimp scene -> TriangleMesh (mesh/triangle_mesh.h).
#include "mesh/triangle_mesh.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include <unistd.h>

#include "formats/image_io.h"
#include "mesh/header_guard.h"
#include "formats/isolated_call.h"

namespace rtm {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// A texture file named by a model: as given (absolute or relative to the model's folder), with '\' read as '/',
// then by its bare file name in the model's folder, then that name case-insensitively. Empty if none exists.
std::string find_texture_file(const fs::path& model_dir, std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    if (name.rfind("file://", 0) == 0) name = name.substr(7);
    std::error_code ec;
    std::vector<fs::path> candidates;
    const fs::path p(name);
    if (p.is_absolute()) candidates.push_back(p);
    candidates.push_back(model_dir / p);
    candidates.push_back(model_dir / p.filename());
    for (const fs::path& c : candidates)
        if (fs::is_regular_file(c, ec)) return c.string();
    const std::string want = lower(p.filename().string());
    if (want.empty()) return {};
    for (fs::directory_iterator it(model_dir.empty() ? fs::path(".") : model_dir, ec), end; !ec && it != end;
         it.increment(ec))
        if (lower(it->path().filename().string()) == want && it->is_regular_file(ec)) return it->path().string();
    return {};
}

// An embedded texture: raw BGRA texels (mHeight > 0) or a compressed file held in memory (mHeight == 0), which is
// decoded by OpenImageIO through a temporary file (formats/ reads images from files only).
ImageRGBA8 decode_embedded(const aiTexture& t) {
    if (t.mHeight > 0) {
        if (uint64_t(t.mWidth) * t.mHeight > uint64_t(kMaxImagePixels))
            throw IoError("embedded texture of " + std::to_string(t.mWidth) + "x" + std::to_string(t.mHeight) +
                          " texels is too large");
        ImageRGBA8 img(int(t.mWidth), int(t.mHeight));
        for (size_t i = 0; i < img.pixels.size(); ++i) {
            const aiTexel& s = t.pcData[i];
            img.pixels[i] = Rgba8{s.r, s.g, s.b, s.a};
        }
        return img;
    }
    std::string hint(t.achFormatHint, strnlen(t.achFormatHint, sizeof(t.achFormatHint)));
    hint.erase(std::remove_if(hint.begin(), hint.end(), [](char c) { return !std::isalnum((unsigned char)c); }),
               hint.end());
    if (hint.empty()) hint = "png";
    const fs::path tmp = fs::temp_directory_path() / ("rtm_embedded_" + std::to_string(::getpid()) + "_" +
                                                      std::to_string(reinterpret_cast<uintptr_t>(&t)) + "." + hint);
    struct Remove {
        fs::path p;
        ~Remove() {
            std::error_code ec;
            fs::remove(p, ec);
        }
    } remove{tmp};
    {
        std::ofstream f(tmp, std::ios::binary);
        f.write(reinterpret_cast<const char*>(t.pcData), std::streamsize(t.mWidth));
        if (!f) throw IoError("embedded texture: cannot write a temporary file in " + tmp.parent_path().string());
    }
    return read_rgba8(tmp.string());
}

std::string material_label(const aiMaterial& m, unsigned index) {
    aiString name;
    std::string label;
    if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0) {
        label += '"';
        label += name.C_Str();
        label += '"';
    } else {
        label += '#';
        label += std::to_string(index);
    }
    return label;
}

MeshMaterial load_material(const std::string& path, const aiScene& scene, unsigned index,
                           std::vector<std::string>& warnings) {
    const aiMaterial& m = *scene.mMaterials[index];
    MeshMaterial out;
    out.name = material_label(m, index);
    aiColor4D c(1, 1, 1, 1);
    const bool has_base = m.Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS;
    aiColor4D diffuse(1, 1, 1, 1);
    const bool has_diffuse = m.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS;
    aiString tex;
    bool has_tex = m.GetTexture(aiTextureType_DIFFUSE, 0, &tex) == AI_SUCCESS ||
                   m.GetTexture(aiTextureType_BASE_COLOR, 0, &tex) == AI_SUCCESS;
    if (has_tex && tex.length == 0) has_tex = false;
    auto clamp01 = [](float x) { return std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : 1.0f; };
    // Alpha is coverage and comes from textures only: a material's opacity does not hide it.
    const aiColor4D colour = has_base ? c : (has_diffuse && !has_tex) ? diffuse : aiColor4D(1, 1, 1, 1);
    out.base_color = glm::vec4(clamp01(colour.r), clamp01(colour.g), clamp01(colour.b), 1.0f);
    if (!has_tex) return out;
    const std::string tex_name = tex.C_Str();
    std::string why;
    try {
        if (const aiTexture* embedded = scene.GetEmbeddedTexture(tex.C_Str())) {
            out.texture = decode_embedded(*embedded);
        } else if (!tex_name.empty() && tex_name[0] == '*') {
            why = "names embedded texture " + tex_name + ", which the file does not hold";
        } else {
            const std::string file = find_texture_file(fs::path(path).parent_path(), tex_name);
            if (file.empty())
                why = "texture \"" + tex_name + "\" not found";
            else
                out.texture = read_rgba8(file);
        }
    } catch (const IoError& e) {
        why = "texture \"" + tex_name + "\" cannot be read (" + e.what() + ")";
    }
    if (!why.empty()) {
        warnings.push_back(path + ": material " + out.name + ": " + why + "; using the material colour");
        // The diffuse colour stands in for the texture it would have been multiplied with.
        if (!has_base && has_diffuse)
            out.base_color = glm::vec4(clamp01(diffuse.r), clamp01(diffuse.g), clamp01(diffuse.b), 1.0f);
    }
    return out;
}

struct Builder {
    const std::string& path;
    const aiScene& scene;
    TriangleMesh& mesh;
    bool warned_no_uv = false;

    void add_mesh(const aiMesh& src, const aiMatrix4x4& transform) {
        if (!(src.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || src.mNumVertices == 0) return;
        const unsigned mat = std::min(src.mMaterialIndex, scene.mNumMaterials ? scene.mNumMaterials - 1 : 0u);
        MeshPart part;
        part.first_index = uint32_t(mesh.indices.size());
        part.material = int(mat);
        const bool textured = mat < mesh.materials.size() && !mesh.materials[mat].texture.empty();
        const bool has_uv = src.HasTextureCoords(0);
        part.use_texture = textured && has_uv;
        part.use_vertex_color = src.HasVertexColors(0);
        if (textured && !has_uv && !warned_no_uv) {
            warned_no_uv = true;
            mesh.warnings.push_back(path + ": mesh \"" + std::string(src.mName.C_Str()) + "\" has a texture but no " +
                                    "texture coordinates; using the material colour");
        }
        const uint32_t base = uint32_t(mesh.vertices.size());
        for (unsigned i = 0; i < src.mNumVertices; ++i) {
            const aiVector3D p = transform * src.mVertices[i];
            MeshVertexAttribs v;
            v.position = glm::vec3(p.x, p.y, p.z);
            if (has_uv) v.uv = glm::vec2(src.mTextureCoords[0][i].x, src.mTextureCoords[0][i].y);
            if (part.use_vertex_color) {
                const aiColor4D& c = src.mColors[0][i];
                auto byte = [](float x) {
                    return uint8_t(std::lround(std::isfinite(x) ? std::clamp(x, 0.f, 1.f) * 255.f : 255.f));
                };
                v.color = glm::u8vec4(byte(c.r), byte(c.g), byte(c.b), 255);
            }
            mesh.vertices.push_back(v);
        }
        for (unsigned f = 0; f < src.mNumFaces; ++f) {
            const aiFace& face = src.mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines left by the importer
            bool ok = true;
            for (int k = 0; k < 3; ++k) ok = ok && face.mIndices[k] < src.mNumVertices;
            if (!ok) continue;
            for (int k = 0; k < 3; ++k) mesh.indices.push_back(base + face.mIndices[k]);
        }
        part.index_count = uint32_t(mesh.indices.size()) - part.first_index;
        if (part.index_count > 0) mesh.parts.push_back(part);
    }

    void add_node(const aiNode& node, const aiMatrix4x4& parent, int depth) {
        if (depth > 1000) throw_io_error(path, "node hierarchy deeper than 1000 levels");
        const aiMatrix4x4 t = parent * node.mTransformation;
        for (unsigned i = 0; i < node.mNumMeshes; ++i)
            if (node.mMeshes[i] < scene.mNumMeshes) add_mesh(*scene.mMeshes[node.mMeshes[i]], t);
        for (unsigned i = 0; i < node.mNumChildren; ++i) add_node(*node.mChildren[i], t, depth + 1);
    }
};

}  // namespace

std::string TriangleMesh::to_string() const {
    std::ostringstream os;
    os << "TriangleMesh{" << vertices.size() << " vertices, " << triangle_count() << " triangles, " << parts.size()
       << " parts, " << materials.size() << " materials, bounds [" << lo.x << "," << lo.y << "," << lo.z << "] .. ["
       << hi.x << "," << hi.y << "," << hi.z << "]}";
    return os.str();
}

namespace {

// The mesh read by assimp in this process (load_mesh runs it in a child).
TriangleMesh read_mesh(const std::string& path) {
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure |
                           aiProcess_JoinIdenticalVertices;
    const aiScene* scene = importer.ReadFile(path, flags);
    if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
        std::string why = importer.GetErrorString();
        if (why.empty()) why = "no scene";
        if (why == "std::bad_alloc") throw std::bad_alloc();  // caught by assimp: out of the child's memory (load_mesh)
        throw_io_error(path, "cannot read mesh: " + why);
    }
    TriangleMesh mesh;
    for (unsigned i = 0; i < scene->mNumMaterials; ++i)
        mesh.materials.push_back(load_material(path, *scene, i, mesh.warnings));
    if (mesh.materials.empty()) mesh.materials.push_back(MeshMaterial{"default", glm::vec4(1.0f), {}});
    Builder b{path, *scene, mesh};
    b.add_node(*scene->mRootNode, aiMatrix4x4(), 0);
    if (mesh.indices.empty()) throw_io_error(path, "mesh has no triangles");

    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (uint32_t idx : mesh.indices) {
        const glm::vec3& p = mesh.vertices[idx].position;
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw_io_error(path, "vertex " + std::to_string(idx) + " has a non-finite position");
        lo = glm::min(lo, glm::dvec3(p));
        hi = glm::max(hi, glm::dvec3(p));
    }
    constexpr double kMaxCoordinate = 1e30;  // as for cameras: past this single precision has no room left
    for (int k = 0; k < 3; ++k)
        if (std::abs(lo[k]) > kMaxCoordinate || std::abs(hi[k]) > kMaxCoordinate)
            throw_io_error(path, "vertex coordinates beyond +-1e30");
    mesh.lo = lo;
    mesh.hi = hi;
    return mesh;
}

// The mesh as bytes from the child (run_isolated), and back: trivially copyable parts as they lie in memory (the same
// program on both ends), strings and arrays after their length.
class Encoder {
public:
    template <class T>
    void pod(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        out_.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    template <class T>
    void array(const std::vector<T>& v) {
        pod(uint64_t(v.size()));
        out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
    void text(const std::string& v) {
        pod(uint64_t(v.size()));
        out_.append(v);
    }
    std::string take() { return std::move(out_); }

private:
    std::string out_;
};

class Decoder {
public:
    explicit Decoder(std::string_view in) : in_(in) {}
    template <class T>
    void pod(T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        std::memcpy(&v, take(sizeof v), sizeof v);
    }
    template <class T>
    void array(std::vector<T>& v) {
        const uint64_t n = count(sizeof(T));
        v.resize(size_t(n));
        if (n) std::memcpy(v.data(), take(size_t(n) * sizeof(T)), size_t(n) * sizeof(T));
    }
    void text(std::string& v) {
        const uint64_t n = count(1);
        v.assign(take(size_t(n)), size_t(n));
    }
    uint64_t count(size_t item) {
        uint64_t n = 0;
        pod(n);
        if (n > (in_.size() - at_) / item) throw std::runtime_error("truncated");
        return n;
    }
    bool done() const { return at_ == in_.size(); }

private:
    const char* take(size_t n) {
        if (n > in_.size() - at_) throw std::runtime_error("truncated");
        const char* p = in_.data() + at_;
        at_ += n;
        return p;
    }
    std::string_view in_;
    size_t at_ = 0;
};

std::string encode(const TriangleMesh& m) {
    Encoder e;
    e.array(m.vertices);
    e.array(m.indices);
    e.array(m.parts);
    e.pod(uint64_t(m.materials.size()));
    for (const MeshMaterial& mat : m.materials) {
        e.text(mat.name);
        e.pod(mat.base_color);
        e.pod(mat.texture.width);
        e.pod(mat.texture.height);
        e.array(mat.texture.pixels);
    }
    e.pod(m.lo);
    e.pod(m.hi);
    e.pod(uint64_t(m.warnings.size()));
    for (const std::string& w : m.warnings) e.text(w);
    return e.take();
}

TriangleMesh decode(std::string_view bytes) {
    Decoder d(bytes);
    TriangleMesh m;
    d.array(m.vertices);
    d.array(m.indices);
    d.array(m.parts);
    m.materials.resize(size_t(d.count(1)));
    for (MeshMaterial& mat : m.materials) {
        d.text(mat.name);
        d.pod(mat.base_color);
        d.pod(mat.texture.width);
        d.pod(mat.texture.height);
        d.array(mat.texture.pixels);
        if (mat.texture.pixels.size() !=
            size_t(std::max(mat.texture.width, 0)) * size_t(std::max(mat.texture.height, 0)))
            throw std::runtime_error("texture size");
    }
    d.pod(m.lo);
    d.pod(m.hi);
    m.warnings.resize(size_t(d.count(1)));
    for (std::string& w : m.warnings) d.text(w);
    if (!d.done()) throw std::runtime_error("trailing bytes");
    return m;
}

}  // namespace

TriangleMesh load_mesh(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw_io_error(path, "cannot read mesh: no such file");
    if (fs::is_directory(path, ec)) throw_io_error(path, "cannot read mesh: it is a folder");
    if (!fs::is_regular_file(path, ec))
        throw_io_error(path,
                       "cannot read mesh: not a regular file (a FIFO or a device: reading it could wait forever)");
    const std::uintmax_t bytes = fs::file_size(path, ec);
    if (ec) throw_io_error(path, "cannot read mesh: " + ec.message());
    if (const std::string why = check_declared_counts(path, bytes); !why.empty())
        throw_io_error(path, "cannot read mesh: " + why);
    constexpr IsolatedReader kReader{"cannot read mesh", "the mesh reader (assimp)", "RTM_MESH_READER_MB",
                                     "RTM_MESH_READER_SECONDS"};
    const IsolatedOutcome r = read_isolated(path, bytes, kReader, [&](const ResultWriter& out) {
        const std::string encoded = encode(read_mesh(path));
        out.write(encoded.data(), encoded.size());
    });
    try {
        return decode(r.bytes);
    } catch (const std::exception& e) {
        throw_io_error(path, std::string("cannot read mesh: its reader's result is damaged (") + e.what() + ")");
    }
}

}  // namespace rtm
