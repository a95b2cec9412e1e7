// bake_box, face_geometry, bake_object, write_object (mesh/bake_object.h).
#include "mesh/bake_object.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "formats/image_io.h"
#include "mesh/mesh_renderer.h"

namespace rtm {
namespace {

namespace fs = std::filesystem;

struct FaceSpec {
    const char* key;
    const char* file_tag;
    int normal_axis;
    double normal_sign;
    int a_axis;
    double a_sign;
    int b_axis;
    double b_sign;
    std::array<int, 3> origin_at_hi;  // per axis: 1 = hi, 0 = lo
};

// The table of mesh/bake_object.h, in kFaceKeys order.
constexpr std::array<FaceSpec, 6> kFaces = {{
    {"+x", "px", 0, +1, 2, -1, 1, +1, {1, 0, 1}},
    {"-x", "nx", 0, -1, 2, +1, 1, +1, {0, 0, 0}},
    {"+y", "py", 1, +1, 0, +1, 2, -1, {0, 1, 1}},
    {"-y", "ny", 1, -1, 0, +1, 2, +1, {0, 0, 0}},
    {"+z", "pz", 2, +1, 0, +1, 1, +1, {0, 0, 1}},
    {"-z", "nz", 2, -1, 0, -1, 1, +1, {1, 0, 0}},
}};

const FaceSpec& spec_of(const std::string& key) {
    for (const FaceSpec& s : kFaces)
        if (key == s.key) return s;
    throw std::invalid_argument("unknown box face \"" + key + "\"; known: +x, -x, +y, -y, +z, -z");
}

glm::dvec3 axis(int k, double sign) {
    glm::dvec3 v(0.0);
    v[k] = sign;
    return v;
}

std::string fmt(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

}  // namespace

BakeBox bake_box(const glm::dvec3& lo, const glm::dvec3& hi, int n, std::vector<std::string>* warnings) {
    if (n < 1 || n > 16384) throw std::invalid_argument("--size: expected N in 1..16384, found " + std::to_string(n));
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]) || lo[k] > hi[k])
            throw std::invalid_argument("the mesh bounds are not finite or empty");
    BakeBox box;
    box.lo = lo;
    box.hi = hi;
    const glm::dvec3 e = hi - lo;
    const double longest = std::max({e.x, e.y, e.z});
    if (!(longest > 0.0)) throw std::invalid_argument("all vertices lie at one point: the bounding box has no size");
    const double s = longest / n;
    static const char* names = "xyz";
    for (int k = 0; k < 3; ++k) {
        if (e[k] < s) {
            const double c = 0.5 * (lo[k] + hi[k]);
            box.lo[k] = c - 0.5 * s;
            box.hi[k] = c + 0.5 * s;
            box.texels[size_t(k)] = 1;
            if (warnings)
                warnings->push_back(std::string("the mesh is flat along ") + names[k] + " (extent " + fmt(e[k]) +
                                    "); the box is thickened to one texel, " + fmt(s));
        } else {
            box.texels[size_t(k)] = std::max(1, int(std::lround(e[k] / s)));
        }
    }
    return box;
}

ReliefGeometry face_geometry(const BakeBox& box, const std::string& key, int* width, int* height) {
    const FaceSpec& s = spec_of(key);
    const glm::dvec3 e = box.extent();
    ReliefGeometry g;
    for (int k = 0; k < 3; ++k) g.origin[k] = s.origin_at_hi[size_t(k)] ? box.hi[k] : box.lo[k];
    const int w = box.texels[size_t(s.a_axis)], h = box.texels[size_t(s.b_axis)];
    g.a = axis(s.a_axis, s.a_sign) * (e[s.a_axis] / w);
    g.b = axis(s.b_axis, s.b_sign) * (e[s.b_axis] / h);
    if (width) *width = w;
    if (height) *height = h;
    return g;
}

glm::dmat4 relief_view_clip(const ReliefGeometry& g, int width, int height, double d_lo, double d_hi) {
    // Dual basis of (a, b, f): u = dot(X - origin, da), v = dot(X - origin, db), d = dot(X - origin, f).
    const glm::dvec3 f = g.f();
    const glm::dvec3 da = glm::cross(g.b, f) / glm::dot(g.a, glm::cross(g.b, f));
    const glm::dvec3 db = glm::cross(f, g.a) / glm::dot(g.b, glm::cross(f, g.a));
    const double margin = 1e-3 * std::max({glm::length(g.a) * width, glm::length(g.b) * height, d_hi - d_lo});
    const double depth = (d_hi - d_lo) + 2.0 * margin;
    glm::dmat4 m(0.0);  // m[column][row]
    auto set_row = [&](int row, const glm::dvec3& dir, double scale, double offset) {
        for (int c = 0; c < 3; ++c) m[c][row] = dir[c] * scale;
        m[3][row] = offset;
    };
    set_row(0, da, 2.0 / width, -2.0 * glm::dot(g.origin, da) / width - 1.0);
    set_row(1, db, 2.0 / height, -2.0 * glm::dot(g.origin, db) / height - 1.0);
    // z_ndc = -1 at d = d_hi + margin, +1 at d = d_lo - margin.
    set_row(2, f, -2.0 / depth, -1.0 + 2.0 * (d_hi + margin + glm::dot(g.origin, f)) / depth);
    m[3][3] = 1.0;
    return m;
}

