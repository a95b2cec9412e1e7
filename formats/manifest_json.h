// What the readers of the project's JSON manifests share: the one-line error (the file's path, then what is
// wrong), short descriptions of hostile values, reading a small text file, parsing JSON with errors that name the
// field, typed field getters, and path resolution (writers use formats/atomic_file.h). Used by the object manifest
// (formats/object_manifest.h), the scene manifest and the relief manifest's reader.
#pragma once

#include <glm/vec3.hpp>

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rtm::manifest_json {

using nlohmann::json;

// The project's coordinate limit (docs/DESIGN.md, "Input limits", as the CLI's camera flags): past it, squared
// lengths in the camera's checks overflow and rendering has no digits left for the scene.
inline constexpr double kMaxCoordinate = 1e30;
// The smallest extent of a quad (or box) relative to its largest coordinate (docs/DESIGN.md, "Input limits"). A
// camera about the quad sits a few sides from it, and Camera::check (texmap/camera.cpp) refuses an eye that equals
// the point looked at within 1e-12 of their distance from the origin: 1e-9 leaves a factor of several hundred for
// orbits and eyes closer than a side, and keeps texel positions (origin + u a + v b) far above double rounding.
inline constexpr double kCoordinatePerMinExtent = 1e9;
double largest_coordinate(const glm::dvec3& v);  // max |component|; NaN compares false against any limit

// Throws rtm::IoError "<path>: <what>", control characters shown as '?' so the message stays one line.
[[noreturn]] void fail(const std::string& path, const std::string& what);
std::string fmt_double(double v);  // shortest round-trip form; nan, inf, -inf
std::string fmt_list(std::initializer_list<std::string> items);
std::string fmt_vec(const glm::dvec3& v);
std::string describe(const json& v);                 // one short line, never recursing into containers
std::string truncate(std::string s, size_t n = 60);  // at most n characters, then "..."
std::string quoted(const std::string& s);            // JSON-quoted, truncated, one line
// The text of a manifest file of the given kind ("object manifest"), at most 1 MiB, not empty.
std::string read_text(const std::string& path, const std::string& kind);
json parse(const std::string& path, const std::string& text);

// Field getters; `where` prefixes the field's name in messages (e.g. "face \"+x\": ").
const json& required(const std::string& path, const json& j, const std::string& where, const char* key,
                     const char* expected);
std::string get_file_name(const std::string& path, const json& j, const std::string& where, const char* key);
std::vector<double> get_numbers(const std::string& path, const json& j, const std::string& where, const char* key,
                                size_t n, const char* expected);
glm::dvec3 get_vec3(const std::string& path, const json& j, const std::string& where, const char* key);

// `file` relative to the manifest's folder (absolute paths stay as they are), lexically normalized.
std::string resolve(const std::string& manifest_path, const std::string& file);
// A relative path from the manifest's folder to `file` (for writers).
std::string relative_to_manifest(const std::string& manifest_path, const std::string& file);

}  // namespace rtm::manifest_json
