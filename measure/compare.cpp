#include "measure/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "formats/image_io.h"
#include "measure/pareto.h"
#include "measure/silhouette.h"
#include "texmap/camera_rig.h"
#include "texmap/gl_context.h"
#include "warp/timing.h"

namespace rtm {

CompareView orbit_view(double azimuth, double elevation, double distance) {
    char name[64];
    std::snprintf(name, sizeof name, "az%02d_el%02d", int(azimuth), int(elevation));
    return {name, azimuth, elevation, distance};
}

std::vector<CompareView> default_compare_views() {
    const double views[][2] = {{0, 0}, {15, 10}, {30, 15}, {45, 20}, {60, 10}, {70, 30}, {80, 5}, {85, 15}};
    std::vector<CompareView> out;
    for (const auto& v : views) out.push_back(orbit_view(v[0], v[1]));
    return out;
}

std::vector<CompareView> quick_compare_views() {
    const std::vector<CompareView> all = default_compare_views();
    return {all[0], all[3], all[6]};
}

Camera compare_camera(const Bounds& b, const CompareView& v, int width, int height) {
    return orbit_camera(b.centre(), b.radius(), {v.azimuth, v.elevation, v.distance}, width, height);
}

Camera compare_camera(const ReliefQuad& quad, const CompareView& v, int width, int height) {
    return compare_camera(relief_bounds(quad.relief()), v, width, height);
}

namespace {

// Timed frames of one entry: the median total and per-stage times.
struct Timed {
    ImageRGBA8 image;
    double ms = 0;
    StageTimes stages;
};

Timed render_timed(CompareSource& src, Renderer& renderer, const Camera& cam, const CompareEntry& e,
                   const CompareOptions& o) {
    RenderSettings s = e.render;
    s.prewarp.threads = o.threads;
    // The ray caster is the slow truth: one frame (its time is not a frame rate anyone would run at).
    const int frames = e.render.method == RenderMethod::raycast ? 1 : std::max(1, o.repeat) + 1;
    std::vector<double> total, pre, up, tex;
    Timed t;
    for (int i = 0; i < frames; ++i) {
        StageTimes st;
        t.image = e.curved() && e.family == "truth"
                      ? src.render_curved_truth(renderer, cam, e.render.method,
                                                e.render.perpixel.quadric_silhouettes.base,
                                                e.render.perpixel.quadric_silhouettes.angle, o.threads, st)
                      : src.render(renderer, cam, s, e.output_scale, st);
        if (frames > 1 && i == 0) continue;  // the first frame warms up (uploads, shader compiles, caches)
        total.push_back(st.total_ms);
        pre.push_back(st.prewarp_ms);
        up.push_back(st.upload_ms);
        tex.push_back(st.texture_map_ms);
    }
    t.ms = median(total);
    t.stages = {median(pre), median(up), median(tex), t.ms};
    return t;
}

// The mean of the iteration counts (grey level = count) over the pixels the colour frame covers.
double mean_iterations(const ImageRGBA8& counts, const ImageRGBA8& colour) {
    double sum = 0;
    long long n = 0;
    for (size_t i = 0; i < colour.pixels.size(); ++i)
        if (covered(colour.pixels[i])) {
            sum += counts.pixels[i].r;
            ++n;
        }
    return n ? sum / double(n) : kNoValue;
}

// File names keep ':' out (a relative URL "a:b.png" would read as a scheme): "two-pass:tables" -> "two-pass.tables".
std::string file_stem(const std::string& id) {
    std::string s = id;
    std::replace(s.begin(), s.end(), ':', '.');
    return s;
}

const CompareEntry* find_entry(const std::vector<CompareEntry>& m, RenderMethod method,
                               const std::string& base = "flat") {
    for (const CompareEntry& e : m)
        if (e.render.method == method && e.family == "truth" && e.base == base) return &e;
    return nullptr;
}

}  // namespace

CompareRun run_comparison(const std::vector<CompareSource*>& sources, const CompareOptions& o) {
    auto ctx = GlContext::create_offscreen(o.width, o.height, {.pin_llvmpipe_threads = true});
    Renderer renderer;
    CompareRun run;
    run.views = o.views;
    size_t total = 0, done = 0;
    for (const CompareEntry& e : o.methods) {
        bool any = false;
        for (CompareSource* src : sources)
            if (src->renders(e)) {
                any = true;
                total += o.views.size();
            }
        if (any) run.methods.push_back(&e);
    }
    // The truths render whether or not the sweep lists them (the errors need them); listed, they are rows too.
    const std::vector<CompareEntry> defaults = compare_sweep(true);
    const CompareEntry* mm_entry = find_entry(o.methods, RenderMethod::micromesh);
    const CompareEntry* rc_entry = find_entry(o.methods, RenderMethod::raycast);
    const CompareEntry& mm = mm_entry ? *mm_entry : *find_entry(defaults, RenderMethod::micromesh);
    const CompareEntry& rc = rc_entry ? *rc_entry : *find_entry(defaults, RenderMethod::raycast);
    // Each curved base's reference, its micro-polygon mesh.
    std::map<std::string, const CompareEntry*> curved_ref;
    for (const char* base : kCurvedBases) {
        const CompareEntry* listed = find_entry(o.methods, RenderMethod::micromesh, base);
        curved_ref[base] = listed ? listed : find_entry(defaults, RenderMethod::micromesh, base);
    }

    const auto save = [&](const std::string& rel, const ImageRGBA8& img) {
        if (o.out_dir.empty()) return std::string();
        write_rgba8(o.out_dir + "/" + rel, img);
        return rel;
    };
    for (CompareSource* src : sources) {
        for (const CompareView& v : o.views) {
            const Camera cam = compare_camera(src->bounds(), v, o.width, o.height);
            const std::string dir = "images/" + src->name + "/" + v.name + "/";
            if (!o.out_dir.empty()) {
                std::error_code ec;
                std::filesystem::create_directories(o.out_dir + "/" + dir, ec);
                if (ec) throw IoError(o.out_dir + "/" + dir + ": cannot create the folder: " + ec.message());
            }
            const Timed mesh = render_timed(*src, renderer, cam, mm, o);
            const bool has_rc = src->has_raycast();
            Timed ray;
            if (has_rc) ray = render_timed(*src, renderer, cam, rc, o);
            const ImageRGBA8& ref = has_rc ? ray.image : mesh.image;
            auto& truth = run.truths[src->name][v.name];
            truth["micromesh"] = save(dir + "micromesh.png", mesh.image);
            truth["raycast"] = has_rc ? save(dir + "raycast.png", ray.image) : std::string();
            // Each curved base's truth, when the source renders any entry of that base in the run.
            std::map<std::string, Timed> curved;
            for (const char* base : kCurvedBases) {
                const bool has = std::any_of(run.methods.begin(), run.methods.end(), [&](const CompareEntry* e) {
                    return e->base == base && src->renders(*e);
                });
                if (!has) continue;
                const CompareEntry& cm = *curved_ref.at(base);
                curved[base] = render_timed(*src, renderer, cam, cm, o);
                truth[cm.id] = save(dir + file_stem(cm.id) + ".png", curved[base].image);
            }

            for (const CompareEntry* e : run.methods) {
                if (!src->renders(*e)) continue;
                const bool is_mesh = e == &mm, is_ray = e == &rc;
                const bool is_curved_truth = e->curved() && e == curved_ref.at(e->base);
                const bool is_truth = is_mesh || is_ray || is_curved_truth;
                const Timed t = is_mesh           ? mesh
                                : is_ray          ? ray
                                : is_curved_truth ? curved.at(e->base)
                                                  : render_timed(*src, renderer, cam, *e, o);
                // A curved base is measured against its own curved mesh alone: the other truths render other
                // surfaces.
                const ImageRGBA8& truth_image = e->curved() ? curved.at(e->base).image : ref;
                const ImageRGBA8& mesh_image = e->curved() ? curved.at(e->base).image : mesh.image;
                CompareRow r;
                r.source = src->name;
                r.view = v.name;
                r.method_id = e->id;
                r.method = e->method;
                r.setting = e->setting;
                r.family = e->family;
                r.base = e->base;
                r.truth = e->curved() ? curved_ref.at(e->base)->id : has_rc ? rc.method : mm.method;
                r.ms = t.ms;
                if (e->family == "pre-warp") {
                    r.has_stages = true;
                    r.stages = t.stages;
                }
                ImageRGBA8 heat;
                r.error = diff_images(truth_image, t.image, &heat);
                r.vs_micromesh = diff_images(mesh_image, t.image);
                r.silhouette_px = silhouette_error(truth_image, t.image);
                if (is_truth) {
                    r.image = truth[is_curved_truth ? e->id : e->method];
                } else {
                    r.image = save(dir + file_stem(e->id) + ".png", t.image);
                }
                const bool is_reference = is_curved_truth || (!e->curved() && (has_rc ? is_ray : is_mesh));
                if (!is_reference) r.heatmap = save(dir + file_stem(e->id) + ".heat.png", heat);
                if (e->counts_iterations()) {
                    RenderSettings s = e->render;
                    s.perpixel.common.iteration_counts = true;
                    StageTimes ignored;
                    const ImageRGBA8 counts = src->render(renderer, cam, s, e->output_scale, ignored);
                    r.iterations_mean = mean_iterations(counts, t.image);
                    r.iterations_image = save(dir + file_stem(e->id) + ".iter.png", counts);
                }
                run.rows.push_back(std::move(r));
                if (o.on_progress) o.on_progress(++done, total, src->name + " " + v.name + " " + e->id);
            }
        }
    }
    return run;
}

namespace {

nlohmann::json num(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }
nlohmann::json path_or_null(const std::string& p) { return p.empty() ? nlohmann::json(nullptr) : nlohmann::json(p); }

nlohmann::json row_json(const CompareRow& r) {
    nlohmann::json stages = nlohmann::json::object();
    if (r.has_stages) {
        const StageTimes& s = r.stages;
        stages = {{"prewarp", num(s.prewarp_ms)},
                  {"upload", num(s.upload_ms)},
                  {"texmap", num(s.texture_map_ms)},
                  {"other", num(std::max(0.0, s.total_ms - s.prewarp_ms - s.upload_ms - s.texture_map_ms))}};
    }
    return {{"source", r.source},
            {"view", r.view},
            {"method_id", r.method_id},
            {"method", r.method},
            {"setting", r.setting},
            {"family", r.family},
            {"base", r.base},
            {"truth", r.truth},
            {"ms", num(r.ms)},
            {"stages", stages},
            {"psnr", num(r.error.psnr)},
            {"rmse", num(r.error.rmse)},
            {"iou", num(r.error.iou)},
            {"silhouette_px", num(r.silhouette_px)},
            {"psnr_vs_micromesh", num(r.vs_micromesh.psnr)},
            {"iou_vs_micromesh", num(r.vs_micromesh.iou)},
            {"iterations_mean", num(r.iterations_mean)},
            {"image", path_or_null(r.image)},
            {"heatmap", path_or_null(r.heatmap)},
            {"iterations_image", path_or_null(r.iterations_image)}};
}

double mean_finite(const std::vector<double>& v) {
    double s = 0;
    int n = 0;
    for (double x : v)
        if (std::isfinite(x)) {
            s += x;
            ++n;
        }
    return n ? s / n : kNoValue;
}

// Summary rows of `rows` (one per method id of base `base`, in `ids` order) under the name `source`, Pareto-marked
// among themselves: the flat and the curved base have different truths, so each has a front of its own.
std::vector<nlohmann::json> summarize(const std::string& source, const std::string& base,
                                      const std::vector<const CompareEntry*>& ids,
                                      const std::vector<const CompareRow*>& rows) {
    std::vector<nlohmann::json> out;
    std::vector<ParetoPoint> points;
    for (const CompareEntry* e : ids) {
        if (e->base != base) continue;
        std::vector<double> ms, psnr, rmse, iou;
        std::string truth;
        for (const CompareRow* r : rows)
            if (r->method_id == e->id) {
                ms.push_back(r->ms);
                psnr.push_back(r->error.psnr);
                rmse.push_back(r->error.rmse);
                iou.push_back(r->error.iou);
                truth = truth.empty() || truth == r->truth ? r->truth : "mixed";
            }
        if (ms.empty()) continue;
        const double m = median(ms), e_rmse = mean_finite(rmse);
        out.push_back({{"source", source},
                       {"method_id", e->id},
                       {"method", e->method},
                       {"setting", e->setting},
                       {"family", e->family},
                       {"base", e->base},
                       {"truth", truth},
                       {"ms", num(m)},
                       {"psnr", num(mean_finite(psnr))},
                       {"rmse", num(e_rmse)},
                       {"iou", num(mean_finite(iou))},
                       {"pareto", false}});
        points.push_back({m, e_rmse});
    }
    for (size_t i : pareto_front(points)) out[i]["pareto"] = true;
    return out;
}

}  // namespace

nlohmann::json comparison_json(const std::vector<CompareSource*>& sources, const CompareOptions& o,
                               const CompareRun& run, const nlohmann::json& meta) {
    nlohmann::json j = meta;
    j["image_size"] = {o.width, o.height};
    nlohmann::json src = nlohmann::json::array();
    for (const CompareSource* s : sources)
        src.push_back({{"name", s->name},
                       {"kind", s->kind},
                       {"path", s->path},
                       {"width", s->width},
                       {"height", s->height},
                       {"reference", s->has_raycast() ? "raycast" : "micromesh"}});
    j["sources"] = src;
    nlohmann::json views = nlohmann::json::array();
    for (const CompareView& v : run.views)
        views.push_back(
            {{"name", v.name}, {"azimuth", v.azimuth}, {"elevation", v.elevation}, {"distance", v.distance}});
    j["views"] = views;
    nlohmann::json methods = nlohmann::json::array();
    for (const CompareEntry* e : run.methods)
        methods.push_back({{"id", e->id},
                           {"method", e->method},
                           {"family", e->family},
                           {"setting", e->setting},
                           {"base", e->base},
                           {"params", e->params}});
    j["methods"] = methods;
    nlohmann::json truths = nlohmann::json::object();
    for (const auto& [s, per_view] : run.truths)
        for (const auto& [v, images] : per_view)
            for (const auto& [kind, path] : images) truths[s][v][kind] = path_or_null(path);
    j["truths"] = truths;
    nlohmann::json rows = nlohmann::json::array();
    for (const CompareRow& r : run.rows) rows.push_back(row_json(r));
    j["rows"] = rows;
    nlohmann::json summary = nlohmann::json::array();
    std::vector<const CompareRow*> all;
    for (const CompareRow& r : run.rows) all.push_back(&r);
    for (const CompareSource* s : sources) {
        std::vector<const CompareRow*> mine;
        for (const CompareRow* r : all)
            if (r->source == s->name) mine.push_back(r);
        for (const char* base : kCompareBases)
            for (nlohmann::json& x : summarize(s->name, base, run.methods, mine)) summary.push_back(std::move(x));
    }
    for (const char* base : kCompareBases)
        for (nlohmann::json& x : summarize("all", base, run.methods, all)) summary.push_back(std::move(x));
    j["summary"] = summary;
    return j;
}

namespace {

std::string csv_cell(const nlohmann::json& v) {
    if (v.is_null()) return "";
    if (v.is_number_float()) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.6g", v.get<double>());
        return buf;
    }
    if (v.is_number() || v.is_boolean()) return v.dump();
    std::string s = v.is_string() ? v.get<std::string>() : v.dump();
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace

std::string comparison_csv(const nlohmann::json& results) {
    const char* columns[] = {"source",
                             "view",
                             "method_id",
                             "method",
                             "setting",
                             "family",
                             "ms",
                             "stage_prewarp",
                             "stage_upload",
                             "stage_texmap",
                             "stage_other",
                             "psnr",
                             "rmse",
                             "iou",
                             "silhouette_px",
                             "psnr_vs_micromesh",
                             "iou_vs_micromesh",
                             "iterations_mean",
                             "image",
                             "heatmap",
                             "iterations_image",
                             "base",
                             "truth"};
    std::string s;
    for (const char* c : columns) {
        if (!s.empty()) s += ',';
        s += c;
    }
    s += "\n";
    for (const nlohmann::json& r : results.at("rows")) {
        std::string line;
        bool first = true;
        for (const std::string c : columns) {
            nlohmann::json v = nullptr;
            if (c.rfind("stage_", 0) == 0) {
                const std::string k = c.substr(6);
                if (r.at("stages").contains(k)) v = r.at("stages").at(k);
            } else if (r.contains(c)) {
                v = r.at(c);
            }
            if (!first) line += ',';
            line += csv_cell(v);
            first = false;
        }
        s += line + "\n";
    }
    return s;
}

std::string comparison_markdown(const nlohmann::json& results) {
    std::string s = "### " + results.value("title", std::string("rtm compare")) +
                    "\n\nMeans over the views of the error against the row's truth (raycast for a relief, "
                    "micromesh for an object or a scene, curved-micromesh and sphere-micromesh for the curved bases: "
                    "the relief bent over the cylinder and the sphere patch of quadric silhouettes): PSNR and RMSE "
                    "over the pixels covered in both, "
                    "coverage IoU; frame time: the median over the views of each view's median frame. Pareto: on the "
                    "run-time-against-RMSE front of its source and base. Every row per view: results.csv.\n\n"
                    "| source | method | setting | family | truth | frame ms | PSNR dB | RMSE | IoU | Pareto |\n"
                    "|---|---|---|---|---|---:|---:|---:|---:|:---:|\n";
    const auto f = [](const nlohmann::json& v, const char* fmt) {
        if (v.is_null()) return std::string("-");
        char buf[64];
        std::snprintf(buf, sizeof buf, fmt, v.get<double>());
        return std::string(buf);
    };
    for (const nlohmann::json& r : results.at("summary"))
        s += "| " + r.at("source").get<std::string>() + " | " + r.at("method").get<std::string>() + " | " +
             r.at("setting").get<std::string>() + " | " + r.at("family").get<std::string>() + " | " +
             r.value("truth", std::string()) + " | " + f(r.at("ms"), "%.2f") + " | " + f(r.at("psnr"), "%.2f") + " | " +
             f(r.at("rmse"), "%.2f") + " | " + f(r.at("iou"), "%.4f") + " | " +
             (r.at("pareto").get<bool>() ? "yes" : "") + " |\n";
    return s;
}

}  // namespace rtm
