#include "measure/scene_bench.h"

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "objects/scene.h"
#include "texmap/gl_context.h"
#include "warp/timing.h"

namespace rtm {

namespace {

// CPU time of the process, all its threads, in milliseconds.
double process_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

std::string loadavg() {
    std::ifstream f("/proc/loadavg");
    std::string line;
    std::getline(f, line);
    return line;
}

SceneVariant variant(std::string name, std::string description) {
    SceneVariant v;
    v.name = std::move(name);
    v.description = std::move(description);
    v.draw.level = -1;
    return v;
}

// The frame loop before draw_quad_frame: level 0, one quad after another, a finish after each upload and draw.
SceneVariant old_loop(std::string name, std::string description, bool skips) {
    SceneVariant v = variant(std::move(name), std::move(description));
    v.draw.level = 0;
    v.draw.skips = skips;
    v.frame = {.concurrent = false, .finish_each = true};
    v.stride = skips ? 1 : 4;
    return v;
}

}  // namespace

std::vector<SceneVariant> scene_frame_variants() {
    std::vector<SceneVariant> v;
    v.push_back(variant("skips", "all skips, level per quad, concurrent pre-warps, one finish a frame"));
    v.push_back(variant("level by density", "as skips, the level by texel density alone (the rule before)"));
    v.back().draw.level_error_px = std::numeric_limits<double>::infinity();
    v.push_back(variant("no depth correction", "as skips, without depth correction: the fast pre-warp kernels"));
    v.back().depth_correction = false;
    v.push_back(variant("serial", "as skips, pre-warps one after another (each with all threads)"));
    v.back().frame.concurrent = false;
    v.push_back(variant("finish per quad", "as serial, and a finish after each quad's upload and draw"));
    v.back().frame = {.concurrent = false, .finish_each = true};
    v.push_back(variant("level 0", "as skips, every quad at pyramid level 0"));
    v.back().draw.level = 0;
    v.push_back(variant("micromesh whole",
                        "as skips, the micro-polygons of quads whose slab holds the eye uploaded and drawn whole "
                        "(not kept on the GPU by tiles)"));
    v.back().draw.micromesh_tiles = false;
    v.push_back(old_loop("skips, old loop", "level 0, serial pre-warps, a finish per quad (before this frame loop)",
                         true));
    v.push_back(variant("no skips", "every quad pre-warped and uploaded every frame, level per quad, concurrent"));
    v.back().draw.skips = false;
    v.back().stride = 4;
    v.push_back(old_loop("no skips, old loop", "no skips, level 0, serial pre-warps, a finish per quad", false));
    v.push_back(variant("floor", "each frame drawn again after its pre-warps: texture mapping and set-up only"));
    v.back().repeat = true;
    v.back().stride = 4;
    v.push_back(variant("floor, no depth correction", "as floor, without depth correction (no gl_FragDepth)"));
    v.back().depth_correction = false;
    v.back().repeat = true;
    v.back().stride = 4;
    return v;
}

std::vector<SceneVariant> select_scene_variants(const std::vector<SceneVariant>& all, const std::string& names) {
    std::vector<std::string> wanted;
    std::stringstream ss(names);
    for (std::string item; std::getline(ss, item, ';');)
        if (!item.empty()) wanted.push_back(item);
    std::vector<SceneVariant> v;
    for (const std::string& w : wanted) {
        bool known = false;
        for (const SceneVariant& a : all) known |= a.name == w;
        if (!known) {
            std::string list;
            for (const SceneVariant& a : all) list += (list.empty() ? "" : "; ") + a.name;
            throw std::invalid_argument("no scene variant \"" + w + "\" (variants: " + list + ")");
        }
    }
    for (const SceneVariant& a : all)
        if (std::find(wanted.begin(), wanted.end(), a.name) != wanted.end()) v.push_back(a);
    return v;
}

std::vector<SceneVariant> scene_skip_variants() {
    std::vector<SceneVariant> v;
    v.push_back(variant("all skips", "every skip on, level per quad"));
    v.push_back(variant("without outside-frustum, back-facing, offscreen-margins",
                        "hidden quads pre-warped (and drawn if in view), whole margins"));
    v.back().draw.cull = false;
    v.push_back(variant("without subpixel-parallax", "far quads pre-warped instead of drawn as plain textures"));
    v.back().draw.subpixel_parallax = 0.0;
    v.push_back(variant("without reuse-prewarp", "every drawn quad pre-warped every frame"));
    v.back().draw.reuse_tolerance = 0.0;
    // The reuse's stated tolerance (docs/SCENES.md, tests/objects/quad_frame_test.cpp): 0.1% of a frame's pixels.
    v.back().max_fraction_off = 0.001;
    v.push_back(variant("without partial-upload", "whole textures uploaded"));
    v.back().draw.partial_upload = false;
    v.back().max_fraction_off = 0.0;  // only pixels that cannot differ are left out of an upload: the same picture
    v.push_back(variant("without level per quad", "every quad at pyramid level 0"));
    v.back().draw.level = 0;
    v.push_back(variant("no skips", "every quad pre-warped and uploaded every frame, level 0"));
    v.back().draw.skips = false;
    v.back().draw.level = 0;
    v.back().stride = 4;
    return v;
}

namespace {

// One variant's state through the run: its own scene (the skips that keep state, such as reuse-prewarp, see the
// path in order), its cameras and its samples.
struct VariantRun {
    SceneVariant v;
    std::unique_ptr<Scene> scene;
    DrawOptions draw;
    int stride = 1;
    std::vector<Camera> cams;  // every stride-th frame of the path
    SceneBenchRow row;
    std::vector<double> pre, up, map, total, cpu;
    ImageRGBA8 image;  // the last frame drawn (for the picture check)
};

// Pixels of `a` and `b` whose largest channel difference exceeds `levels`.
long long pixels_off(const ImageRGBA8& a, const ImageRGBA8& b, int levels) {
    long long n = 0;
    for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
        const Rgba8 p = a.pixels[i], q = b.pixels[i];
        n += std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)}) > levels;
    }
    return n;
}

}  // namespace

