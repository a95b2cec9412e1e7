// NAME.object.json reading and writing (formats/object_manifest.h, docs/OBJECTS.md).
#include "formats/object_manifest.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "formats/image_io.h"
#include "formats/atomic_file.h"
#include "formats/manifest_json.h"
#include "formats/relief_manifest.h"

namespace rtm {

namespace {

namespace fs = std::filesystem;
using namespace manifest_json;

const char* kAxisNames[3] = {"x", "y", "z"};

// The coordinate limit and the smallest extent relative to the largest coordinate (manifest_json.h) hold for the box,
// as each of its faces is a relief.
// What is wrong with the box's size and place (min < max is checked before), or an empty string.
std::string box_problem(const Box& box) {
    if (!(largest_coordinate(box.lo) <= kMaxCoordinate))
        return "field \"min\" " + fmt_vec(box.lo) + " has a coordinate beyond +-1e30";
    if (!(largest_coordinate(box.hi) <= kMaxCoordinate))
        return "field \"max\" " + fmt_vec(box.hi) + " has a coordinate beyond +-1e30";
    const double largest = std::max(largest_coordinate(box.lo), largest_coordinate(box.hi));
    const glm::dvec3 ext = box.hi - box.lo;
    for (int i = 0; i < 3; ++i)
        if (!(ext[i] >= largest / kCoordinatePerMinExtent))
            return std::string("the extent ") + fmt_double(ext[i]) + " along " + kAxisNames[i] +
                   " is lost in rounding at the box's coordinates: every extent must be at least 1e-9 times the "
                   "largest |coordinate| " +
                   fmt_double(largest) + ", that is " + fmt_double(largest / kCoordinatePerMinExtent);
    return {};
}

std::string face_where(int f) { return std::string("face \"") + kFaceKeys[size_t(f)] + "\": "; }

std::string default_name(const std::string& path) {
    std::string stem = fs::path(path).filename().string();
    for (const char* suffix : {".object.json", ".json"}) {
        const std::string s = suffix;
        if (stem.size() > s.size() && stem.compare(stem.size() - s.size(), s.size(), s) == 0) {
            stem.resize(stem.size() - s.size());
            break;
        }
    }
    return stem;
}

// lo <= hi <= 0 and lo >= -(depth of the box along the face's normal), finite.
std::string range_problem(double lo, double hi, double depth) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return "must hold 2 finite numbers";
    if (lo > hi) return "must be [lo, hi] with lo <= hi";
    if (hi > 0.0) return "must have hi <= 0 (the surface lies inside the box, the normal points out)";
    // A relative hair of slack for ranges computed in floating point by a writer.
    if (lo < -depth * (1.0 + 1e-9)) return "must have lo >= -" + fmt_double(depth) + " (the box's depth there)";
    return {};
}

void parse_face(const std::string& path, const json& j, int f, const Box& box, ObjectFaceEntry& e) {
    const std::string where = face_where(f);
    if (!j.is_object()) fail(path, where + "must be a JSON object, found " + describe(j));
    const double depth = box.extent()[face_axis(f)];
    if (auto it = j.find("relief"); it != j.end()) {
        e.relief_path = resolve(path, get_file_name(path, j, where, "relief"));
        ReliefManifest m;
        try {
            m = parse_relief_manifest(e.relief_path);
        } catch (const IoError& err) {
            fail(path, where + "field \"relief\": " + err.what());
        }
        e.color_path = m.color_path;
        e.displacement_path = m.displacement_path;
        e.range_min = m.range_min;
        e.range_max = m.range_max;
        e.discontinuity = m.discontinuity_threshold;
        e.geometry = m.geometry;
        if (const std::string why = range_problem(e.range_min, e.range_max, depth); !why.empty())
            fail(path, where + "the relief's field \"displacement_range\" " + why + ", found " +
                           fmt_list({fmt_double(e.range_min), fmt_double(e.range_max)}));
        return;
    }
    e.color_path = resolve(path, get_file_name(path, j, where, "color"));
    e.displacement_path = resolve(path, get_file_name(path, j, where, "displacement"));
    const json& r = required(path, j, where, "displacement_range", "an array of 2 finite numbers [lo, hi]");
    const std::vector<double> range = get_numbers(path, j, where, "displacement_range", 2,
                                                  "an array of 2 finite numbers [lo, hi]");
    if (const std::string why = range_problem(range[0], range[1], depth); !why.empty())
        fail(path, where + "field \"displacement_range\" " + why + ", found " + describe(r));
    e.range_min = range[0];
    e.range_max = range[1];
    if (auto it = j.find("discontinuity"); it != j.end()) {
        if (!(it->is_number() && std::isfinite(it->get<double>()) && it->get<double>() >= 0.0))
            fail(path,
                 where + "field \"discontinuity\" must be a finite number >= 0 (world units), found " + describe(*it));
        e.discontinuity = it->get<double>();
    }
}

// World displacement from the normalized image, as load_relief maps it.
ImageF world_displacement(const std::string& path, const std::string& where, const ImageF& disp, double lo, double hi,
                          const std::string& disp_name) {
    ImageF world(disp.width, disp.height);
    for (int row = 0; row < disp.height; ++row)
        for (int x = 0; x < disp.width; ++x) {
            float n = disp.at(x, row);
            if (!std::isfinite(n) || n < -1e-6f || n > 1.0f + 1e-6f)
                fail(path, where + "displacement image " + disp_name + " has the value " + fmt_double(n) +
                               " at texel (" + std::to_string(x) + ", " + std::to_string(row) +
                               "), expected a finite value in 0..1");
            n = std::clamp(n, 0.0f, 1.0f);
            world.at(x, row) = float(lo + double(n) * (hi - lo));
        }
    return world;
}

std::string size_str(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

const char* face_tag(int face) {
    static constexpr const char* tags[kFaceCount] = {"px", "nx", "py", "ny", "pz", "nz"};
    return tags[face];
}

ObjectManifest parse_object_manifest(const std::string& path) {
    const json j = parse(path, read_text(path, "object manifest"));
    if (!j.is_object()) fail(path, "top level must be a JSON object, found " + describe(j));
    ObjectManifest m;
    m.path = path;
    m.name = default_name(path);
    if (auto it = j.find("name"); it != j.end()) {
        if (!it->is_string()) fail(path, "field \"name\" must be a string, found " + describe(*it));
        if (!it->get_ref<const std::string&>().empty()) m.name = it->get<std::string>();
    }
    const json& box = required(path, j, "", "box", "an object {\"min\": [x, y, z], \"max\": [x, y, z]}");
    if (!box.is_object())
        fail(path, "field \"box\" must be an object {\"min\": [x, y, z], \"max\": [x, y, z]}, found " + describe(box));
    m.box.lo = get_vec3(path, box, "field \"box\": ", "min");
    m.box.hi = get_vec3(path, box, "field \"box\": ", "max");
    for (int i = 0; i < 3; ++i) {
        const double ext = m.box.hi[i] - m.box.lo[i];
        if (!(ext > 0.0) || !std::isfinite(ext))
            fail(path, std::string("field \"box\" must have min < max on every axis, found min ") + fmt_vec(m.box.lo) +
                           " and max " + fmt_vec(m.box.hi) + " (axis " + kAxisNames[i] + ")");
    }
    if (const std::string why = box_problem(m.box); !why.empty()) fail(path, "field \"box\": " + why);
    const json& faces = required(path, j, "", "faces", "an object with the six faces \"+x\" ... \"-z\"");
    if (!faces.is_object())
        fail(path, "field \"faces\" must be an object with the six faces \"+x\" ... \"-z\", found " + describe(faces));
    for (const auto& [key, value] : faces.items())
        if (std::find(kFaceKeys.begin(), kFaceKeys.end(), key) == kFaceKeys.end())
            fail(path, "field \"faces\" has the key " + quoted(key) +
                           ", expected exactly \"+x\", \"-x\", \"+y\", \"-y\", \"+z\", \"-z\"");
    for (int f = 0; f < kFaceCount; ++f) {
        auto it = faces.find(kFaceKeys[size_t(f)]);
        if (it == faces.end())
            fail(path, std::string("field \"faces\" lacks face \"") + kFaceKeys[size_t(f)] +
                           "\", expected all of \"+x\", \"-x\", \"+y\", \"-y\", \"+z\", \"-z\"");
        parse_face(path, *it, f, m.box, m.faces[size_t(f)]);
    }
    return m;
}

SixFaceObject load_object(const std::string& path, ObjectManifest* manifest_out) {
    ObjectManifest m = parse_object_manifest(path);
    SixFaceObject obj;
    obj.name = m.name;
    obj.box = m.box;
    const glm::dvec3 ext = m.box.extent();
    const double box_size = std::max({ext.x, ext.y, ext.z});
    // Texel spacing along each axis, and the first face that set it.
    double spacing[3] = {0, 0, 0};
    int spacing_face[3] = {-1, -1, -1};
    for (int f = 0; f < kFaceCount; ++f) {
        const ObjectFaceEntry& e = m.faces[size_t(f)];
        const std::string where = face_where(f);
        ImageRGBA8 color;
        ImageF disp;
        try {
            color = read_rgba8(e.color_path);
            disp = read_gray(e.displacement_path);
        } catch (const IoError& err) {
            fail(path, where + err.what());
        }
        const std::string color_name = fs::path(e.color_path).filename().string();
        const std::string disp_name = fs::path(e.displacement_path).filename().string();
        if (disp.width != color.width || disp.height != color.height)
            fail(path, where + "displacement image " + disp_name + " is " + size_str(disp.width, disp.height) +
                           " but color " + color_name + " is " + size_str(color.width, color.height));
        const ReliefGeometry g = box_face_geometry(m.box, f, color.width, color.height);
        if (!e.relief_path.empty()) {
            const double tol = 1e-6 * box_size;
            const double w = color.width, h = color.height;
            const double off = std::max({glm::length(e.geometry.origin - g.origin),
                                         glm::length(e.geometry.a * w - g.a * w),
                                         glm::length(e.geometry.b * h - g.b * h)});
            if (!(off <= tol))
                fail(path, where + "the relief's frame (origin " + fmt_vec(e.geometry.origin) + ", a " +
                               fmt_vec(e.geometry.a) + ", b " + fmt_vec(e.geometry.b) +
                               ") is not the box face's (origin " + fmt_vec(g.origin) + ", a " + fmt_vec(g.a) + ", b " +
                               fmt_vec(g.b) + ")");
        }
        for (int which = 0; which < 2; ++which) {
            const int axis = face_step_axis(f, which);
            const double s = ext[axis] / double(which == 0 ? color.width : color.height);
            if (spacing_face[axis] < 0) {
                spacing[axis] = s;
                spacing_face[axis] = f;
            } else if (std::abs(s - spacing[axis]) > 1e-6 * spacing[axis]) {
                fail(path, std::string("faces \"") + kFaceKeys[size_t(spacing_face[axis])] + "\" and \"" +
                               kFaceKeys[size_t(f)] + "\" differ in texel spacing along " + kAxisNames[axis] + ": " +
                               fmt_double(spacing[axis]) + " vs " + fmt_double(s) + " (face \"" + kFaceKeys[size_t(f)] +
                               "\" is " + size_str(color.width, color.height) + ")");
            }
        }
        const ImageF world = world_displacement(path, where, disp, e.range_min, e.range_max, disp_name);
        ReliefTexture& t = obj.faces[size_t(f)];
        try {
            t = make_relief(color, world, e.range_min, e.range_max, g);
        } catch (const std::invalid_argument& err) {
            fail(path, where + err.what());
        }
        if (e.discontinuity && *e.discontinuity > 0) mark_discontinuities(t, *e.discontinuity);
    }
    if (manifest_out) *manifest_out = std::move(m);
    return obj;
}

void write_object_manifest(const std::string& path, const std::string& name, const Box& box,
                           const std::array<ObjectFaceImages, kFaceCount>& faces) {
    const glm::dvec3 ext = box.extent();
    for (int i = 0; i < 3; ++i)
        if (!(ext[i] > 0.0) || !std::isfinite(ext[i]) || !std::isfinite(box.lo[i]))
            fail(path, "cannot write: box must have finite min < max on every axis, found " + box.to_string());
    if (const std::string why = box_problem(box); !why.empty()) fail(path, "cannot write: box: " + why);
    double spacing[3] = {0, 0, 0};
    int spacing_face[3] = {-1, -1, -1};
    for (int f = 0; f < kFaceCount; ++f) {
        const ObjectFaceImages& fi = faces[size_t(f)];
        const std::string where = std::string("cannot write ") + face_where(f);
        const int w = fi.color.width, h = fi.color.height;
        if (w <= 0 || h <= 0) fail(path, where + "color image is empty (" + size_str(w, h) + ")");
        if (fi.displacement_normalized.width != w || fi.displacement_normalized.height != h)
            fail(path, where + "displacement image is " +
                           size_str(fi.displacement_normalized.width, fi.displacement_normalized.height) +
                           " but color is " + size_str(w, h));
        if (const std::string why = range_problem(fi.range_min, fi.range_max, ext[face_axis(f)]); !why.empty())
            fail(path, where + "displacement_range " + why + ", found " +
                           fmt_list({fmt_double(fi.range_min), fmt_double(fi.range_max)}));
        if (fi.discontinuity && !(std::isfinite(*fi.discontinuity) && *fi.discontinuity >= 0))
            fail(path, where + "discontinuity must be a finite number >= 0, found " + fmt_double(*fi.discontinuity));
        for (float v : fi.displacement_normalized.pixels)
            if (!std::isfinite(v) || v < -1e-6f || v > 1.0f + 1e-6f)
                fail(path, where + "normalized displacement " + fmt_double(v) + " is outside 0..1");
        for (int which = 0; which < 2; ++which) {
            const int axis = face_step_axis(f, which);
            const double s = ext[axis] / double(which == 0 ? w : h);
            if (spacing_face[axis] < 0) {
                spacing[axis] = s;
                spacing_face[axis] = f;
            } else if (std::abs(s - spacing[axis]) > 1e-6 * spacing[axis]) {
                fail(path, std::string("cannot write: faces \"") + kFaceKeys[size_t(spacing_face[axis])] + "\" and \"" +
                               kFaceKeys[size_t(f)] + "\" differ in texel spacing along " + kAxisNames[axis]);
            }
        }
    }
    const fs::path mp(path);
    const std::string stem = default_name(path);
    if (stem.empty()) fail(path, "cannot write: the manifest's file name has no stem to name images by");
    const fs::path dir = mp.parent_path();
    if (!dir.empty()) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) fail(path, "cannot create folder " + dir.string() + ": " + ec.message());
    }
    auto num = [](double v) { return json(v).dump(); };
    std::ostringstream o;
    o << "{\n  \"name\": " << quoted(name.empty() ? stem : name) << ",\n";
    o << "  \"box\": { \"min\": " << fmt_list({num(box.lo.x), num(box.lo.y), num(box.lo.z)})
      << ", \"max\": " << fmt_list({num(box.hi.x), num(box.hi.y), num(box.hi.z)}) << " },\n";
    o << "  \"faces\": {\n";
    // Images first, manifest last: a manifest on disk always refers to complete images.
    for (int f = 0; f < kFaceCount; ++f) {
        const ObjectFaceImages& fi = faces[size_t(f)];
        const std::string color_file = stem + "_" + face_tag(f) + "_color.png";
        const std::string disp_file = stem + "_" + face_tag(f) + "_disp.png";
        write_rgba8((dir / color_file).string(), fi.color);
        ImageF d = fi.displacement_normalized;
        for (float& v : d.pixels) v = std::clamp(v, 0.0f, 1.0f);
        write_gray((dir / disp_file).string(), d);
        o << "    " << quoted(kFaceKeys[size_t(f)]) << ": { \"color\": " << quoted(color_file)
          << ", \"displacement\": " << quoted(disp_file)
          << ", \"displacement_range\": " << fmt_list({num(fi.range_min), num(fi.range_max)});
        if (fi.discontinuity) o << ", \"discontinuity\": " << num(*fi.discontinuity);
        o << " }" << (f + 1 < kFaceCount ? "," : "") << "\n";
    }
    o << "  }\n}\n";
    write_text_atomically(path, o.str());
}

}  // namespace rtm
