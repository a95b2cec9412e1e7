// NAME.relief.json reading and writing (docs/FORMATS.md, "The relief manifest").
//
// Every failure is an rtm::IoError with one line: "<manifest path>: <what is wrong, expected vs found>". Values that
// are quoted back to the user go through describe(), which never recurses into nested containers, so a hostile
// manifest (deep nesting, huge arrays, control characters) cannot make the message multi-line or unbounded.
#include "formats/relief_manifest.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <initializer_list>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "formats/atomic_file.h"
#include "formats/image_io.h"
#include "formats/manifest_json.h"

namespace rtm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A manifest is a few hundred bytes; refuse to slurp anything absurd.
constexpr std::uintmax_t kMaxManifestBytes = 1u << 20;

// The one-line error and the short descriptions of hostile values are the manifests' shared ones
// (formats/manifest_json.h).
using manifest_json::describe;
using manifest_json::fail;
using manifest_json::fmt_double;
using manifest_json::fmt_list;
using manifest_json::fmt_vec;
using manifest_json::kCoordinatePerMinExtent;
using manifest_json::kMaxCoordinate;
using manifest_json::largest_coordinate;
using manifest_json::truncate;

// The manifest's text, after checking the file itself.
std::string read_text(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) {
        const int err = (ec && ec != std::errc::no_such_file_or_directory) ? ec.value() : ENOENT;
        fail(path, std::string("cannot open relief manifest: ") + std::strerror(err));
    }
    if (fs::is_directory(st)) fail(path, "is a directory, expected a relief manifest file (NAME.relief.json)");
    if (!fs::is_regular_file(st)) fail(path, "is not a regular file, expected a relief manifest file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) fail(path, "cannot open relief manifest: " + ec.message());
    if (size > kMaxManifestBytes)
        fail(path, "relief manifest is " + std::to_string(size) + " bytes, expected at most " +
                       std::to_string(kMaxManifestBytes));
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, std::string("cannot open relief manifest: ") + std::strerror(errno));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) fail(path, "cannot read relief manifest: I/O error");
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        fail(path, "relief manifest is empty, expected a JSON object");
    return text;
}

json parse_json(const std::string& path, const std::string& text) {
    // The last top-level key seen, so that a number too large for a double (which nlohmann reports as
    // out_of_range.406 without a position) can still be blamed on its field.
    std::string last_key;
    const json::parser_callback_t track = [&](int depth, json::parse_event_t event, json& parsed) {
        if (event == json::parse_event_t::key && depth == 1 && parsed.is_string()) last_key = parsed.get<std::string>();
        return true;
    };
    auto strip = [](std::string msg) {
        // what() is "[json.exception.parse_error.101] parse error at line L, column C: ..."; keep the useful part.
        if (const size_t p = msg.find("] "); msg.rfind("[json.exception", 0) == 0 && p != std::string::npos)
            msg = msg.substr(p + 2);
        std::replace(msg.begin(), msg.end(), '\n', ' ');
        return msg;
    };
    try {
        return json::parse(text, track);
    } catch (const json::parse_error& e) {
        const std::string msg = strip(e.what());
        // The parser read past the last byte: the text stops in the middle of a value.
        const bool truncated = e.byte > text.size() || msg.find("unexpected end of input") != std::string::npos;
        fail(path, std::string(truncated ? "truncated" : "malformed") + " JSON: " + msg + " (byte " +
                       std::to_string(e.byte) + ")");
    } catch (const json::out_of_range& e) {
        if (e.id == 406) {  // "number overflow parsing '1e999'"
            std::string msg = strip(e.what()), token;
            if (const size_t a = msg.find('\''), b = msg.rfind('\''); a != std::string::npos && b > a)
                token = truncate(msg.substr(a + 1, b - a - 1), 40);
            // The key is quoted through JSON so that control characters in it cannot break the line.
            const std::string where = last_key.empty()
                                          ? std::string("the manifest")
                                          : "field " + truncate(json(last_key).dump(-1, ' ', false,
                                                                                    json::error_handler_t::replace));
            fail(path, where + " must hold finite numbers, found " + token + ", which overflows a double");
        }
        fail(path, "malformed JSON: " + strip(e.what()));
    } catch (const json::exception& e) {
        fail(path, "malformed JSON: " + strip(e.what()));
    }
}

const json& required(const std::string& path, const json& j, const char* key, const char* expected) {
    auto it = j.find(key);
    if (it == j.end()) fail(path, std::string("required field \"") + key + "\" is missing, expected " + expected);
    return *it;
}