SceneBench bench_scene(const std::string& scene_path, int width, int height, const std::vector<SceneVariant>& variants,
                       const std::function<void(const std::string&)>& progress, bool interleaved) {
    SceneBench b;
    b.interleaved = interleaved;
    b.scene = scene_path;
    b.width = width;
    b.height = height;
    b.load_before = loadavg();
    auto ctx = GlContext::create_offscreen(width, height, {.pin_llvmpipe_threads = true});
    b.gl_renderer = ctx->describe();
    Renderer renderer;
    Camera base;
    base.width = width;
    base.height = height;
    PrewarpOptions opt;
    opt.keep_outliers = true;  // side polygons, as rtm render --scene draws
    std::vector<VariantRun> runs;
    auto load = [&](VariantRun& r) {  // the variant's own scene, freshly loaded
        r.scene = std::make_unique<Scene>(Scene::load(scene_path));
        Scene& scene = *r.scene;
        const int n = scene.manifest().path_frames;
        if (scene.manifest().path_keys.empty()) throw std::runtime_error(scene_path + ": the scene has no camera_path");
        b.path_frames = n;
        b.quads = int(scene.quads().size());
        r.cams.clear();
        for (int k = 0; k < n; k += r.stride) r.cams.push_back(scene_path_camera(scene, k, base));
    };
    for (const SceneVariant& v : variants) {
        VariantRun r;
        r.v = v;
        r.draw = v.draw;
        r.draw.depth_correction = v.depth_correction;
        r.stride = std::max(1, v.stride);
        r.row.variant = v;
        runs.push_back(std::move(r));
    }
    auto frame = [&](VariantRun& r, const Camera& cam, bool timed) {
        SceneFrameReport rep;
        Scene& scene = *r.scene;
        if (r.v.repeat) scene.draw(renderer, cam, RenderMethod::two_pass, opt, r.draw, rep, r.v.frame);
        rep = {};
        const double cpu0 = process_cpu_ms();
        scene.draw(renderer, cam, RenderMethod::two_pass, opt, r.draw, rep, r.v.frame);
        (void)renderer.read_pixels(1, 1);  // as a frame that is shown or saved: the rendering is complete
        if (!timed) return;
        r.cpu.push_back(process_cpu_ms() - cpu0);
        r.image = renderer.read_pixels(width, height);  // for the picture check, after the frame's timing
        r.pre.push_back(rep.times.prewarp_ms);
        r.up.push_back(rep.times.upload_ms);
        r.map.push_back(rep.times.texture_map_ms);
        r.total.push_back(rep.times.total_ms);
        SceneBenchRow& row = r.row;
        row.drawn += rep.drawn;
        row.prewarped += rep.prewarped;
        row.texels += double(rep.texels_warped);
        for (const auto& [name, count] : rep.skips) row.skips[name] += count;
        for (size_t q = 0; q < rep.quad_levels.size(); ++q) {
            bool hidden = false;
            for (const std::string& s : rep.quad_skips[q]) hidden |= s == kSkipBackFacing || s == kSkipOutsideFrustum;
            if (!hidden) ++row.levels[rep.quad_levels[q]];
        }
    };
    // Warm-up: each variant's first two frames (textures allocated, pyramid levels built for the first views); the
    // timed pass then starts over from the first frame.
    auto warm_up = [&](VariantRun& r) {
        for (size_t k = 0; k < std::min<size_t>(2, r.cams.size()); ++k) frame(r, r.cams[k], false);
    };
    if (runs.empty()) return b;
    load(runs[0]);
    // The timed pass, interleaved: frame k of every variant (that draws it) before frame k + 1 of any, the variants'
    // order rotated by one each frame. Drift of the machine over the run (other jobs, the clock, the caches) then
    // falls on every variant alike, and no variant is always the first or the last of a frame. Run one after
    // another (--scene-sequential), the first variant of rtm bench-skips' quiet run of 2026-12-02 took 16.50 ms a
    // frame against 14.50 to 14.79 ms for the same work in later rows (docs/BENCHMARKS.md).
    const int n = b.path_frames;
    const size_t nv = runs.size();
    auto check = [&](SceneBenchRow& row, const ImageRGBA8& first, const ImageRGBA8& image) {
        const long long off = pixels_off(first, image, 8);
        row.pixels_off_max = std::max(row.pixels_off_max, off);
        row.frames_off += off > 0;
        ++row.frames_compared;
    };
    if (interleaved) {
        for (size_t i = 1; i < nv; ++i) load(runs[i]);
        for (VariantRun& r : runs) warm_up(r);
        for (int k = 0; k < n; ++k) {
            std::vector<bool> drew(nv, false);
            for (size_t j = 0; j < nv; ++j) {
                const size_t i = (j + size_t(k)) % nv;
                if (k % runs[i].stride != 0) continue;
                frame(runs[i], runs[i].cams[size_t(k / runs[i].stride)], true);
                drew[i] = true;
            }
            // The picture check: each variant's frame against the first variant's frame of the same camera.
            if (!drew[0]) continue;
            for (size_t i = 1; i < nv; ++i)
                if (drew[i]) check(runs[i].row, runs[0].image, runs[i].image);
        }
    } else {  // each variant's whole pass in turn (the first variant's frames kept for the picture check)
        std::vector<ImageRGBA8> first;
        for (size_t i = 0; i < nv; ++i) {
            if (i > 0) load(runs[i]);
            warm_up(runs[i]);
            for (int k = 0; k < n; k += runs[i].stride) {
                frame(runs[i], runs[i].cams[size_t(k / runs[i].stride)], true);
                if (i == 0)
                    first.push_back(std::move(runs[0].image));
                else if (k % runs[0].stride == 0)
                    check(runs[i].row, first[size_t(k / runs[0].stride)], runs[i].image);
            }
            runs[i].scene.reset();  // as each variant's scene was freed before the next one's was loaded
        }
    }
    for (VariantRun& r : runs) {
        SceneBenchRow& row = r.row;
        row.frames = int(r.total.size());
        row.prewarp_ms = median(r.pre);
        row.upload_ms = median(r.up);
        row.texture_map_ms = median(r.map);
        row.total_ms = median(r.total);
        row.cpu_ms = median(r.cpu);
        row.fps = 1000.0 / row.total_ms;
        row.drawn /= row.frames;
        row.prewarped /= row.frames;
        row.texels /= row.frames;
        row.ratio = b.rows.empty() ? 1.0 : row.total_ms / b.rows.front().total_ms;
        b.rows.push_back(row);
        if (progress) {
            char buf[256];
            std::snprintf(buf, sizeof buf,
                          "scene: %s: %d frames, median %.2f ms (%.0f fps), CPU %.2f ms, %.1f pre-warps a frame",
                          r.v.name.c_str(), row.frames, row.total_ms, row.fps, row.cpu_ms, row.prewarped);
            progress(buf);
        }
    }
    b.load_after = loadavg();
    return b;
}

