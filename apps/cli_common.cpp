#include "cli_common.h"

#include "perpixel/curved_patch.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "formats/atomic_file.h"
#include "warp/upsample.h"
#include "procedural/procedural_media.h"
#include "texmap/camera_rig.h"
#include "warp/timing.h"
#include "formats/image_io.h"

namespace rtm::cli {

CLI::Validator non_negative_threshold() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            char* end = nullptr;  // strtod: a value that underflows (1e-320) is a small threshold, not an error
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || v < 0)
                return "expected a threshold >= 0 (world units), found \"" + text + "\"";
            return "";
        },
        "T >= 0");
}

bool parse_whole_number(const std::string& text, int& out, int max) {
    // Compared with the limit before any conversion to int (sscanf's %d wrapped 4294967297 to 1).
    if (text.empty() || text.size() > 10 ||
        !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return false;
    const long long v = std::stoll(text);
    if (v > max) return false;
    out = int(v);
    return true;
}

CLI::Validator whole_number() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            int v = 0;
            return parse_whole_number(text, v) ? ""
                                               : "expected a whole number (decimal digits), found \"" + text + "\"";
        },
        "");
}

std::string first_given(const CLI::App& app, std::initializer_list<const char*> flags) {
    for (const char* f : flags)
        if (app.count(f) > 0) return f;
    return "";
}

CLI::Validator frame_index() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            int v = 0;
            return parse_whole_number(text, v) ? "" : "expected a frame number K >= 0, found \"" + text + "\"";
        },
        "K >= 0");
}

CLI::Validator non_empty_list() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            return text.empty() ? "expected a comma-separated list, found an empty one" : "";
        },
        "LIST");
}

CLI::Option* add_threads_option(CLI::App& app, int& threads, const std::string& what) {
    return app.add_option("--threads", threads, what + " (0 = all; at most " + std::to_string(kMaxThreads) + ")")
        ->check(whole_number())
        ->check(CLI::Range(0, kMaxThreads))
        ->capture_default_str();
}

glm::dvec3 parse_vec3(const std::string& text, const std::string& flag) {
    std::vector<double> v;
    std::stringstream ss(text);
    std::string item;
    bool ok = true;
    while (std::getline(ss, item, ',')) {
        // strtod, not stod: stod refuses a number that underflows (1e-320, finite, read as a denormal or 0).
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(item.c_str(), &end);
        const bool overflow = errno == ERANGE && std::abs(x) > 1.0;
        while (*end != '\0' && std::isspace(static_cast<unsigned char>(*end))) ++end;
        if (end == item.c_str() || *end != '\0' || overflow || !std::isfinite(x)) ok = false;
        v.push_back(x);
    }
    if (!ok || v.size() != 3 || (!text.empty() && text.back() == ','))
        throw UsageError(flag + ": expected " + (flag == "--orbit" ? "AZ,EL,D" : "X,Y,Z") +
                         " (three finite numbers separated by commas), found \"" + text + "\"");
    return {v[0], v[1], v[2]};
}

void check_coordinates(const glm::dvec3& v, const std::string& what) {
    // Past this, squared lengths in the camera's own checks overflow and single-precision rendering has no digits
    // left for the scene (docs/DESIGN.md, "Input limits").
    constexpr double kMaxCoordinate = 1e30;
    if (std::abs(v.x) <= kMaxCoordinate && std::abs(v.y) <= kMaxCoordinate && std::abs(v.z) <= kMaxCoordinate) return;
    std::ostringstream os;
    os << what << v.x << "," << v.y << "," << v.z << " has a coordinate beyond +-1e30";
    throw UsageError(os.str());
}

int parse_level(const std::string& text) {
    if (text == "auto") return -1;
    int n = 0;
    if (!parse_whole_number(text, n, 30))
        throw UsageError("--level: expected N (0..30) or auto, found \"" + text + "\"");
    return n;
}

Isa parse_isa_arg(const std::string& text, const std::string& flag) {
    Isa isa;
    if (!parse_isa(text, isa))
        throw UsageError(flag + ": unknown target \"" + text + "\"; known: auto, " + isa_names());
    if (!isa_supported(isa)) {
        std::string have;
        for (Isa i : supported_isas()) have += std::string(have.empty() ? "" : ", ") + isa_name(i);
        throw UsageError(flag + ": this CPU cannot run target \"" + text + "\"; it runs: " + have);
    }
    check_isa_environment();  // RTM_ISA, which "auto" follows
    return isa;
}

