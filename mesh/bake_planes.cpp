#include "mesh/bake_planes.h"

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "formats/image_io.h"
#include "formats/manifest_json.h"
#include "formats/relief_manifest.h"
#include "mesh/bake_object.h"
#include "mesh/mesh_renderer.h"

namespace rtm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

bool finite_number(const json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

glm::dvec3 vec3_field(const std::string& path, const std::string& where, const json& p, const char* key) {
    if (!p.contains(key)) throw_io_error(path, where + ": missing field \"" + key + "\"");
    const json& v = p[key];
    if (!v.is_array() || v.size() != 3 || !finite_number(v[0]) || !finite_number(v[1]) || !finite_number(v[2]))
        throw_io_error(path, where + ": field \"" + key + "\" must be an array of 3 finite numbers, found " +
                                 v.dump(-1, ' ', false, json::error_handler_t::replace));
    return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

}  // namespace

std::vector<BakePlane> parse_bake_planes(const std::string& path) {
    // A small regular file (a FIFO or a device is refused without being opened), parsed with errors that say where.
    const json j = manifest_json::parse(path, manifest_json::read_text(path, "planes"));
    if (!j.is_object() || !j.contains("planes") || !j["planes"].is_array() || j["planes"].empty())
        throw_io_error(path, "expected an object with a non-empty array \"planes\"");
    std::vector<BakePlane> out;
    std::set<std::string> names;
    for (size_t i = 0; i < j["planes"].size(); ++i) {
        const json& p = j["planes"][i];
        std::string where = "plane " + std::to_string(i);
        if (!p.is_object()) throw_io_error(path, where + ": expected an object");
        BakePlane b;
        if (!p.contains("name") || !p["name"].is_string())
            throw_io_error(path, where + ": field \"name\" must be a string");
        b.name = p["name"].get<std::string>();
        const bool name_ok = !b.name.empty() && b.name.size() <= 64 &&
                             std::all_of(b.name.begin(), b.name.end(), [](char c) {
                                 return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
                             });
        if (!name_ok) throw_io_error(path, where + ": field \"name\" must be 1..64 letters, digits, '_' or '-'");
        where += " (\"" + b.name + "\")";
        if (!names.insert(b.name).second) throw_io_error(path, where + ": the name is used twice");
        b.geometry.origin = vec3_field(path, where, p, "origin");
        b.geometry.a = vec3_field(path, where, p, "a");
        b.geometry.b = vec3_field(path, where, p, "b");
        if (const std::string why = b.geometry.validate(); !why.empty()) throw_io_error(path, where + ": " + why);
        const json* size = p.contains("size") ? &p["size"] : nullptr;
        if (!size || !size->is_array() || size->size() != 2 || !(*size)[0].is_number_integer() ||
            !(*size)[1].is_number_integer() || (*size)[0].get<long long>() < 1 || (*size)[0].get<long long>() > 16384 ||
            (*size)[1].get<long long>() < 1 || (*size)[1].get<long long>() > 16384)
            throw_io_error(path, where + ": field \"size\" must be [w, h], integers in 1..16384");
        b.width = int((*size)[0].get<long long>());
        b.height = int((*size)[1].get<long long>());
        if (p.contains("range")) {
            const json& r = p["range"];
            if (!r.is_array() || r.size() != 2 || !finite_number(r[0]) || !finite_number(r[1]) ||
                r[0].get<double>() > r[1].get<double>())
                throw_io_error(path, where + ": field \"range\" must be [lo, hi], finite numbers with lo <= hi");
            b.range_lo = r[0].get<double>();
            b.range_hi = r[1].get<double>();
        }
        if (p.contains("cull_back_faces")) {
            if (!p["cull_back_faces"].is_boolean())
                throw_io_error(path, where + ": field \"cull_back_faces\" must be true or false, found " +
                                         p["cull_back_faces"].dump(-1, ' ', false, json::error_handler_t::replace));
            b.cull_back_faces = p["cull_back_faces"].get<bool>();
        }
        out.push_back(b);
    }
    return out;
}

std::vector<std::string> bake_planes(const TriangleMesh& mesh, const std::vector<BakePlane>& planes,
                                     const std::string& dir, const std::string& stem) {
    MeshRenderer renderer(mesh);
    std::vector<BakedFace> views;
    for (const BakePlane& p : planes) {
        double lo = 0.0, hi = 0.0;
        if (p.range_lo) {
            lo = *p.range_lo;
            hi = *p.range_hi;
        } else {
            // Every corner of the mesh's bounds, measured along f from the plane.
            const glm::dvec3 f = p.geometry.f();
            for (int c = 0; c < 8; ++c) {
                const glm::dvec3 x((c & 1) ? mesh.hi.x : mesh.lo.x, (c & 2) ? mesh.hi.y : mesh.lo.y,
                                   (c & 4) ? mesh.hi.z : mesh.lo.z);
                const double d = glm::dot(x - p.geometry.origin, f);
                lo = c ? std::min(lo, d) : d;
                hi = c ? std::max(hi, d) : d;
            }
        }
        views.push_back(bake_view(renderer, p.geometry, p.width, p.height, lo, hi, p.cull_back_faces));
    }
    std::vector<std::string> manifests, written;
    const fs::path d = dir.empty() ? fs::path(".") : fs::path(dir);
    try {
        for (size_t i = 0; i < planes.size(); ++i) {
            const BakedFace& v = views[i];
            ReliefManifest m;
            m.name = stem + "_" + planes[i].name;
            m.range_min = v.range_lo;
            m.range_max = v.range_hi;
            m.geometry = planes[i].geometry;
            ImageF normalized(v.displacement.width, v.displacement.height);
            const double span = v.range_hi - v.range_lo;
            for (size_t k = 0; k < normalized.pixels.size(); ++k)
                normalized.pixels[k] = v.color.pixels[k].a == 0 || !(span > 0.0)
                                           ? 0.0f
                                           : float(std::clamp((double(v.displacement.pixels[k]) - v.range_lo) / span,
                                                              0.0, 1.0));
            const std::string manifest = (d / (m.name + ".relief.json")).string();
            // write_relief's images: NAME_color.png and NAME_disp.png beside the manifest.
            written.push_back((d / (m.name + "_color.png")).string());
            written.push_back((d / (m.name + "_disp.png")).string());
            written.push_back(manifest);
            write_relief(manifest, m, v.color, normalized);
            manifests.push_back(manifest);
        }
    } catch (...) {
        std::error_code ec;
        for (const std::string& f : written) fs::remove(f, ec);
        throw;
    }
    return manifests;
}

}  // namespace rtm
