#include "measure/compare_sweep.h"

#include "perpixel/curved_patch.h"

namespace rtm {

namespace {

// One pre-warp setting. More pre-warp settings (an output scale, ...) go here: a field, and a line in the table.
struct PrewarpSetting {
    const char* name;
    Reconstruction reconstruction;
    bool exact;          // unquantized double-precision coordinates instead of the lookup tables
    bool side_polygons;  // keep the samples that leave the quad (the paper's section 3.3)
    int level;           // relief texture pyramid level
    Filter filter;
    bool quick;            // in the --quick sweep
    int output_scale = 1;  // pre-warp into a texture this many times the relief's size (docs/DESIGN.md)
};

// The paper's default (tables, side polygons, level 0, point filter) for both reconstructions, then one change
// each: the exact path, no side polygons, the next pyramid level, the coverage filter (two-pass only: the pipelined
// reconstruction has no coverage filter), the output scale 2 (two-pass; a relief only). Not the full product: each
// line answers one question (what the tables cost in error, what the side polygons add, ...).
const PrewarpSetting kPrewarpSettings[] = {
    {"tables", Reconstruction::two_pass, false, true, 0, Filter::point, true},
    {"exact", Reconstruction::two_pass, true, true, 0, Filter::point, true},
    {"no-sides", Reconstruction::two_pass, false, false, 0, Filter::point, false},
    {"level1", Reconstruction::two_pass, false, true, 1, Filter::point, false},
    {"coverage", Reconstruction::two_pass, false, true, 0, Filter::coverage, false},
    {"scale2", Reconstruction::two_pass, false, true, 0, Filter::point, false, 2},
    {"tables", Reconstruction::pipelined, false, true, 0, Filter::point, true},
    {"exact", Reconstruction::pipelined, true, true, 0, Filter::point, true},
    {"level1", Reconstruction::pipelined, false, true, 1, Filter::point, false},
};

CompareEntry entry(RenderMethod m, const std::string& setting, const std::string& family, nlohmann::json params) {
    CompareEntry e;
    e.method = to_string(m);
    e.setting = setting;
    e.id = setting.empty() ? e.method : e.method + ":" + setting;
    e.family = family;
    e.params = std::move(params);
    e.render.method = m;
    e.render.draw.skips = false;  // every frame does all the work: the times compare methods, not caches
    return e;
}

// A list of settings of which --quick keeps the first (the cheapest) and the one marked default.
template <class T>
struct Setting {
    T value;
    bool is_default;
};

template <class T>
std::vector<T> pick(const std::vector<Setting<T>>& all, bool quick) {
    std::vector<T> out;
    for (size_t i = 0; i < all.size(); ++i)
        if (!quick || i == 0 || all[i].is_default) out.push_back(all[i].value);
    return out;
}

// Appended piece by piece: `a + std::to_string(x)` inlined into the curved base's loop drew a false GCC 12
// -Wrestrict warning.
std::string steps(const char* a, int x, const char* b, int y) {
    std::string s = a;
    s += std::to_string(x);
    s += '-';
    s += b;
    s += std::to_string(y);
    return s;
}

}  // namespace

std::vector<CompareEntry> compare_sweep(bool quick) {
    std::vector<CompareEntry> out;
    out.push_back(entry(RenderMethod::flat, "", "conventional", nlohmann::json::object()));

    for (const PrewarpSetting& p : kPrewarpSettings) {
        if (quick && !p.quick) continue;
        const RenderMethod m = p.reconstruction == Reconstruction::two_pass ? RenderMethod::two_pass
                                                                            : RenderMethod::pipelined;
        CompareEntry e = entry(m, p.name, "pre-warp",
                               {{"reconstruction", to_string(p.reconstruction)},
                                {"lookup", p.exact ? "exact" : "tables"},
                                {"side_polygons", p.side_polygons},
                                {"level", p.level},
                                {"filter", to_string(p.filter)},
                                {"output_scale", p.output_scale}});
        e.output_scale = p.output_scale;
        e.render.prewarp.method = p.reconstruction;
        e.render.prewarp.exact = p.exact;
        e.render.prewarp.keep_outliers = p.side_polygons;
        e.render.prewarp.filter = p.filter;
        e.render.draw.level = p.level;
        out.push_back(e);
    }

    // Per-pixel methods: unlit colour (as the pre-warp), depth correction on (relief mapping's paper). The first
    // setting of each list is the cheapest; the default is the paper's recommendation (perpixel_method.h).
    const auto perpixel = [&](RenderMethod m, const std::string& setting, nlohmann::json params, const auto& set) {
        CompareEntry e = entry(m, setting, "per-pixel", std::move(params));
        set(e.render.perpixel);
        out.push_back(e);
    };
    perpixel(RenderMethod::parallax, "", {{"scale", 1.0}, {"bias", 0.0}}, [](PerPixelSettings&) {});
    perpixel(RenderMethod::parallax_offset_limiting, "", {{"scale", 1.0}, {"bias", 0.0}}, [](PerPixelSettings&) {});

    using MinMax = std::pair<int, int>;
    for (const MinMax& s :
         pick<MinMax>({{{4, 16}, false}, {{8, 32}, false}, {{10, 60}, true}, {{32, 128}, false}}, quick))
        perpixel(RenderMethod::steep_parallax, steps("n", s.first, "", s.second),
                 {{"min_steps", s.first}, {"max_steps", s.second}}, [&](PerPixelSettings& p) {
                     p.steep_parallax.min_steps = s.first;
                     p.steep_parallax.max_steps = s.second;
                 });
    for (const MinMax& s :
         pick<MinMax>({{{4, 16}, false}, {{8, 50}, true}, {{16, 100}, false}, {{32, 200}, false}}, quick))
        perpixel(RenderMethod::parallax_occlusion, steps("n", s.first, "", s.second),
                 {{"nMinSamples", s.first}, {"nMaxSamples", s.second}}, [&](PerPixelSettings& p) {
                     p.parallax_occlusion.nMinSamples = s.first;
                     p.parallax_occlusion.nMaxSamples = s.second;
                 });
    using LinBin = std::pair<int, int>;
    const std::vector<Setting<LinBin>> search = {{{8, 2}, false}, {{16, 4}, false}, {{32, 8}, true}, {{64, 16}, false}};
    for (const LinBin& s : pick(search, quick))
        perpixel(RenderMethod::relief_mapping, steps("l", s.first, "b", s.second),
                 {{"linear_search_steps", s.first}, {"binary_search_steps", s.second}}, [&](PerPixelSettings& p) {
                     p.relief_mapping.linear_search_steps = s.first;
                     p.relief_mapping.binary_search_steps = s.second;
                 });
    for (const LinBin& s :
         pick<LinBin>({{{8, 2}, false}, {{16, 5}, false}, {{32, 10}, true}, {{64, 20}, false}}, quick))
        perpixel(RenderMethod::interval_mapping, steps("l", s.first, "i", s.second),
                 {{"linear_search_steps", s.first}, {"max_iterations", s.second}, {"convergence_threshold", 0.01}},
                 [&](PerPixelSettings& p) {
                     p.interval_mapping.linear_search_steps = s.first;
                     p.interval_mapping.max_iterations = s.second;
                 });
    for (const LinBin& s : pick(search, quick))
        perpixel(RenderMethod::protruded_displacement, steps("l", s.first, "b", s.second),
                 {{"linear_search_steps", s.first}, {"binary_search_steps", s.second}}, [&](PerPixelSettings& p) {
                     p.protruded_displacement.linear_search_steps = s.first;
                     p.protruded_displacement.binary_search_steps = s.second;
                 });

    out.push_back(entry(RenderMethod::micromesh, "", "truth", nlohmann::json::object()));
    out.push_back(entry(RenderMethod::raycast, "", "truth", nlohmann::json::object()));

    // The curved base (Oliveira and Policarpo 2005): the quadric search at relief mapping's steps, each beside the
    // same shader with zero quadric coefficients ("no-quadric-", the paper's Figure 9, left), so that the pair at
    // one setting differs by the quadrics alone. The patch is the default one (angle 1.2, 32 x 4 quads).
    const QuadricSilhouettesSettings q;
    const auto patch_of = [](const QuadricSilhouettesSettings& p) {
        return nlohmann::json{{"shape", to_string(p.base)},
                              {"angle", p.angle},
                              {"segments", p.segments},
                              {"rows", p.rows}};
    };
    // One quadric-silhouettes entry on `base` with the patch and steps of `p`; `prefix` names it.
    const auto quadric_entry = [&](const std::string& base, const std::string& prefix,
                                   const QuadricSilhouettesSettings& p) {
        nlohmann::json params = {{"linear_search_steps", p.linear_search_steps},
                                 {"binary_search_steps", p.binary_search_steps},
                                 {"quadric", p.quadric}};
        if (p.exact_distance) params["exact_distance"] = true;
        params["patch"] = patch_of(p);
        CompareEntry e = entry(RenderMethod::quadric_silhouettes,
                               prefix + steps("l", p.linear_search_steps, "b", p.binary_search_steps), "per-pixel",
                               std::move(params));
        e.base = base;
        e.render.perpixel.quadric_silhouettes = p;
        return e;
    };
    // A curved base's truths: its micro-polygon mesh (the reference of its rows) and a CPU ray caster of the same
    // bent relief (measure/curved_raycast.h), a row measured against the mesh: how far the two truths agree.
    const auto truths_of = [&](const std::string& base, const QuadricSilhouettesSettings& p) {
        for (RenderMethod m : {RenderMethod::micromesh, RenderMethod::raycast}) {
            CompareEntry truth = entry(m, "", "truth", {{"patch", patch_of(p)}});
            truth.id = truth.method = curved_truth_id(base, to_string(m));
            truth.base = base;
            truth.render.perpixel.quadric_silhouettes = p;
            out.push_back(truth);
        }
    };
    for (bool quadric : {true, false})
        for (const LinBin& s : pick(search, quick)) {
            QuadricSilhouettesSettings p = q;
            p.linear_search_steps = s.first;
            p.binary_search_steps = s.second;
            p.quadric = quadric;
            out.push_back(quadric_entry("curved", quadric ? "" : "no-quadric-", p));
        }
    // The paper's exact ray-quadric distance (equation 6, perpixel/quadric_distance.h) at the default steps, beside
    // the approximate one it uses (equation 7): its Figure 11 and its claim of twice the speed for the approximation.
    {
        QuadricSilhouettesSettings p = q;
        p.exact_distance = true;
        out.push_back(quadric_entry("curved", "exact-", p));
    }
    truths_of("curved", q);

    // The sphere base (the paraboloid of the paper's Figure 7 (a)): the default steps with and without the quadrics,
    // in both sweeps; a sphere curves along both axes, so its mesh has as many rows as segments (as rtm render
    // --curved-base sphere draws it).
    QuadricSilhouettesSettings sphere = q;
    sphere.set_base(CurvedShape::sphere);
    for (bool quadric : {true, false}) {
        QuadricSilhouettesSettings p = sphere;
        p.quadric = quadric;
        out.push_back(quadric_entry("sphere", quadric ? "sphere-" : "no-quadric-sphere-", p));
    }
    truths_of("sphere", sphere);
    return out;
}

}  // namespace rtm
