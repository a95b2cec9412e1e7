#include "measure/time_error_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "measure/html_text.h"

namespace rtm {

std::string family_colour(const std::string& family) {
    if (family == "pre-warp") return "#e6550d";
    if (family == "per-pixel") return "#3182bd";
    if (family == "conventional") return "#636363";
    if (family == "truth") return "#31a354";
    // The curved base's plot (measure/compare_page.cpp) colours quadric silhouettes by whether the quadrics are on,
    // and the paper's exact distance apart.
    if (family == "quadrics") return "#9467bd";
    if (family == "no quadrics") return "#8c564b";
    if (family == "exact distance") return "#e377c2";
    return "#9467bd";
}

namespace {

std::string one_decimal(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

// A tick label: as few digits as the value needs (0.1, 0.2, 1, 20, 500).
std::string tick(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// The largest "nice" value (1, 2 or 5 times a power of ten) at or above v > 0.
double nice_ceiling(double v) {
    const double p = std::pow(10.0, std::floor(std::log10(v)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= v * (1 - 1e-12)) return m * p;
    return 10 * p;
}

}  // namespace

TimeErrorPlot time_error_plot(const std::vector<SummaryRow>& rows, const std::string& plot_id) {
    constexpr double W = 640, H = 400, left = 64, right = 16, top = 16, bottom = 48;
    TimeErrorPlot plot;
    std::vector<const SummaryRow*> pts;
    for (const SummaryRow& r : rows) {
        if (std::isfinite(r.ms) && r.ms > 0 && std::isfinite(r.rmse))
            pts.push_back(&r);
        else
            plot.left_out.push_back(r.method_id);
    }
    // Axes: whole decades of time around the points; RMSE from 0 to a nice value above the largest.
    double tmin = 1, tmax = 10, emax = 1;
    if (!pts.empty()) {
        tmin = tmax = pts[0]->ms;
        emax = 0;
        for (const SummaryRow* r : pts) {
            tmin = std::min(tmin, r->ms);
            tmax = std::max(tmax, r->ms);
            emax = std::max(emax, r->rmse);
        }
        emax = emax > 0 ? nice_ceiling(emax * 1.05) : 1.0;
    }
    const double d0 = std::floor(std::log10(tmin)), d1 = std::max(d0 + 1, std::ceil(std::log10(tmax)));
    auto X = [&](double ms) { return left + (std::log10(ms) - d0) / (d1 - d0) * (W - left - right); };
    auto Y = [&](double e) { return top + (1 - e / emax) * (H - top - bottom); };

    std::string s = "<svg id=\"" + html_escape(plot_id) +
                    "\" class=\"plot\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 640 400\" width=\"640\" "
                    "height=\"400\" role=\"img\" aria-label=\"frame time against RMSE\">\n";
    s += "<rect x=\"" + one_decimal(left) + "\" y=\"" + one_decimal(top) + "\" width=\"" +
         one_decimal(W - left - right) + "\" height=\"" + one_decimal(H - top - bottom) +
         "\" fill=\"#fff\" stroke=\"#888\"/>\n";
    // Time ticks: every decade labelled, 2 and 5 as light grid lines.
    for (double d = d0; d <= d1 + 1e-9; ++d)
        for (double m : {1.0, 2.0, 5.0}) {
            const double ms = m * std::pow(10.0, d);
            if (std::log10(ms) > d1 + 1e-9) break;
            const double x = X(ms);
            s += "<line x1=\"" + one_decimal(x) + "\" y1=\"" + one_decimal(top) + "\" x2=\"" + one_decimal(x) +
                 "\" y2=\"" + one_decimal(H - bottom) + "\" stroke=\"" + (m == 1.0 ? "#ccc" : "#eee") + "\"/>\n";
            s += "<text x=\"" + one_decimal(x) + "\" y=\"" + one_decimal(H - bottom + 16) +
                 "\" text-anchor=\"middle\" font-size=\"" + (m == 1.0 ? "12" : "10") + "\">" + tick(ms) + "</text>\n";
        }
    for (int i = 0; i <= 5; ++i) {
        const double e = emax * i / 5, y = Y(e);
        s += "<line x1=\"" + one_decimal(left) + "\" y1=\"" + one_decimal(y) + "\" x2=\"" + one_decimal(W - right) +
             "\" y2=\"" + one_decimal(y) + "\" stroke=\"#eee\"/>\n";
        s += "<text x=\"" + one_decimal(left - 6) + "\" y=\"" + one_decimal(y + 4) +
             "\" text-anchor=\"end\" font-size=\"11\">" + tick(e) + "</text>\n";
    }
    s += "<text x=\"" + one_decimal((left + W - right) / 2) + "\" y=\"" + one_decimal(H - 10) +
         "\" text-anchor=\"middle\" font-size=\"12\">median frame time (ms, log scale)</text>\n";
    s += "<text transform=\"translate(14 " + one_decimal((top + H - bottom) / 2) +
         ") rotate(-90)\" text-anchor=\"middle\" font-size=\"12\">RMSE against the ray caster (mean over "
         "views)</text>\n";

    // The Pareto front as a step line: faster points first; from each, across to the next one's time, then down
    // to its error (a slower point on the front is more accurate).
    std::vector<const SummaryRow*> front;
    for (const SummaryRow* r : pts)
        if (r->pareto) front.push_back(r);
    std::sort(front.begin(), front.end(), [](const SummaryRow* a, const SummaryRow* b) { return a->ms < b->ms; });
    if (!front.empty()) {
        std::string d = "M" + one_decimal(X(front[0]->ms)) + " " + one_decimal(Y(front[0]->rmse));
        for (size_t i = 1; i < front.size(); ++i)
            d += " H" + one_decimal(X(front[i]->ms)) + " V" + one_decimal(Y(front[i]->rmse));
        s += "<path class=\"front\" d=\"" + d +
             "\" fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\" "
             "stroke-dasharray=\"4 3\"/>\n";
    }
    for (const SummaryRow* r : pts) {
        const std::string label = r->method_id + " (" + r->family + "): " + significant(r->ms) + " ms, RMSE " +
                                  fixed(r->rmse, 2) + ", PSNR " + fixed(r->psnr, 2) + " dB, IoU " + fixed(r->iou, 4) +
                                  (r->pareto ? ", on the Pareto front" : "");
        const std::string cx = one_decimal(X(r->ms)), cy = one_decimal(Y(r->rmse));
        s += "<g class=\"pt\" data-id=\"" + html_escape(r->method_id) + "\" data-pareto=\"" +
             (r->pareto ? "true" : "false") + "\" data-label=\"" + html_escape(label) + "\">";
        if (r->pareto)
            s += "<circle class=\"front-mark\" cx=\"" + cx + "\" cy=\"" + cy +
                 "\" r=\"8\" fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\"/>";
        s += "<circle cx=\"" + cx + "\" cy=\"" + cy + "\" r=\"5\" fill=\"" + family_colour(r->family) +
             "\" stroke=\"#fff\"/><title>" + html_escape(label) + "</title></g>\n";
    }
    // Legend: the families present, then the front's marker.
    std::vector<std::string> families;
    for (const SummaryRow* r : pts)
        if (std::find(families.begin(), families.end(), r->family) == families.end()) families.push_back(r->family);
    double ly = top + 14;
    for (const std::string& f : families) {
        s += "<circle cx=\"" + one_decimal(W - right - 130) + "\" cy=\"" + one_decimal(ly - 4) + "\" r=\"5\" fill=\"" +
             family_colour(f) + "\"/><text x=\"" + one_decimal(W - right - 120) + "\" y=\"" + one_decimal(ly) +
             "\" font-size=\"12\">" + html_escape(f.empty() ? "(no family)" : f) + "</text>\n";
        ly += 16;
    }
    if (!front.empty())
        s += "<circle cx=\"" + one_decimal(W - right - 130) + "\" cy=\"" + one_decimal(ly - 4) +
             "\" r=\"7\" fill=\"none\" stroke=\"#000\"/><text x=\"" + one_decimal(W - right - 120) + "\" y=\"" +
             one_decimal(ly) + "\" font-size=\"12\">Pareto front</text>\n";
    s += "</svg>\n";
    plot.svg = std::move(s);
    return plot;
}

}  // namespace rtm
