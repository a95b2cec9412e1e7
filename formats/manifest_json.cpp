#include "formats/manifest_json.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "formats/image_io.h"

namespace rtm::manifest_json {

namespace fs = std::filesystem;

namespace {

constexpr std::uintmax_t kMaxManifestBytes = 1u << 20;

}  // namespace

std::string truncate(std::string s, size_t n) {
    if (s.size() > n) s = s.substr(0, n) + "...";
    return s;
}

void fail(const std::string& path, const std::string& what) { throw_io_error(path, what); }

double largest_coordinate(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

std::string fmt_double(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return json(v).dump();
}

std::string fmt_list(std::initializer_list<std::string> items) {
    std::string s(1, '[');
    for (const std::string& i : items) {
        if (s.size() > 1) s += ", ";
        s += i;
    }
    s += ']';
    return s;
}

std::string fmt_vec(const glm::dvec3& v) { return fmt_list({fmt_double(v.x), fmt_double(v.y), fmt_double(v.z)}); }

std::string quoted(const std::string& s) {
    return truncate(json(s).dump(-1, ' ', false, json::error_handler_t::replace));
}

std::string describe(const json& v) {
    switch (v.type()) {
        case json::value_t::null: return "null";
        case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
        case json::value_t::number_integer:
        case json::value_t::number_unsigned: return v.dump();
        case json::value_t::number_float: return fmt_double(v.get<double>());
        case json::value_t::string: return "the string " + quoted(v.get_ref<const std::string&>());
        case json::value_t::object: return "an object with " + std::to_string(v.size()) + " fields";
        case json::value_t::array: {
            if (v.size() > 8) return "an array of " + std::to_string(v.size()) + " elements";
            std::string s = "[";
            for (size_t i = 0; i < v.size(); ++i) {
                if (i) s += ", ";
                const json& e = v[i];
                if (e.is_array())
                    s += "[...]";
                else if (e.is_object())
                    s += "{...}";
                else if (e.is_string())
                    s += truncate(quoted(e.get_ref<const std::string&>()), 20);
                else
                    s += describe(e);
            }
            return s + "]";
        }
        default: return "an unsupported value";
    }
}

std::string read_text(const std::string& path, const std::string& kind) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) {
        const int err = (ec && ec != std::errc::no_such_file_or_directory) ? ec.value() : ENOENT;
        fail(path, "cannot open " + kind + ": " + std::strerror(err));
    }
    if (fs::is_directory(st)) fail(path, "is a directory, expected " + kind + " file");
    if (!fs::is_regular_file(st)) fail(path, "is not a regular file, expected " + kind + " file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) fail(path, "cannot open " + kind + ": " + ec.message());
    if (size > kMaxManifestBytes)
        fail(path,
             kind + " is " + std::to_string(size) + " bytes, expected at most " + std::to_string(kMaxManifestBytes));
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open " + kind + ": " + std::strerror(errno));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) fail(path, "cannot read " + kind + ": I/O error");
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) fail(path, kind + " is empty, expected a JSON object");
    return text;
}

json parse(const std::string& path, const std::string& text) {
    auto strip = [](std::string msg) {
        if (const size_t p = msg.find("] "); msg.rfind("[json.exception", 0) == 0 && p != std::string::npos)
            msg = msg.substr(p + 2);
        std::replace(msg.begin(), msg.end(), '\n', ' ');
        return msg;
    };
    try {
        return json::parse(text);
    } catch (const json::parse_error& e) {
        const std::string msg = strip(e.what());
        const bool truncated = e.byte > text.size() || msg.find("unexpected end of input") != std::string::npos;
        fail(path, std::string(truncated ? "truncated" : "malformed") + " JSON: " + msg + " (byte " +
                       std::to_string(e.byte) + ")");
    } catch (const json::out_of_range& e) {
        if (e.id == 406) fail(path, "a number overflows a double: " + truncate(strip(e.what()), 80));
        fail(path, "malformed JSON: " + strip(e.what()));
    } catch (const json::exception& e) {
        fail(path, "malformed JSON: " + strip(e.what()));
    }
}

const json& required(const std::string& path, const json& j, const std::string& where, const char* key,
                     const char* expected) {
    auto it = j.find(key);
    if (it == j.end()) fail(path, where + "required field \"" + key + "\" is missing, expected " + expected);
    return *it;
}

std::string get_file_name(const std::string& path, const json& j, const std::string& where, const char* key) {
    const json& v = required(path, j, where, key, "an image file name");
    if (!v.is_string() || v.get_ref<const std::string&>().empty())
        fail(path, where + "field \"" + key + "\" must be a non-empty string (a file name), found " + describe(v));
    const std::string& s = v.get_ref<const std::string&>();
    if (s.find('\0') != std::string::npos)
        fail(path, where + "field \"" + key + "\" must be a file name, found a string with a NUL character");
    return s;
}

std::vector<double> get_numbers(const std::string& path, const json& j, const std::string& where, const char* key,
                                size_t n, const char* expected) {
    const json& v = required(path, j, where, key, expected);
    bool ok = v.is_array() && v.size() == n;
    std::vector<double> out;
    if (ok) {
        for (const json& e : v) {
            if (!e.is_number() || !std::isfinite(e.get<double>())) {
                ok = false;
                break;
            }
            out.push_back(e.get<double>());
        }
    }
    if (!ok) fail(path, where + "field \"" + key + "\" must be " + expected + ", found " + describe(v));
    return out;
}

glm::dvec3 get_vec3(const std::string& path, const json& j, const std::string& where, const char* key) {
    const std::vector<double> v = get_numbers(path, j, where, key, 3, "an array of 3 finite numbers");
    return {v[0], v[1], v[2]};
}

std::string resolve(const std::string& manifest_path, const std::string& file) {
    const fs::path p(file);
    if (p.is_absolute()) return p.lexically_normal().string();
    return (fs::path(manifest_path).parent_path() / p).lexically_normal().string();
}

std::string relative_to_manifest(const std::string& manifest_path, const std::string& file) {
    const fs::path dir = fs::path(manifest_path).parent_path();
    const fs::path rel = fs::path(file).lexically_relative(dir.empty() ? fs::path(".") : dir);
    return rel.empty() ? file : rel.string();
}

}  // namespace rtm::manifest_json