std::string get_file_name(const std::string& path, const json& j, const char* key) {
    const json& v = required(path, j, key, "an image file name");
    if (!v.is_string() || v.get_ref<const std::string&>().empty())
        fail(path, std::string("field \"") + key + "\" must be a non-empty string (an image file name), found " +
                       describe(v));
    const std::string& s = v.get_ref<const std::string&>();
    if (s.find('\0') != std::string::npos)
        fail(path, std::string("field \"") + key + "\" must be a file name, found a string with a NUL character");
    return s;
}

// An array of exactly n finite numbers; otherwise fails naming the field and what was found.
std::vector<double> get_numbers(const std::string& path, const json& j, const char* key, size_t n,
                                const char* expected) {
    const json& v = required(path, j, key, expected);
    bool ok = v.is_array() && v.size() == n;
    std::vector<double> out;
    if (ok) {
        for (const json& e : v) {
            if (!e.is_number()) {
                ok = false;
                break;
            }
            const double d = e.get<double>();
            if (!std::isfinite(d)) {
                ok = false;
                break;
            }
            out.push_back(d);
        }
    }
    if (!ok) fail(path, std::string("field \"") + key + "\" must be " + expected + ", found " + describe(v));
    return out;
}

glm::dvec3 get_vec3(const std::string& path, const json& j, const char* key) {
    const std::vector<double> v = get_numbers(path, j, key, 3, "an array of 3 finite numbers");
    return {v[0], v[1], v[2]};
}

// Divides by the largest component so lengths and cross products neither overflow nor underflow; the parallel
// test below is relative, so scaling does not change its outcome.
glm::dvec3 scaled(const glm::dvec3& v) {
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return m > 0.0 ? v / m : v;
}

void check_geometry(const std::string& path, const ReliefGeometry& g) {
    if (!(largest_coordinate(g.origin) <= kMaxCoordinate))
        fail(path, "field \"origin\" " + fmt_vec(g.origin) + " has a coordinate beyond +-1e30");
    const glm::dvec3 a = scaled(g.a), b = scaled(g.b);
    if (a == glm::dvec3(0.0))
        fail(path, "field \"a\" has zero length, expected a nonzero texel step vector, found " + fmt_vec(g.a));
    if (b == glm::dvec3(0.0))
        fail(path, "field \"b\" has zero length, expected a nonzero texel step vector, found " + fmt_vec(g.b));
    const double la = glm::length(a), lb = glm::length(b);
    if (glm::length(glm::cross(a, b)) <= 1e-12 * la * lb)
        fail(path, "fields \"a\" and \"b\" are parallel, expected two independent directions, found a = " +
                       fmt_vec(g.a) + " and b = " + fmt_vec(g.b));
    // The warp library's own check is the final word. Having passed the scaled checks above, it can only fail on
    // magnitude: |a| and |b| so tiny (or huge) that their cross product underflows (or overflows) a double.
    if (const std::string why = g.validate(); !why.empty())
        fail(path, "fields \"a\" and \"b\" are too small or too large for double precision (" + why +
                       " after rounding), found a = " + fmt_vec(g.a) + " and b = " + fmt_vec(g.b));
}

std::string default_name(const std::string& path) {
    std::string stem = fs::path(path).filename().string();
    for (const char* suffix : {".relief.json", ".json"}) {
        const std::string s = suffix;
        if (stem.size() > s.size() && stem.compare(stem.size() - s.size(), s.size(), s) == 0) {
            stem.resize(stem.size() - s.size());
            break;
        }
    }
    return stem;
}

std::string resolve(const std::string& manifest_path, const std::string& file) {
    const fs::path p(file);
    if (p.is_absolute()) return p.lexically_normal().string();
    return (fs::path(manifest_path).parent_path() / p).lexically_normal().string();
}

std::string size_str(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// The quad of a w x h texture: its corners within the coordinate limit, its sides not lost in rounding at its
// origin (kCoordinatePerMinExtent).
void check_quad(const std::string& path, const ReliefGeometry& g, int w, int h) {
    const glm::dvec3 aw = g.a * double(w), bh = g.b * double(h);
    const std::pair<const char*, glm::dvec3> corners[] = {{"origin + width * a", g.origin + aw},
                                                          {"origin + height * b", g.origin + bh},
                                                          {"origin + width * a + height * b", g.origin + aw + bh}};
    for (const auto& [name, c] : corners)
        if (!(largest_coordinate(c) <= kMaxCoordinate))
            fail(path, std::string("the quad's corner ") + name + " = " + fmt_vec(c) +
                           " has a coordinate beyond +-1e30" + " (the texture is " + size_str(w, h) + ")");
    const double side_a = glm::length(aw), side_b = glm::length(bh);
    const double least = largest_coordinate(g.origin) / kCoordinatePerMinExtent;
    if (!(std::min(side_a, side_b) >= least))
        fail(path, "the quad's extent " + fmt_double(std::min(side_a, side_b)) + " is lost in rounding at origin " +
                       fmt_vec(g.origin) + ": |a| * width (" + fmt_double(side_a) + ") and |b| * height (" +
                       fmt_double(side_b) + ") must each be at least 1e-9 times the origin's largest coordinate, " +
                       fmt_double(least));
}

}  // namespace

