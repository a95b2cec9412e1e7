// rtm bake: acquisition. From a mesh, six orthographic colour and depth views of its bounding box written as a
// six-face object (DIR/NAME.object.json, mesh/bake_object.h); from a height map, one relief texture
// (DIR/NAME.relief.json, formats/height_map.h). NAME is the input file's stem. docs/BAKE.md.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "cli_common.h"
#include "formats/height_map.h"
#include "formats/image_io.h"
#include "mesh/bake_object.h"
#include "mesh/bake_planes.h"
#include "mesh/triangle_mesh.h"
#include "texmap/gl_context.h"
#include "warp/timing.h"

namespace rtm::cli {

namespace {

struct BakeArgs {
    std::string mesh, planes, height, color, range, out;
    double texel = 0.0;
    int size = 256;
    bool texel_given = false, size_given = false;
};

// "MIN,MAX": two finite numbers, MIN <= MAX.
void parse_range(const std::string& text, double& lo, double& hi) {
    std::stringstream ss(text);
    std::string a, b, extra;
    bool ok = static_cast<bool>(std::getline(ss, a, ',')) && static_cast<bool>(std::getline(ss, b, ',')) &&
              !std::getline(ss, extra, ',');
    if (ok) {
        try {
            size_t ua = 0, ub = 0;
            lo = std::stod(a, &ua);
            hi = std::stod(b, &ub);
            ok = ua == a.size() && ub == b.size() && std::isfinite(lo) && std::isfinite(hi) && lo <= hi;
        } catch (const std::exception&) {
            ok = false;
        }
    }
    if (!ok) throw UsageError("--range: expected MIN,MAX (two finite numbers, MIN <= MAX), found \"" + text + "\"");
}

void bake_mesh(const BakeArgs& a) {
    if (a.size < 1 || a.size > 16384)
        throw UsageError("--size: expected N texels along the longest side, 1..16384, found " + std::to_string(a.size));
    if (!a.planes.empty() && a.size_given)
        throw UsageError("--size applies to the six-face bake; with --planes each plane gives its size");
    const auto start = Clock::now();
    const std::vector<BakePlane> planes = a.planes.empty() ? std::vector<BakePlane>{} : parse_bake_planes(a.planes);
    const TriangleMesh mesh = load_mesh(a.mesh);
    for (const std::string& w : mesh.warnings) std::fprintf(stderr, "rtm: warning: %s\n", w.c_str());
    const std::string name = std::filesystem::path(a.mesh).stem().string();
    if (!planes.empty()) {
        auto ctx = GlContext::create_offscreen(16, 16);
        for (const std::string& m : bake_planes(mesh, planes, a.out, name)) std::printf("%s\n", m.c_str());
        return;
    }
    std::vector<std::string> box_warnings;
    try {
        (void)bake_box(mesh.lo, mesh.hi, a.size, &box_warnings);  // refuse a point-sized mesh before any GL work
    } catch (const std::invalid_argument& e) {
        throw IoError(a.mesh + ": cannot bake: " + e.what());
    }
    bool shown = false;
    auto ctx = GlContext::create_offscreen(16, 16);
    const BakedObject obj = bake_object(mesh, a.size, [&](int done, int total) {
        // Progress only for bakes that take more than a second.
        if (ms_since(start) < 1000.0 && !shown) return;
        shown = true;
        // On a terminal one line updated in place; in a log one line each.
        std::fprintf(stderr, isatty(2) ? "\rbake: %d of %d faces" : "bake: %d of %d faces\n", done, total);
    });
    for (const std::string& w : obj.warnings) std::fprintf(stderr, "rtm: warning: %s: %s\n", a.mesh.c_str(), w.c_str());
    const std::string manifest = write_object(a.out, name, obj, std::filesystem::path(a.mesh).filename().string());
    if (shown && isatty(2)) std::fprintf(stderr, "\n");
    std::printf("%s\n", manifest.c_str());
}

void bake_height(const BakeArgs& a) {
    HeightBakeOptions o;
    if (a.size_given) {
        if (a.size < 1 || a.size > 16384)
            throw UsageError("--size: expected N texels along the longer side, 1..16384, found " +
                             std::to_string(a.size));
        o.size = a.size;
    }
    o.height_path = a.height;
    o.color_path = a.color;
    if (!a.range.empty()) {
        double lo = 0, hi = 0;
        parse_range(a.range, lo, hi);
        o.range_min = lo;
        o.range_max = hi;
    }
    if (a.texel_given) o.texel = a.texel;  // checked by bake_height_map, with the range it implies
    try {
        std::printf("%s\n", bake_height_map(o, a.out).c_str());
    } catch (const std::invalid_argument& e) {  // a bad --range, --texel or --size: a usage error
        throw UsageError(e.what());
    }
}

void run_bake(const BakeArgs& a) {
    if (a.mesh.empty() == a.height.empty()) throw UsageError("bake needs one of --mesh FILE and --height IMG");
    // A folder that cannot be one is refused before any work.
    if (std::error_code ec; std::filesystem::exists(a.out, ec) && !std::filesystem::is_directory(a.out, ec))
        throw IoError("--out " + a.out + ": exists and is not a folder");
    if (!a.mesh.empty()) {
        if (!a.color.empty() || !a.range.empty() || a.texel_given)
            throw UsageError("--color, --range and --texel apply to --height, not --mesh");
        bake_mesh(a);
    } else {
        if (!a.planes.empty()) throw UsageError("--planes applies to --mesh");
        bake_height(a);
    }
}

}  // namespace

void add_bake_command(CLI::App& app) {
    auto a = std::make_shared<BakeArgs>();
    CLI::App* sub = app.add_subcommand(
        "bake", "Bake a mesh into a six-face relief object, or a height map into a relief texture");
    sub->add_option("--mesh", a->mesh, "A mesh (any file assimp reads): writes DIR/NAME.object.json");
    sub->add_option("--planes", a->planes,
                    "Bake one relief texture per rectangle of P.json (docs/BAKE.md) instead of six faces");
    sub->add_option("--height", a->height, "A height map image: writes DIR/NAME.relief.json");
    sub->add_option("--color", a->color, "Colour image for --height (default: grey levels of the height)");
    sub->add_option("--range", a->range, "MIN,MAX world units the height's 0..1 map onto (default 0, width/10)");
    auto* texel = sub->add_option("--texel", a->texel, "World size of a height-map texel (default 1/width)");
    auto* size = sub->add_option("--size", a->size,
                                 "Texels along the longest side: the mesh box's (default 256), or the height map's "
                                 "(resampled; default: the map's own size)")
                     ->check(whole_number());
    sub->add_option("--out", a->out, "Output folder (created if missing)")->required();
    sub->callback([a, texel, size] {
        a->texel_given = texel->count() > 0;
        a->size_given = size->count() > 0;
        run_bake(*a);
    });
}

}  // namespace rtm::cli
