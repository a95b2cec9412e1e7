// rtm compare: every method at every quality setting on one or more reliefs, an object or a scene, from views from
// frontal to grazing: time against error. Writes DIR/results.json, DIR/results.csv, DIR/compare.md, the pictures
// under DIR/images/ and the page DIR/index.html (docs/COMPARE.md). With --mesh: a baked mesh against the mesh
// (apps/cmd_compare_mesh.h).
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "cli_common.h"
#include "cmd_compare_mesh.h"
#include "formats/atomic_file.h"
#include "measure/bench.h"
#include "measure/compare.h"
#include "measure/compare_page.h"

namespace rtm::cli {

namespace {

struct CompareArgs {
    std::vector<std::string> reliefs;
    std::string object, scene, out, size;
    int repeat = -1, threads = 0;
    bool quick = false;
    CompareMeshArgs mesh;  // --mesh and its options
};

void run_compare(const CompareArgs& a) {
    check_isa_environment();
    const bool mesh = !a.mesh.mesh.empty();
    if (mesh) {
        if (!a.reliefs.empty() || !a.scene.empty() || a.quick || a.repeat != -1)
            throw UsageError(
                "--mesh takes --object, --texels, --discontinuity, --size, --threads and --no-images only");
        CompareMeshArgs m = a.mesh;
        m.object = a.object;
        m.out = a.out;
        m.threads = a.threads;
        if (!a.size.empty()) m.size = a.size;
        return run_compare_mesh(m);
    }
    if (a.mesh.texels_given || a.mesh.discontinuity != -1 || a.mesh.no_images)
        throw UsageError("--texels, --discontinuity and --no-images apply to --mesh");
    const int kinds = int(!a.reliefs.empty()) + int(!a.object.empty()) + int(!a.scene.empty());
    if (kinds != 1)
        throw UsageError(
            "compare needs one kind of source: --relief M (repeatable), --object O, --scene S or --mesh FILE");
    if (a.repeat != -1 && a.repeat < 1)
        throw UsageError("--repeat: expected N >= 1, found " + std::to_string(a.repeat));
    CompareOptions o;
    parse_size(a.size.empty() ? (a.quick ? "128x128" : "512x512") : a.size, "--size", o.width, o.height);
    o.repeat = a.repeat != -1 ? a.repeat : a.quick ? 1 : 3;
    o.threads = a.threads;
    o.views = a.quick ? quick_compare_views() : default_compare_views();
    o.methods = compare_sweep(a.quick);

    std::vector<std::unique_ptr<CompareSource>> owned;
    for (const std::string& r : a.reliefs) owned.push_back(load_relief_source(r));
    if (!a.object.empty()) owned.push_back(load_object_source(a.object));
    if (!a.scene.empty()) owned.push_back(load_scene_source(a.scene));
    std::set<std::string> names;  // unique names: they name the image folders and the rows
    std::vector<CompareSource*> sources;
    for (auto& s : owned) {
        // Letters, digits, '-' and '_' only: the name is a folder under --out (images/NAME/), and a manifest's
        // "name" such as "../../x" or "a/b" wrote pictures outside it.
        std::string base = s->name;
        for (char& c : base)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
        if (base.empty()) base = "source";
        s->name = base;
        for (int k = 2; names.count(s->name); ++k) s->name = base + "-" + std::to_string(k);
        names.insert(s->name);
        sources.push_back(s.get());
    }

    make_output_folder(a.out);
    check_output_file(a.out + "/results.json", "--out");
    o.out_dir = a.out;
    o.on_progress = [](size_t done, size_t total, const std::string& what) {
        std::fprintf(stderr, "compare %zu/%zu: %s\n", done, total, what.c_str());
    };
    const CompareRun run = run_comparison(sources, o);

    std::string title;
    for (const CompareSource* s : sources)
        title += (title.empty() ? "" : ", ") + s->name + " (" + std::to_string(s->width) + "x" +
                 std::to_string(s->height) + " texels)";
    title += ", " + std::to_string(o.width) + "x" + std::to_string(o.height) + " pixels";
    const nlohmann::json meta = {{"title", title},
                                 {"machine", machine_description()},
                                 {"threads", o.threads},
                                 {"quick", a.quick}};
    const nlohmann::json results = comparison_json(sources, o, run, meta);
    write_json(a.out + "/results.json", results);
    write_text_atomically(a.out + "/results.csv", comparison_csv(results));
    const std::string md = comparison_markdown(results);
    write_text_atomically(a.out + "/compare.md", md);

    ComparePageInput page;
    page.out_dir = a.out;
    page.results = results;
    for (CompareSource* s : sources)
        if (ReliefQuad* q = s->relief()) {  // the step-by-step section: the first relief, an oblique view
            page.steps_relief = q;
            page.steps_camera = compare_camera(*q, orbit_view(45, 20), o.width, o.height);
            break;
        }
    write_compare_page(page);
    std::printf("%s", md.c_str());
    std::fprintf(stderr, "compare: wrote %s, results.csv, results.json\n",
                 (std::filesystem::path(a.out) / "index.html").lexically_normal().string().c_str());
}

}  // namespace

void add_compare_command(CLI::App& app) {
    auto a = std::make_shared<CompareArgs>();
    CLI::App* sub = app.add_subcommand(
        "compare", "Every method at every setting from frontal to grazing views: time against error, a web page");
    sub->add_option("--relief", a->reliefs, "Relief texture manifest (repeat for several)");
    sub->add_option("--object", a->object, "Six-face object manifest (with --mesh: baked from it, instead of baking)");
    sub->add_option("--scene", a->scene, "Scene manifest");
    sub->add_option("--mesh", a->mesh.mesh,
                    "A mesh: bake it (or take --object) and compare the object with the mesh over 32 views");
    sub->add_option("--discontinuity", a->mesh.discontinuity,
                    "With --mesh: re-mark every face's discontinuities (world units, 0 = none); default: the "
                    "manifest's")
        ->check(non_negative_threshold());
    auto* texels = sub->add_option("--texels", a->mesh.texels, "With --mesh: bake texels along the box's longest side")
                       ->check(whole_number())
                       ->capture_default_str();
    sub->add_flag("--no-images", a->mesh.no_images, "With --mesh: only the table");
    sub->add_option("--out", a->out, "Output folder")->required();
    sub->add_flag("--quick", a->quick, "3 views, 2 settings per method, 1 timed frame, 128x128 pixels");
    sub->add_option("--size", a->size, "Image size WxH (default 512x512; --quick 128x128)");
    sub->add_option("--repeat", a->repeat, "Frames timed per method and view after a warm-up (default 3; --quick 1)")
        ->check(whole_number());
    add_threads_option(*sub, a->threads);
    sub->callback([a, texels] {
        a->mesh.texels_given = texels->count() > 0;
        run_compare(*a);
    });
}

}  // namespace rtm::cli