ReliefManifest parse_relief_manifest(const std::string& path) {
    const json j = parse_json(path, read_text(path));
    if (!j.is_object()) fail(path, "top level must be a JSON object, found " + describe(j));

    ReliefManifest m;
    m.path = path;
    // Required fields, in the order of docs/FORMATS.md.
    m.color_path = resolve(path, get_file_name(path, j, "color"));
    m.displacement_path = resolve(path, get_file_name(path, j, "displacement"));
    const std::vector<double> range = get_numbers(path, j, "displacement_range", 2,
                                                  "an array of 2 finite numbers [min, max]");
    if (range[0] > range[1])
        fail(path, "field \"displacement_range\" must be [min, max] with min <= max, found [" + fmt_double(range[0]) +
                       ", " + fmt_double(range[1]) + "]");
    m.range_min = range[0];
    m.range_max = range[1];
    m.geometry.origin = get_vec3(path, j, "origin");
    m.geometry.a = get_vec3(path, j, "a");
    m.geometry.b = get_vec3(path, j, "b");
    check_geometry(path, m.geometry);

    // Optional fields.
    m.name = default_name(path);
    if (auto it = j.find("name"); it != j.end()) {
        if (!it->is_string()) fail(path, "field \"name\" must be a string, found " + describe(*it));
        if (!it->get_ref<const std::string&>().empty()) m.name = it->get<std::string>();
    }
    if (auto it = j.find("discontinuity_threshold"); it != j.end()) {
        const bool ok = it->is_number() && std::isfinite(it->get<double>()) && it->get<double>() >= 0.0;
        if (!ok)
            fail(path, "field \"discontinuity_threshold\" must be a finite number >= 0 (world units), found " +
                           describe(*it));
        m.discontinuity_threshold = it->get<double>();
    }
    return m;
}

ReliefTexture load_relief(const std::string& manifest_path, ReliefManifest* manifest_out) {
    ReliefManifest m = parse_relief_manifest(manifest_path);
    ImageRGBA8 color;
    ImageF disp;
    try {
        color = read_rgba8(m.color_path);
        disp = read_gray(m.displacement_path);
    } catch (const IoError& e) {
        // The image reader names the image; say which manifest asked for it.
        fail(manifest_path, e.what());
    }
    const std::string color_name = fs::path(m.color_path).filename().string();
    const std::string disp_name = fs::path(m.displacement_path).filename().string();
    if (disp.width != color.width || disp.height != color.height)
        fail(manifest_path, "displacement image " + disp_name + " is " + size_str(disp.width, disp.height) +
                                " but color " + color_name + " is " + size_str(color.width, color.height));
    check_quad(manifest_path, m.geometry, color.width, color.height);

    // Normalized 0..1 onto displacement_range, in world units along +f.
    const double span = m.range_max - m.range_min;
    ImageF world(disp.width, disp.height);
    for (int row = 0; row < disp.height; ++row) {
        for (int x = 0; x < disp.width; ++x) {
            float n = disp.at(x, row);
            // Integer formats always convert to 0..1; float formats (PFM, EXR, TIFF) can hold anything. A hair
            // outside (float rounding) is clamped, as write_relief does.
            if (!std::isfinite(n) || n < -1e-6f || n > 1.0f + 1e-6f)
                fail(manifest_path, "displacement image " + disp_name + " has " +
                                        (std::isfinite(n) ? "the value " : "a non-finite value (") + fmt_double(n) +
                                        (std::isfinite(n) ? "" : ")") + " at texel (" + std::to_string(x) + ", " +
                                        std::to_string(row) + "), expected a finite value in 0..1");
            n = std::clamp(n, 0.0f, 1.0f);
            const float d = float(m.range_min + double(n) * span);
            if (!std::isfinite(d))
                fail(manifest_path, "field \"displacement_range\" [" + fmt_double(m.range_min) + ", " +
                                        fmt_double(m.range_max) +
                                        "] gives displacements too large for single precision");
            world.at(x, row) = d;
        }
    }
    // After the texels, so that a range beyond single precision is named as such.
    if (!(std::max(std::abs(m.range_min), std::abs(m.range_max)) <= kMaxCoordinate))
        fail(manifest_path, "field \"displacement_range\" [" + fmt_double(m.range_min) + ", " +
                                fmt_double(m.range_max) + "] reaches beyond the coordinate limit +-1e30");

    ReliefTexture t;
    try {
        t = make_relief(color, world, m.range_min, m.range_max, m.geometry);
    } catch (const std::invalid_argument& e) {
        fail(manifest_path, e.what());
    }
    // The manifest's own threshold marks the surface's discontinuities (paper section 4.1.1); 0 means none.
    if (m.discontinuity_threshold) mark_discontinuities(t, *m.discontinuity_threshold);
    if (manifest_out) *manifest_out = std::move(m);
    return t;
}