BakedFace bake_view(MeshRenderer& renderer, const ReliefGeometry& g, int width, int height, double d_lo, double d_hi,
                    bool cull_back_faces) {
    const glm::dvec3 f = g.f();
    const glm::dvec4 plane(f, -glm::dot(f, g.origin));
    MeshFrame frame = renderer.render(relief_view_clip(g, width, height, d_lo, d_hi), width, height, Rgba8{0, 0, 0, 0},
                                      plane, cull_back_faces);
    BakedFace face;
    face.geometry = g;
    face.color = std::move(frame.color);
    face.displacement = std::move(frame.distance);
    double lo = 0.0, hi = 0.0;
    bool any = false;
    for (size_t p = 0; p < face.color.pixels.size(); ++p) {
        float& d = face.displacement.pixels[p];
        if (face.color.pixels[p].a == 0) {
            d = 0.0f;
            continue;
        }
        face.color.pixels[p].a = 255;
        // The surface lies in the slab; rounding may put it a hair outside.
        d = float(std::clamp(double(d), d_lo, d_hi));
        lo = any ? std::min(lo, double(d)) : double(d);
        hi = any ? std::max(hi, double(d)) : double(d);
        any = true;
    }
    face.range_lo = lo;
    face.range_hi = hi;
    return face;
}

BakedObject bake_object(const TriangleMesh& mesh, int n, const std::function<void(int, int)>& progress) {
    BakedObject obj;
    obj.box = bake_box(mesh.lo, mesh.hi, n, &obj.warnings);
    const glm::dvec3 e = obj.box.extent();
    MeshRenderer renderer(mesh);
    for (size_t i = 0; i < kFaces.size(); ++i) {
        const FaceSpec& s = kFaces[i];
        BakedFace& face = obj.faces[i];
        face.key = s.key;
        int w = 0, h = 0;
        face.geometry = face_geometry(obj.box, s.key, &w, &h);
        BakedFace view = bake_view(renderer, face.geometry, w, h, -e[s.normal_axis], 0.0);
        face.color = std::move(view.color);
        face.displacement = std::move(view.displacement);
        face.range_lo = view.range_lo;
        face.range_hi = view.range_hi;
        face.discontinuity = kBakeDiscontinuityTexels *
                             std::max(glm::length(face.geometry.a), glm::length(face.geometry.b));
        if (progress) progress(int(i) + 1, int(kFaces.size()));
    }
    return obj;
}

std::string write_object(const std::string& dir, const std::string& name, const BakedObject& obj,
                         const std::string& source) {
    if (name.empty()) throw IoError(dir + ": cannot write an object without a name");
    std::error_code ec;
    if (!dir.empty()) {
        fs::create_directories(dir, ec);
        if (ec || !fs::is_directory(dir, ec)) throw IoError(dir + ": cannot create the output folder");
    }
    const fs::path d = dir.empty() ? fs::path(".") : fs::path(dir);
    const std::string manifest = (d / (name + ".object.json")).string();
    std::vector<std::string> written;
    auto cleanup = [&] {
        std::error_code e2;
        for (const std::string& p : written) fs::remove(p, e2);
        fs::remove(manifest + ".tmp", e2);
    };
    try {
        auto num = [](double v) { return nlohmann::json(v); };
        nlohmann::json faces = nlohmann::json::object();
        for (size_t i = 0; i < kFaces.size(); ++i) {
            const BakedFace& face = obj.faces[i];
            const std::string color_file = name + "_" + kFaces[i].file_tag + "_color.png";
            const std::string disp_file = name + "_" + kFaces[i].file_tag + "_disp.png";
            ImageF normalized(face.displacement.width, face.displacement.height);
            const double span = face.range_hi - face.range_lo;
            for (size_t p = 0; p < normalized.pixels.size(); ++p)
                normalized.pixels[p] = face.color.pixels[p].a == 0 || !(span > 0.0)
                                           ? 0.0f
                                           : float(std::clamp((double(face.displacement.pixels[p]) - face.range_lo) /
                                                                  span,
                                                              0.0, 1.0));
            write_rgba8((d / color_file).string(), face.color);
            written.push_back((d / color_file).string());
            write_gray((d / disp_file).string(), normalized);
            written.push_back((d / disp_file).string());
            faces[face.key] = {{"color", color_file},
                               {"displacement", disp_file},
                               {"displacement_range", {num(face.range_lo), num(face.range_hi)}},
                               {"size", {face.color.width, face.color.height}}};
            if (face.discontinuity > 0) faces[face.key]["discontinuity"] = num(face.discontinuity);
        }
        nlohmann::json j = {{"name", name},
                            {"box",
                             {{"min", {obj.box.lo.x, obj.box.lo.y, obj.box.lo.z}},
                              {"max", {obj.box.hi.x, obj.box.hi.y, obj.box.hi.z}}}},
                            {"faces", faces}};
        if (!source.empty()) j["source"] = source;
        const std::string tmp = manifest + ".tmp";
        {
            std::ofstream f(tmp);
            f << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            if (!f) throw IoError(manifest + ": write failed");
        }
        fs::rename(tmp, manifest, ec);
        if (ec) throw IoError(manifest + ": cannot write: " + ec.message());
    } catch (...) {
        cleanup();
        throw;
    }
    return manifest;
}

}  // namespace rtm