void check_isa_environment() {
    try {
        default_isa();
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
}

void warn_isa_not_run(const std::string& asked, Isa ran, const PrewarpOptions& options) {
    if (asked == "auto" || ran == options.isa) return;
    std::fprintf(stderr, "rtm: warning: --isa %s: this pre-warp ran on the %s kernels (%s)\n", asked.c_str(),
                 isa_name(ran),
                 options.exact                     ? "--exact runs on the generic kernels"
                 : options.filter != Filter::point ? "the coverage filter runs on the generic kernels"
                                                   : "the fast kernels do not take this relief and view");
}

std::vector<Isa> parse_isa_list(const std::string& text, const std::string& flag) {
    std::vector<Isa> v;
    std::stringstream ss(text);
    for (std::string item; std::getline(ss, item, ',');) v.push_back(parse_isa_arg(item, flag));
    if (v.empty()) throw UsageError(flag + ": expected at least one target");
    return v;
}

Filter parse_filter(const std::string& text, Reconstruction method) {
    Filter f;
    if (text == "point")
        f = Filter::point;
    else if (text == "coverage")
        f = Filter::coverage;
    else
        throw UsageError("--filter: unknown filter \"" + text + "\"; known: point, coverage");
    if (f == Filter::coverage && method != Reconstruction::two_pass)
        throw UsageError("--filter coverage works with the two-pass reconstruction only, not " + to_string(method));
    return f;
}

std::vector<std::string> parse_relief_names(const std::string& text, const std::string& flag) {
    const std::vector<std::string> known = procedural_names();
    std::vector<std::string> out;
    std::stringstream ss(text);
    for (std::string item; std::getline(ss, item, ',');) {
        if (std::find(known.begin(), known.end(), item) == known.end())
            throw UsageError(flag + ": unknown relief \"" + item + "\"; known: " + procedural_names_list());
        out.push_back(item);
    }
    if (out.empty()) throw UsageError(flag + ": expected at least one relief name");
    return out;
}

void PerPixelArgs::add_to(CLI::App& app) {
    app.add_option("--curved-base", curved_base,
                   "quadric-silhouettes: the relief bent over a cylinder (default) or a sphere patch");
    app.add_option("--quadric-distance", quadric_distance,
                   "quadric-silhouettes: the paper's approximate ray-quadric distance (equation 7, default) or its "
                   "exact one (equation 6)");
    app.add_option("--steep-texture", steep_texture,
                   "protruded-displacement: colour steep slopes from this image (repeated), or 'builtin' (bricks)");
}

PerPixelSettings PerPixelArgs::settings() const {
    PerPixelSettings s;
    QuadricSilhouettesSettings& q = s.quadric_silhouettes;
    if (!curved_base.empty()) {
        const std::optional<CurvedShape> shape = parse_curved_shape(curved_base);
        if (!shape) throw UsageError("--curved-base: expected cylinder or sphere, found \"" + curved_base + "\"");
        q.set_base(*shape);
    }
    if (!quadric_distance.empty()) {
        if (quadric_distance != "approximate" && quadric_distance != "exact")
            throw UsageError("--quadric-distance: expected approximate or exact, found \"" + quadric_distance + "\"");
        q.exact_distance = quadric_distance == "exact";
    }
    s.protruded_displacement.steep_texture = !steep_texture.empty();
    return s;
}

std::optional<ImageRGBA8> PerPixelArgs::steep_image() const {
    if (steep_texture.empty() || steep_texture == "builtin") return std::nullopt;
    return read_rgba8(steep_texture);
}

void parse_size(const std::string& text, const std::string& flag, int& w, int& h) {
    // A whole number on each side of the 'x' (parse_whole_number: no sign, no space).
    const auto side = [](const std::string& digits, int& out) {
        return parse_whole_number(digits, out, 16384) && out >= 1;
    };
    const size_t x = text.find_first_of("xX");
    int a = 0, b = 0;
    if (x == std::string::npos || !side(text.substr(0, x), a) || !side(text.substr(x + 1), b))
        throw UsageError(flag + ": expected WxH with 1 <= W, H <= 16384, found \"" + text + "\"");
    w = a;
    h = b;
}

ReliefTexture apply_output_scale(ReliefTexture relief, int factor, const std::string& path) {
    if (factor < 1 || factor > 8)
        throw UsageError("--output-scale: expected a factor from 1 to 8, found " + std::to_string(factor));
    if (factor == 1) return relief;
    try {
        return upsample(relief, factor);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
}

void CameraArgs::add_to(CLI::App& app, bool eye_required) {
    auto* e = app.add_option("--eye", eye, "Centre of projection X,Y,Z");
    auto* o = app.add_option("--orbit", orbit, "AZ,EL,D: azimuth about +y, elevation (degrees), distance in radii");
    e->excludes(o);
    if (eye_required) e->required();
    const auto typed = [this](const char* flag) {
        return [this, flag](const std::string&) {
            if (view_flag.empty()) view_flag = flag;
        };
    };
    app.add_option("--look-at", look_at, "Point looked at X,Y,Z (default: centre of what is rendered)")
        ->each(typed("--look-at"));
    app.add_option("--up", up, "Up vector X,Y,Z")->capture_default_str()->each(typed("--up"));
    app.add_option("--fov", fov, "Vertical field of view in degrees")->capture_default_str()->each(typed("--fov"));
    app.add_option("--size", size, "Output size WxH")->capture_default_str();
}

Camera CameraArgs::resolve(const Bounds& bounds) const {
    Camera cam;
    parse_size(size, "--size", cam.width, cam.height);
    if (!(fov > 0.0 && fov < 180.0)) {
        std::ostringstream found;
        found << fov;  // shortest form: "0", "180", "nan" rather than "0.000000"
        throw UsageError("--fov: expected degrees in (0, 180), found " + found.str());
    }
    cam.fov_deg = fov;
    const glm::dvec3 centre = bounds.centre();
    cam.look_at = look_at.empty() ? centre : parse_vec3(look_at, "--look-at");
    cam.up = parse_vec3(up, "--up");
    if (!eye.empty()) {
        cam.eye = parse_vec3(eye, "--eye");
    } else if (!orbit.empty()) {
        const glm::dvec3 o = parse_vec3(orbit, "--orbit");
        if (!(o.z > 0.0)) throw UsageError("--orbit: distance D must be > 0, found \"" + orbit + "\"");
        cam.eye = orbit_eye(centre, bounds.radius(), {o.x, o.y, o.z});
    } else {
        throw UsageError("a camera needs --eye X,Y,Z or --orbit AZ,EL,D");
    }
    check_coordinates(cam.eye, std::string(eye.empty() ? "--orbit" : "--eye") + ": the eye ");
    check_coordinates(cam.look_at,
                      "--look-at: " +
                          std::string(look_at.empty() ? "the default, the centre of what is rendered, " : ""));
    check_coordinates(cam.up, "--up: ");
    // Camera::check() is the one judge of a usable camera; it names the setting, which names the flag.
    if (const CameraProblem p = cam.check(); p.field != CameraField::none) {
        const std::string eye_flag = eye.empty() ? "--orbit" : "--eye";
        std::string flag = "camera";
        switch (p.field) {
            case CameraField::eye: flag = eye_flag; break;
            case CameraField::look_at: flag = "--look-at"; break;
            case CameraField::eye_and_look_at: flag = eye_flag + (look_at.empty() ? "" : " and --look-at"); break;
            case CameraField::up:  // not given: the eye's flag made the view run along the default up
                flag = up == CameraArgs{}.up ? eye_flag + " (with the default --up " + up + "; give another --up)"
                                             : "--up";
                break;
            case CameraField::fov: flag = "--fov"; break;
            case CameraField::none:
            case CameraField::size:
            case CameraField::clip_planes: break;
        }
        throw UsageError(flag + ": " + p.message);
    }
    cam.fit_clip_planes(centre, std::max(bounds.radius(), 1e-12));
    return cam;
}

void check_output_file(const std::string& path, const std::string& flag) {
    namespace fs = std::filesystem;
    try {
        // Where the file will be written: a symbolic link is written through (formats/atomic_file.h), so its
        // target's folder is the one that must exist and take new files.
        const fs::path p(output_target(path));
        const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
        std::error_code ec;
        if (!fs::is_directory(dir, ec))
            throw IoError(path + ": cannot write: folder " + dir.string() + " does not exist");
        if (fs::is_directory(p, ec)) throw IoError(path + ": cannot write: it is a folder");
        // A temporary file as write_json makes one, created and removed: the folder takes new files.
        const AtomicFile probe(path);
        if (!std::ofstream(probe.temp_path())) throw IoError(path + ": cannot write in folder " + dir.string());
    } catch (const IoError& e) {
        throw IoError(flag + " " + e.what());
    }
}

void make_output_folder(const std::string& path, const std::string& flag) {
    namespace fs = std::filesystem;
    if (path.empty()) throw UsageError(flag + ": expected a folder, found an empty name");
    std::error_code ec;
    fs::create_directories(path, ec);
    if (ec || !fs::is_directory(path))
        throw IoError(flag + " " + path + ": cannot create the output folder" +
                      (ec                 ? ": " + ec.message()
                       : fs::exists(path) ? ": it exists and is not a folder"
                                          : ""));
}

void write_json(const std::string& path, const nlohmann::json& j) { write_text_atomically(path, j.dump(2) + "\n"); }

nlohmann::json timing_json(std::vector<double> ms) {
    if (ms.empty()) return {{"min", 0.0}, {"median", 0.0}, {"mean", 0.0}, {"count", 0}};
    std::sort(ms.begin(), ms.end());
    double sum = 0;
    for (double x : ms) sum += x;
    const size_t n = ms.size();
    return {
        {"min", ms.front()}, {"median", rtm::median(ms)}, {"mean", sum / double(n)}, {"max", ms.back()}, {"count", n}};
}

}  // namespace rtm::cli