void write_relief(const std::string& manifest_path, const ReliefManifest& m, const ImageRGBA8& color,
                  const ImageF& displacement_normalized) {
    // Refuse to write what load_relief would reject.
    if (color.width <= 0 || color.height <= 0)
        fail(manifest_path, "cannot write: color image is empty (" + size_str(color.width, color.height) + ")");
    if (displacement_normalized.width != color.width || displacement_normalized.height != color.height)
        fail(manifest_path, "cannot write: displacement image is " +
                                size_str(displacement_normalized.width, displacement_normalized.height) +
                                " but color is " + size_str(color.width, color.height));
    if (!std::isfinite(m.range_min) || !std::isfinite(m.range_max) || m.range_min > m.range_max)
        fail(manifest_path, "cannot write: displacement_range must be 2 finite numbers with min <= max, found [" +
                                fmt_double(m.range_min) + ", " + fmt_double(m.range_max) + "]");
    const std::pair<const char*, glm::dvec3> vectors[] = {{"origin", m.geometry.origin},
                                                          {"a", m.geometry.a},
                                                          {"b", m.geometry.b}};
    for (const auto& [key, v] : vectors)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            fail(manifest_path,
                 std::string("cannot write: \"") + key + "\" must be 3 finite numbers, found " + fmt_vec(v));
    check_geometry(manifest_path, m.geometry);
    if (m.discontinuity_threshold && !(std::isfinite(*m.discontinuity_threshold) && *m.discontinuity_threshold >= 0))
        fail(manifest_path, "cannot write: discontinuity_threshold must be a finite number >= 0, found " +
                                fmt_double(*m.discontinuity_threshold));
    // Normalized displacement must be 0..1; a hair outside (float rounding) is clamped, anything else refused.
    ImageF disp = displacement_normalized;
    for (size_t i = 0; i < disp.pixels.size(); ++i) {
        float& v = disp.pixels[i];
        if (!std::isfinite(v) || v < -1e-6f || v > 1.0f + 1e-6f)
            fail(manifest_path,
                 "cannot write: normalized displacement at texel (" + std::to_string(i % size_t(disp.width)) + ", " +
                     std::to_string(i / size_t(disp.width)) + ") is " + fmt_double(v) + ", expected 0..1");
        v = std::clamp(v, 0.0f, 1.0f);
    }

    const fs::path mp(manifest_path);
    const std::string stem = default_name(manifest_path);
    if (stem.empty()) fail(manifest_path, "cannot write: the manifest's file name has no stem to name images by");
    const std::string color_file = stem + "_color.png";
    const std::string disp_file = stem + "_disp.png";
    const fs::path dir = mp.parent_path();
    if (!dir.empty()) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) fail(manifest_path, "cannot create folder " + dir.string() + ": " + ec.message());
    }
    if (std::error_code ec; fs::is_directory(mp, ec)) fail(manifest_path, "cannot write: is a directory");

    // Images first, manifest last: a manifest on disk always refers to complete images.
    write_rgba8((dir / color_file).string(), color);
    write_gray((dir / disp_file).string(), disp);

    auto num = [](double v) { return json(v).dump(); };
    auto vec = [&](const glm::dvec3& v) { return fmt_list({num(v.x), num(v.y), num(v.z)}); };
    auto str = [](const std::string& s) { return json(s).dump(-1, ' ', false, json::error_handler_t::replace); };
    std::ostringstream o;
    o << "{\n";
    o << "  \"name\": " << str(m.name.empty() ? stem : m.name) << ",\n";
    o << "  \"color\": " << str(color_file) << ",\n";
    o << "  \"displacement\": " << str(disp_file) << ",\n";
    o << "  \"displacement_range\": " << fmt_list({num(m.range_min), num(m.range_max)}) << ",\n";
    o << "  \"origin\": " << vec(m.geometry.origin) << ",\n";
    o << "  \"a\": " << vec(m.geometry.a) << ",\n";
    o << "  \"b\": " << vec(m.geometry.b);
    if (m.discontinuity_threshold) o << ",\n  \"discontinuity_threshold\": " << num(*m.discontinuity_threshold);
    o << "\n}\n";
    write_text_atomically(manifest_path, o.str());
}

}  // namespace rtm