std::string scene_picture_failures(const SceneBench& b) {
    std::string out;
    for (const SceneBenchRow& r : b.rows)
        if (r.variant.max_fraction_off >= 0 &&
            double(r.pixels_off_max) > r.variant.max_fraction_off * double(b.width) * double(b.height)) {
            char buf[512];
            std::snprintf(buf, sizeof buf,
                          "%s: variant \"%s\": %lld pixels of a %dx%d frame more than 8 levels off the first "
                          "variant's (at most %g%% allowed)\n",
                          b.scene.c_str(), r.variant.name.c_str(), r.pixels_off_max, b.width, b.height,
                          r.variant.max_fraction_off * 100.0);
            out += buf;
        }
    return out;
}

std::string scene_bench_markdown(const SceneBench& b) {
    std::ostringstream s;
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "Scene %s: %d relief quads, its %d-frame camera path at %dx%d (two-pass, side polygons, depth "
                  "correction).  \nOpenGL: %s  \nLoad average before: %s; after: %s\n\n",
                  b.scene.c_str(), b.quads, b.path_frames, b.width, b.height, b.gl_renderer.c_str(),
                  b.load_before.c_str(), b.load_after.c_str());
    s << buf;
    s << "Median milliseconds a frame over the frames drawn (stride: every k-th frame of the path, for variants that "
         "keep no state from frame to frame); x first: the median frame against the first row's, in this run. "
         "Pre-warp: the wall time of the frame's pre-warp step; upload and texture mapping: issuing the calls, and "
         "the frame's one finish (or each quad's) in texture mapping. CPU: the process's CPU time a frame (every "
         "thread, llvmpipe's included), the work a frame does whatever the load. "
      << (b.interleaved
              ? "The variants ran interleaved: frame k of each (their order rotated every frame) before frame "
                "k + 1 of any. "
              : "The variants ran one after another (--scene-sequential). ")
      << "Pixels off: the most pixels of a frame more than 8 levels off the first row's frame of the same camera "
         "(frames that differed at all / frames compared).\n\n";
    s << "| variant | frames | pre-warp | upload | texture mapping | frame | frames/s | x first | CPU ms | drawn | "
         "pre-warped | Mtexels warped | levels drawn | pixels off |\n";
    s << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n";
    for (const SceneBenchRow& r : b.rows) {
        std::string levels;
        for (const auto& [level, count] : r.levels)
            levels += (levels.empty() ? "" : ", ") + std::to_string(level) + ": " + std::to_string(count);
        const std::string off = &r == &b.rows.front()
                                    ? "-"
                                    : std::to_string(r.pixels_off_max) + " (" + std::to_string(r.frames_off) + "/" +
                                          std::to_string(r.frames_compared) + ")";
        std::snprintf(buf, sizeof buf,
                      "| %s | %d | %.2f | %.2f | %.2f | %.2f | %.1f | %.2f | %.2f | %.1f | %.1f | %.3f | %s | %s |\n",
                      r.variant.name.c_str(), r.frames, r.prewarp_ms, r.upload_ms, r.texture_map_ms, r.total_ms, r.fps,
                      r.ratio, r.cpu_ms, r.drawn, r.prewarped, r.texels / 1e6, levels.c_str(), off.c_str());
        s << buf;
    }
    s << "\n";
    for (const SceneBenchRow& r : b.rows) {
        std::string skips;
        for (const auto& [name, count] : r.skips)
            skips += (skips.empty() ? "" : ", ") + name + " " + std::to_string(count);
        s << "- " << r.variant.name << ": " << r.variant.description << (skips.empty() ? "" : "; fired: " + skips)
          << "\n";
    }
    return s.str();
}

