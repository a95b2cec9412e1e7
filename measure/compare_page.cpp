#include "measure/compare_page.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "formats/atomic_file.h"
#include "measure/compare_reading.h"
#include "measure/compare_results.h"
#include "measure/html_text.h"
#include "measure/prewarp_figures.h"
#include "measure/time_error_plot.h"

namespace rtm {

namespace {

// The page is well-formed XML as well as HTML (every element closed, attributes quoted, the scripts in CDATA), so
// a strict parser can check it.
constexpr const char* kStyle = R"(
body { font: 14px/1.45 system-ui, sans-serif; margin: 0 2em 4em; color: #222; max-width: 1400px; }
h1 { margin-top: 0.8em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
.meta { color: #555; } .note { color: #666; font-size: 13px; }
.plots { display: flex; flex-wrap: wrap; gap: 1.5em; }
.plot-block { flex: 0 0 auto; } .plot text { fill: #333; font-family: system-ui, sans-serif; }
.plot g.pt { cursor: pointer; } .plot g.pt:hover circle { stroke: #000; }
.tip { position: absolute; background: #ffffe8; border: 1px solid #999; padding: 2px 6px; font-size: 12px;
       pointer-events: none; max-width: 420px; }
table { border-collapse: collapse; font-size: 13px; }
th, td { border: 1px solid #ddd; padding: 2px 8px; } td.n { text-align: right; font-variant-numeric: tabular-nums; }
th { background: #f3f3f3; cursor: pointer; user-select: none; } th.sorted-up::after { content: " \25B2"; }
th.sorted-down::after { content: " \25BC"; } tr.front td { background: #fff7e0; }
.views { display: flex; flex-wrap: wrap; gap: 10px; align-items: flex-start; }
.cell { width: 140px; margin: 0; font-size: 12px; }
.cell img { width: 140px; display: block; background: #000; image-rendering: pixelated; margin-bottom: 2px; }
.cell.truth figcaption { font-weight: bold; }
details.view { margin: 0.4em 0; } details.view > summary { cursor: pointer; font-weight: 600; padding: 2px 0; }
details.view > summary .note { font-weight: normal; }
.steps { display: flex; flex-wrap: wrap; gap: 14px; } .step { margin: 0; width: 260px; font-size: 12px; }
.stack { position: relative; } .stack img { display: block; image-rendering: pixelated; background: #000; }
.stack svg.overlay { position: absolute; left: 0; top: 0; width: 100%; height: 100%; overflow: visible; }
#page-errors { color: #b00; }
)";

// Records script errors and pictures that fail to load (capturing, so it must come before the pictures).
constexpr const char* kHeadScript = R"(//<![CDATA[
window.pageErrors = [];
window.addEventListener('error', function (e) {
  var t = e.target;
  window.pageErrors.push(t && t.tagName ? 'cannot load ' + (t.getAttribute('src') || t.tagName) :
                         'script error: ' + e.message);
}, true);
//]]>)";

// After the load: the counts a headless browser reads back from <body>'s attributes (tests/cli/compare_page.sh);
// the plot's hover labels; sortable tables.
constexpr const char* kBodyScript = R"(//<![CDATA[
(function () {
  var body = document.body;
  window.addEventListener('load', function () {
    var imgs = document.images, ok = 0;
    for (var i = 0; i < imgs.length; i++) {
      if (imgs[i].complete && imgs[i].naturalWidth > 0) ok++;
      else window.pageErrors.push('not loaded: ' + imgs[i].getAttribute('src'));
    }
    var plots = document.querySelectorAll('svg.plot');
    var drawn = 0;
    for (var p = 0; p < plots.length; p++) if (plots[p].getBBox().width > 0) drawn++;
    body.setAttribute('data-images', String(imgs.length));
    body.setAttribute('data-images-loaded', String(ok));
    body.setAttribute('data-plots', String(plots.length));
    body.setAttribute('data-plots-drawn', String(drawn));
    body.setAttribute('data-plot-points', String(document.querySelectorAll('svg.plot g.pt').length));
    body.setAttribute('data-errors', String(window.pageErrors.length));
    document.getElementById('page-errors').textContent = window.pageErrors.join('\n');
    body.setAttribute('data-status', 'ready');
  });
  var tip = document.getElementById('tip');
  document.addEventListener('mousemove', function (e) {
    var g = e.target.closest ? e.target.closest('g.pt') : null;
    if (!g) { tip.hidden = true; return; }
    tip.textContent = g.getAttribute('data-label');
    tip.style.left = (e.pageX + 14) + 'px';
    tip.style.top = (e.pageY + 14) + 'px';
    tip.hidden = false;
  });
  function key(cell, numeric) {
    if (!numeric) return cell.textContent;
    var v = parseFloat(cell.getAttribute('data-value'));
    return isNaN(v) ? Infinity : v;
  }
  var tables = document.querySelectorAll('table.sortable');
  for (var t = 0; t < tables.length; t++) (function (table) {
    var heads = table.querySelectorAll('th');
    for (var h = 0; h < heads.length; h++) (function (th, col) {
      th.addEventListener('click', function () {
        var numeric = th.getAttribute('data-type') === 'number';
        var up = !th.classList.contains('sorted-up');
        for (var k = 0; k < heads.length; k++) heads[k].classList.remove('sorted-up', 'sorted-down');
        th.classList.add(up ? 'sorted-up' : 'sorted-down');
        var tbody = table.tBodies[0], rows = Array.prototype.slice.call(tbody.rows);
        rows.sort(function (a, b) {
          var x = key(a.cells[col], numeric), y = key(b.cells[col], numeric);
          var c = x < y ? -1 : x > y ? 1 : 0;
          return up ? c : -c;
        });
        for (var r = 0; r < rows.length; r++) tbody.appendChild(rows[r]);
      });
    })(heads[h], h);
  })(tables[t]);
})();
//]]>)";

std::string esc(const std::string& s) { return html_escape(s); }

std::string number_cell(double v, const std::string& shown) {
    return "<td class=\"n\" data-value=\"" + (std::isfinite(v) ? fixed(v, 6) : std::string("NaN")) + "\">" + shown +
           "</td>";
}

std::string header(const CompareResults& r) {
    std::string s = "<header><h1>" + esc(r.title.empty() ? "rtm compare" : r.title) + "</h1>\n<p class=\"meta\">";
    s += "The pre-warp of relief texture mapping (Oliveira, Bishop and McAllister, SIGGRAPH 2000) beside the "
         "per-pixel methods that followed it: each method at each setting renders the same views, timed in the same "
         "run and measured against the exact ray caster.";
    s += "</p>\n<p class=\"meta\">";
    std::vector<std::string> facts;
    if (r.image_width > 0)
        facts.push_back(std::to_string(r.image_width) + "x" + std::to_string(r.image_height) + " pixels");
    facts.push_back(std::to_string(r.sources.size()) + " source" + (r.sources.size() == 1 ? "" : "s"));
    facts.push_back(std::to_string(r.views.size()) + " views");
    facts.push_back(std::to_string(r.methods.size()) + " methods and settings");
    if (!r.machine.empty()) facts.push_back(r.machine);
    if (r.threads > 0) facts.push_back(std::to_string(r.threads) + " threads");
    if (r.quick) facts.push_back("quick run (--quick)");
    for (size_t i = 0; i < facts.size(); ++i) s += (i ? " &#183; " : "") + esc(facts[i]);
    s += "</p>\n<nav><a href=\"#reading\">Reading</a> &#183; <a href=\"#plots\">Time against error</a> &#183; "
         "<a href=\"#summary\">Summary</a> &#183; <a href=\"#views\">Views</a> &#183; <a href=\"#curved\">The "
         "curved bases</a> &#183; <a href=\"#steps\">The "
         "pre-warp step by step</a> &#183; <a href=\"results.csv\">results.csv</a> &#183; <a "
         "href=\"results.json\">results.json</a></nav></header>\n";
    return s;
}

std::string reading(const CompareResults& r) {
    std::string s = "<section id=\"reading\"><h2>Reading the figures</h2>\n";
    for (const std::string& p : compare_reading(r)) s += "<p>" + esc(p) + "</p>\n";
    s += "<p class=\"note\">Written by the program from the measured values in results.json (measure/"
         "compare_reading.cpp): the numbers are this run's; a dash is a missing value.</p>\n</section>\n";
    return s;
}

// The plot blocks of one base: over all sources (when the file has "all" rows of it) and per source. A curved
// base's blocks carry data-base="BASE" and their points are coloured by whether the quadrics are on.
std::string plot_blocks(const CompareResults& r, const std::string& base) {
    const bool curved = is_curved_base(base);
    std::string s;
    std::vector<std::pair<std::string, std::string>> blocks;  // source key, heading
    if (!r.summary_of("all", base).empty()) blocks.push_back({"all", "All sources"});
    for (const ResultSource& src : r.sources) blocks.push_back({src.name, src.name});
    int n = 0;
    for (const auto& [key, heading] : blocks) {
        std::vector<SummaryRow> rows = r.summary_of(key, base);
        if (rows.empty()) continue;
        if (curved)
            for (SummaryRow& x : rows)
                if (x.family != "truth")
                    x.family = x.setting.rfind("no-quadric-", 0) == 0 ? "no quadrics"
                               : x.setting.rfind("exact-", 0) == 0    ? "exact distance"
                                                                      : "quadrics";
        const TimeErrorPlot plot = time_error_plot(rows, (curved ? base + "-plot-" : "plot-") + std::to_string(n++));
        s += "<div class=\"plot-block\" data-source=\"" + esc(key) + "\"" +
             (curved ? " data-base=\"" + esc(base) + "\"" : "") + "><h3>" + esc(heading) + "</h3>\n" + plot.svg;
        if (!plot.left_out.empty()) {
            s += "<p class=\"note\">Not plotted (no time or no RMSE): ";
            for (size_t i = 0; i < plot.left_out.size(); ++i) s += (i ? ", " : "") + esc(plot.left_out[i]);
            s += ".</p>\n";
        }
        s += "</div>\n";
    }
    return s;
}

std::string plots(const CompareResults& r) {
    return "<section id=\"plots\"><h2>Run time against error</h2>\n<p>One point per method and setting: "
           "the median frame time over the views (log scale) against the mean RMSE over the views. Colour "
           "by family; the Pareto front (no method both faster and more accurate) is the dashed step line, "
           "its points ringed. Hover a point for its figures. The curved bases (quadric silhouettes on a cylinder and "
           "on a sphere patch) have truths of their own and plots of their own: <a href=\"#curved\">below</a>.</p>\n"
           "<div class=\"plots\">\n" +
           plot_blocks(r, "flat") + "</div>\n</section>\n";
}

std::string summary_table(const CompareResults& r) {
    std::string s =
        "<section id=\"summary\"><h2>Summary</h2>\n<p>Per source and method: median frame time over "
        "the views, mean PSNR, RMSE and IoU against the row's truth over the views; source \"all\" over "
        "every source. Click a heading to sort.</p>\n<table id=\"summary-table\" class=\"sortable\">"
        "<thead><tr><th>source</th><th>method</th><th>family</th><th>truth</th><th data-type=\"number\">ms</th>"
        "<th data-type=\"number\">PSNR dB</th><th data-type=\"number\">RMSE</th>"
        "<th data-type=\"number\">IoU</th><th>front</th></tr></thead>\n<tbody>\n";
    for (const SummaryRow& x : r.summary) {
        s += std::string("<tr") + (x.pareto ? " class=\"front\"" : "") + "><td>" + esc(x.source) + "</td><td>" +
             esc(x.method_id) + "</td><td>" + esc(x.family) + "</td><td>" + esc(x.truth) + "</td>" +
             number_cell(x.ms, significant(x.ms)) + number_cell(x.psnr, fixed(x.psnr, 2)) +
             number_cell(x.rmse, fixed(x.rmse, 2)) + number_cell(x.iou, fixed(x.iou, 4)) + "<td>" +
             (x.pareto ? "yes" : "") + "</td></tr>\n";
    }
    return s + "</tbody></table>\n</section>\n";
}

// A picture with, below it, its error heat map and its iteration-count map where given (hover names each).
std::string cell(const std::string& caption, const std::vector<std::string>& images, bool truth = false,
                 const std::string& against = "the ray caster") {
    const std::string kinds[] = {"the frame", "error heat map against " + against, "search iterations per pixel"};
    std::string s = std::string("<figure class=\"cell") + (truth ? " truth" : "") + "\">";
    for (size_t i = 0; i < images.size(); ++i)
        if (!images[i].empty())
            s += "<img src=\"" + esc(images[i]) + "\" alt=\"" + esc(images[i]) + "\" title=\"" +
                 esc(kinds[std::min<size_t>(i, 2)]) + "\"/>";
    return s + "<figcaption>" + caption + "</figcaption></figure>\n";
}

std::string row_caption(const ResultRow& row) {
    std::string s = "<b>" + esc(row.method_id) + "</b><br/>" + significant(row.ms) + " ms";
    if (const auto p = row.stages.find("prewarp"); p != row.stages.end())
        s += " (pre-warp " + significant(p->second) + ")";
    s += "<br/>PSNR " + fixed(row.psnr, 2) + " dB, IoU " + fixed(row.iou, 4);
    if (std::isfinite(row.silhouette_px)) s += "<br/>silhouette " + fixed(row.silhouette_px, 2) + " px";
    if (std::isfinite(row.iterations_mean)) s += "<br/>" + fixed(row.iterations_mean, 1) + " iterations/pixel";
    return s;
}

// The method ids of the rows of one base, in the methods' order (then any only the rows name).
std::vector<std::string> ids_of(const CompareResults& r, const std::string& base) {
    std::vector<std::string> ids;
    for (const ResultMethod& m : r.methods)
        if (base_name(m.base) == base) ids.push_back(m.id);
    for (const ResultRow& row : r.rows)
        if (base_name(row.base) == base && std::find(ids.begin(), ids.end(), row.method_id) == ids.end())
            ids.push_back(row.method_id);
    return ids;
}

// Per source and view, a collapsible grid (<details>, the first view of each source open, so that the long page
// opens on one grid per source): the named truths first, then every method id's picture that has a row.
std::string view_grids(const CompareResults& r, const std::vector<std::string>& ids,
                       const std::vector<const char*>& truth_names, const std::string& against) {
    std::string s;
    for (const ResultSource& src : r.sources) {
        std::string grids;
        bool first = true;
        for (const ResultView& v : r.views) {
            std::string cells;
            const auto ts = r.truths.find(src.name);
            if (ts != r.truths.end())
                if (const auto tv = ts->second.find(v.name); tv != ts->second.end())
                    for (const char* name : truth_names)
                        if (const auto img = tv->second.find(name); img != tv->second.end())
                            cells += cell(std::string("<b>") + name + "</b> (truth)", {img->second}, true);
            int n = 0;
            for (const std::string& id : ids)
                if (const ResultRow* row = r.row(src.name, v.name, id)) {
                    cells += cell(row_caption(*row), {row->image, row->heatmap, row->iterations_image}, false, against);
                    ++n;
                }
            if (n == 0) continue;
            grids += std::string("<details class=\"view\"") + (first ? " open=\"open\"" : "") + "><summary>" +
                     esc(v.name) + " <span class=\"note\">(azimuth " + fixed(v.azimuth, 0) + ", elevation " +
                     fixed(v.elevation, 0) + ": " + fixed(v.angle_from_normal(), 0) + " degrees from the normal; " +
                     std::to_string(n) + " methods)</span></summary>\n<div class=\"views\">\n" + cells +
                     "</div>\n</details>\n";
            first = false;
        }
        if (!grids.empty()) s += "<h3>" + esc(src.name) + "</h3>\n" + grids;
    }
    return s;
}

std::string views(const CompareResults& r) {
    return "<section id=\"views\"><h2>Views</h2>\n<p>Per source and view (click a view to open or close it): the "
           "truths first (the exact ray caster, the micro-polygon mesh), then every method; under each picture its "
           "error heat map against the ray caster and, for the searching methods, the per-pixel iteration "
           "count.</p>\n" +
           view_grids(r, ids_of(r, "flat"), {"raycast", "micromesh"}, "the ray caster") + "</section>\n";
}

// Relief mapping with quadric silhouettes on the curved bases: each base's own plot and front, and its pictures.
std::string curved_section(const CompareResults& r) {
    std::string s =
        "<section id=\"curved\"><h2>The curved bases: quadric silhouettes</h2>\n<p>Relief mapping with quadric "
        "silhouettes (Oliveira and Policarpo 2005) draws the relief bent over a curved patch "
        "(perpixel/curved_patch.h), so every row here is measured against the truth of that same curved surface, its "
        "micro-polygon mesh, never against the flat truths above; its points are kept out of the flat plot. A second "
        "truth (the same bent relief cast on the CPU) is a row measured against the mesh: how far the two truths "
        "agree. Beside each setting, the same shader without the quadrics "
        "(quadric-silhouettes:no-quadric-...): the original relief mapping on the curved mesh, whose silhouette is "
        "the mesh's. Same views, timing and error measures as above.</p>\n";
    struct Base {
        const char *name, *heading, *text;
    };
    const Base bases[] = {
        {"curved", "The cylinder patch",
         "The relief bent over a cylinder patch, measured against curved-micromesh (curved-raycast is the second "
         "truth), at each of relief mapping's settings. And the paper's exact ray-quadric distance "
         "(quadric-silhouettes:exact-..., its equation 6) beside the approximate one it uses (equation 7): equation 6 "
         "measures along the direction perpendicular to the ray, which on a flat base is the depth divided by the "
         "sine of the ray's angle from the normal, so it draws the relief too shallow and loses rays that equation 7 "
         "takes to the bottom."},
        {"sphere", "The sphere patch",
         "The relief bent over a sphere patch of the same radius (the paraboloid of the paper's Figure 7 (a): it "
         "curves along both axes, so the quadric is curved in both), measured against sphere-micromesh "
         "(sphere-raycast is the second truth), at relief mapping's default setting."},
    };
    bool any_curved = false;
    for (const Base& b : bases) {
        bool any = false;
        for (const ResultRow& row : r.rows) any |= row.base == b.name;
        any_curved |= any;
        if (!any) continue;
        s += "<h3 id=\"" + std::string(b.name) + "-base\">" + b.heading + "</h3>\n<p>" + b.text + "</p>\n";
        s += "<div class=\"plots\">\n" + plot_blocks(r, b.name) + "</div>\n";
        const std::string truth = curved_truth_id(b.name, "micromesh");
        s += view_grids(r, ids_of(r, b.name), {truth.c_str()}, "the curved micro-polygon mesh (" + truth + ")");
    }
    if (!any_curved)
        return s +
               "<p class=\"note\">Not part of this run (an object or a scene has no curved base).</p>\n</section>\n";
    return s + "</section>\n";
}

}  // namespace

std::string compare_page_html(const nlohmann::json& results, const std::string& steps_section) {
    const CompareResults r = parse_compare_results(results);
    std::string s = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"/><title>" +
                    esc(r.title.empty() ? "rtm compare" : r.title) + "</title>\n<style>" + kStyle +
                    "</style>\n<script>" + kHeadScript + "</script></head>\n<body data-status=\"loading\">\n";
    s += header(r) + reading(r) + plots(r) + summary_table(r) + views(r) + curved_section(r);
    s += steps_section.empty()
             ? "<section id=\"steps\"><h2>The pre-warp step by step</h2><p class=\"note\">Not part of this run.</p>"
               "</section>\n"
             : steps_section;
    s += "<div id=\"tip\" class=\"tip\" hidden=\"hidden\"></div>\n<pre id=\"page-errors\"></pre>\n<script>";
    s += kBodyScript;
    return s + "</script>\n</body></html>\n";
}

void write_compare_page(const ComparePageInput& input) {
    std::error_code ec;  // a folder that cannot be made shows as the IoError of the first file written into it
    std::filesystem::create_directories(input.out_dir, ec);
    std::string steps;
    if (input.steps_relief && input.steps_camera) {
        PrewarpFiguresInput f;
        f.relief = &input.steps_relief->relief();
        f.camera = *input.steps_camera;
        f.out_dir = input.out_dir;
        f.frame = input.steps_frame;
        steps = prewarp_figures(f);
    }
    write_text_atomically(input.out_dir + "/index.html", compare_page_html(input.results, steps));
}

}  // namespace rtm
