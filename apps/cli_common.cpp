#include "cli_common.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "texmap/image_io.h"

namespace rtm::cli {

glm::dvec3 parse_vec3(const std::string& text, const std::string& flag) {
    std::vector<double> v;
    std::stringstream ss(text);
    std::string item;
    bool ok = true;
    while (std::getline(ss, item, ',')) {
        try {
            size_t used = 0;
            const double x = std::stod(item, &used);
            while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) ++used;
            if (used != item.size() || !std::isfinite(x)) ok = false;
            v.push_back(x);
        } catch (const std::exception&) {
            ok = false;
        }
    }
    if (!ok || v.size() != 3 || (!text.empty() && text.back() == ','))
        throw UsageError(flag + ": expected X,Y,Z (three finite numbers separated by commas), found \"" + text + "\"");
    return {v[0], v[1], v[2]};
}

void parse_size(const std::string& text, const std::string& flag, int& w, int& h) {
    int a = 0, b = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &a, &x, &b, &extra) != 3 || (x != 'x' && x != 'X') || a <= 0 ||
        b <= 0 || a > 16384 || b > 16384)
        throw UsageError(flag + ": expected WxH with 1 <= W, H <= 16384, found \"" + text + "\"");
    w = a;
    h = b;
}

void CameraArgs::add_to(CLI::App& app, bool eye_required) {
    auto* e = app.add_option("--eye", eye, "Centre of projection X,Y,Z");
    auto* o = app.add_option("--orbit", orbit, "AZ,EL,D: azimuth about +y, elevation (degrees), distance in radii");
    e->excludes(o);
    if (eye_required) e->required();
    app.add_option("--look-at", look_at, "Point looked at X,Y,Z (default: centre of what is rendered)");
    app.add_option("--up", up, "Up vector X,Y,Z")->capture_default_str();
    app.add_option("--fov", fov, "Vertical field of view in degrees")->capture_default_str();
    app.add_option("--size", size, "Output size WxH")->capture_default_str();
}

Camera CameraArgs::resolve(const Bounds& bounds) const {
    Camera cam;
    parse_size(size, "--size", cam.width, cam.height);
    if (!(fov > 0.0 && fov < 180.0)) throw UsageError("--fov: expected degrees in (0, 180), found " + std::to_string(fov));
    cam.fov_deg = fov;
    const glm::dvec3 centre = bounds.centre();
    cam.look_at = look_at.empty() ? centre : parse_vec3(look_at, "--look-at");
    cam.up = parse_vec3(up, "--up");
    if (!eye.empty()) {
        cam.eye = parse_vec3(eye, "--eye");
    } else if (!orbit.empty()) {
        const glm::dvec3 o = parse_vec3(orbit, "--orbit");
        if (!(o.z > 0.0)) throw UsageError("--orbit: distance D must be > 0, found \"" + orbit + "\"");
        const double az = glm::radians(o.x), el = glm::radians(o.y);
        const double r = std::max(bounds.radius(), 1e-12) * o.z;
        cam.eye = centre + r * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
    } else {
        throw UsageError("a camera needs --eye X,Y,Z or --orbit AZ,EL,D");
    }
    if (std::string why = cam.validate(); !why.empty()) throw UsageError("camera: " + why);
    cam.fit_clip_planes(centre, std::max(bounds.radius(), 1e-12));
    return cam;
}

void write_json(const std::string& path, const nlohmann::json& j) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp);
        if (!f) throw IoError(path + ": cannot write");
        f << j.dump(2) << "\n";
        if (!f) {
            std::filesystem::remove(tmp);
            throw IoError(path + ": write failed");
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp);
        throw IoError(path + ": cannot write: " + ec.message());
    }
}

nlohmann::json timing_json(std::vector<double> ms) {
    if (ms.empty()) return {{"min", 0.0}, {"median", 0.0}, {"mean", 0.0}, {"count", 0}};
    std::sort(ms.begin(), ms.end());
    double sum = 0;
    for (double x : ms) sum += x;
    const size_t n = ms.size();
    const double median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
    return {{"min", ms.front()}, {"median", median}, {"mean", sum / double(n)}, {"max", ms.back()}, {"count", n}};
}

}  // namespace rtm::cli