nlohmann::json scene_bench_json(const SceneBench& b) {
    nlohmann::json rows = nlohmann::json::array();
    for (const SceneBenchRow& r : b.rows) {
        nlohmann::json levels = nlohmann::json::object();
        for (const auto& [level, count] : r.levels) levels[std::to_string(level)] = count;
        rows.push_back({{"variant", r.variant.name},
                        {"description", r.variant.description},
                        {"frames", r.frames},
                        {"stride", r.variant.stride},
                        {"prewarp_ms", r.prewarp_ms},
                        {"upload_ms", r.upload_ms},
                        {"texture_map_ms", r.texture_map_ms},
                        {"total_ms", r.total_ms},
                        {"fps", r.fps},
                        {"cpu_ms", r.cpu_ms},
                        {"ratio_to_first", r.ratio},
                        {"quads_drawn", r.drawn},
                        {"quads_prewarped", r.prewarped},
                        {"texels_warped", r.texels},
                        {"quads_skipped", r.skips},
                        {"quads_by_level", levels},
                        {"pixels_off_max", r.pixels_off_max},
                        {"frames_off", r.frames_off},
                        {"frames_compared", r.frames_compared},
                        {"max_fraction_off", r.variant.max_fraction_off}});
    }
    return {{"scene", b.scene},           {"size", {b.width, b.height}},  {"path_frames", b.path_frames},
            {"quads", b.quads},           {"gl_renderer", b.gl_renderer}, {"load_before", b.load_before},
            {"load_after", b.load_after}, {"interleaved", b.interleaved}, {"rows", rows}};
}

}  // namespace rtm
