#include "measure/compare_reading.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "measure/html_text.h"

namespace rtm {

namespace {

double median_or_nan(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mean(const std::vector<double>& v) {
    if (v.empty()) return NAN;
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
}

std::string percent(double f) { return fixed(100.0 * f, 0) + "%"; }

std::string join(const std::vector<std::string>& parts) {
    std::string s;
    for (size_t i = 0; i < parts.size(); ++i) {
        if (i) s += i + 1 == parts.size() ? " and " : ", ";
        s += parts[i];
    }
    return s;
}

// The summary over all sources, or the only source's when there is no "all" row.
std::vector<SummaryRow> overall(const CompareResults& r) {
    std::vector<SummaryRow> all = r.summary_of("all");
    if (all.empty() && r.sources.size() == 1) all = r.summary_of(r.sources[0].name);
    return all;
}

std::string front_sentence(const CompareResults& r) {
    std::vector<SummaryRow> all = overall(r);
    std::vector<SummaryRow> front;
    for (const SummaryRow& s : all)
        if (s.pareto) front.push_back(s);
    if (all.empty()) return "The results hold no summary rows: there is no front to read.";
    if (front.empty()) return "No method is marked as on the run-time-against-RMSE Pareto front.";
    std::sort(front.begin(), front.end(), [](const SummaryRow& a, const SummaryRow& b) { return a.ms < b.ms; });
    std::vector<std::string> names;
    for (const SummaryRow& s : front)
        names.push_back(s.method_id + " (" + significant(s.ms) + " ms, RMSE " + fixed(s.rmse, 2) + ")");
    std::map<std::string, int> families;
    for (const SummaryRow& s : front) ++families[s.family.empty() ? "unnamed" : s.family];
    std::vector<std::string> fam;
    for (const auto& [f, n] : families) fam.push_back(std::to_string(n) + " " + f);
    return std::string("On the run-time-against-RMSE Pareto front") +
           (r.sources.size() > 1 ? " over all sources" : "") + " are " + std::to_string(front.size()) + " of " +
           std::to_string(all.size()) + " methods (" + join(fam) +
           "), from the fastest to the most accurate: " + join(names) +
           ". Every other method is dominated: a method on the front is at least as fast and at least as accurate.";
}

std::string prewarp_cost_sentence(const CompareResults& r) {
    std::vector<double> pre, up, tex, pre_ms, frame_ms;
    for (const ResultRow& row : r.rows) {
        if (row.family != "pre-warp" || !(row.ms > 0)) continue;
        const auto p = row.stages.find("prewarp");
        if (p == row.stages.end()) continue;
        pre.push_back(p->second / row.ms);
        pre_ms.push_back(p->second);
        frame_ms.push_back(row.ms);
        if (const auto u = row.stages.find("upload"); u != row.stages.end()) up.push_back(u->second / row.ms);
        if (const auto t = row.stages.find("texmap"); t != row.stages.end()) tex.push_back(t->second / row.ms);
    }
    std::string s;
    if (!pre.empty())
        s += "In the pre-warp methods' frames (" + std::to_string(pre.size()) + " rows), the pre-warp itself took a " +
             "median " + percent(median_or_nan(pre)) + " of the frame time (median " +
             significant(median_or_nan(pre_ms)) + " ms of " + significant(median_or_nan(frame_ms)) + " ms)" +
             (up.empty() ? "" : ", the upload into texture memory " + percent(median_or_nan(up))) +
             (tex.empty() ? "" : ", the texture-mapping draw " + percent(median_or_nan(tex))) + ". ";
    const std::vector<SummaryRow> all = overall(r);
    const SummaryRow* fastest_pre = nullptr;
    std::vector<const SummaryRow*> perpixel;
    for (const SummaryRow& x : all) {
        if (!(x.ms > 0)) continue;
        if (x.family == "pre-warp" && (!fastest_pre || x.ms < fastest_pre->ms)) fastest_pre = &x;
        if (x.family == "per-pixel") perpixel.push_back(&x);
    }
    if (fastest_pre && !perpixel.empty()) {
        auto by_ms = [](const SummaryRow* a, const SummaryRow* b) { return a->ms < b->ms; };
        const auto [lo, hi] = std::minmax_element(perpixel.begin(), perpixel.end(), by_ms);
        s += "The fastest pre-warp method, " + fastest_pre->method_id + ", took " + significant(fastest_pre->ms) +
             " ms per frame at RMSE " + fixed(fastest_pre->rmse, 2) + "; the per-pixel methods took from " +
             significant((*lo)->ms) + " ms (" + (*lo)->method_id + ") to " + significant((*hi)->ms) + " ms (" +
             (*hi)->method_id + ")";
        const SummaryRow* closest = nullptr;
        if (std::isfinite(fastest_pre->rmse))
            for (const SummaryRow* p : perpixel)
                if (std::isfinite(p->rmse) &&
                    (!closest || std::abs(p->rmse - fastest_pre->rmse) < std::abs(closest->rmse - fastest_pre->rmse)))
                    closest = p;
        if (closest)
            s += "; the per-pixel method closest in RMSE, " + closest->method_id + " (RMSE " + fixed(closest->rmse, 2) +
                 "), took " + significant(closest->ms) + " ms; the pre-warp's frame took " +
                 fixed(fastest_pre->ms / closest->ms, 2) + " times as long";
        s += ".";
        if (!r.machine.empty()) s += " All times come from this one run on " + r.machine + ".";
    }
    return s;
}

struct ViewPick {
    const ResultView* frontal = nullptr;
    const ResultView* grazing = nullptr;
};

ViewPick pick_views(const CompareResults& r) {
    ViewPick p;
    for (const ResultView& v : r.views) {
        if (!std::isfinite(v.angle_from_normal())) continue;
        if (!p.frontal || v.angle_from_normal() < p.frontal->angle_from_normal()) p.frontal = &v;
        if (!p.grazing || v.angle_from_normal() > p.grazing->angle_from_normal()) p.grazing = &v;
    }
    return p;
}

// Mean over sources of a row field for one view and method id (NaN values left out).
double view_mean(const CompareResults& r, const std::string& view, const std::string& id, double ResultRow::*field) {
    std::vector<double> v;
    for (const ResultRow& row : r.rows)
        if (row.view == view && row.method_id == id && std::isfinite(row.*field)) v.push_back(row.*field);
    return mean(v);
}

std::vector<std::string> compared_ids(const CompareResults& r) {
    std::vector<std::string> ids;
    for (const ResultMethod& m : r.methods)
        if (m.family != "truth" && !is_curved_base(m.base)) ids.push_back(m.id);
    if (ids.empty())
        for (const ResultRow& row : r.rows)
            if (row.family != "truth" && !row.curved() && std::find(ids.begin(), ids.end(), row.method_id) == ids.end())
                ids.push_back(row.method_id);
    return ids;
}

std::string grazing_sentence(const CompareResults& r) {
    const ViewPick p = pick_views(r);
    if (!p.frontal || p.frontal == p.grazing) return {};
    struct Drop {
        std::string id;
        double front, graze;
    };
    std::vector<Drop> drops;
    for (const std::string& id : compared_ids(r)) {
        const double a = view_mean(r, p.frontal->name, id, &ResultRow::psnr);
        const double b = view_mean(r, p.grazing->name, id, &ResultRow::psnr);
        if (std::isfinite(a) && std::isfinite(b)) drops.push_back({id, a, b});
    }
    if (drops.empty()) return {};
    std::sort(drops.begin(), drops.end(),
              [](const Drop& x, const Drop& y) { return x.front - x.graze > y.front - y.graze; });
    int fell = 0;
    for (const Drop& d : drops) fell += d.graze < d.front;
    auto say = [](const Drop& d) { return d.id + " (" + fixed(d.front, 1) + " to " + fixed(d.graze, 1) + " dB)"; };
    std::vector<std::string> worst;
    for (size_t i = 0; i < std::min<size_t>(3, drops.size()); ++i) worst.push_back(say(drops[i]));
    std::string s = "From the most frontal view, " + p.frontal->name + " (" + fixed(p.frontal->angle_from_normal(), 0) +
                    " degrees from the relief's normal), to the most grazing, " + p.grazing->name + " (" +
                    fixed(p.grazing->angle_from_normal(), 0) + " degrees), the PSNR against the ray caster falls for " +
                    std::to_string(fell) + " of " + std::to_string(drops.size()) +
                    " methods. The largest drops: " + join(worst);
    if (drops.size() > 3) s += "; the smallest: " + say(drops.back());
    return s + ".";
}

std::string silhouette_sentence(const CompareResults& r) {
    const ViewPick p = pick_views(r);
    if (!p.grazing) return {};
    struct Value {
        std::string id;
        double v;
    };
    std::vector<Value> iou, sil;
    for (const std::string& id : compared_ids(r)) {
        const double a = view_mean(r, p.grazing->name, id, &ResultRow::iou);
        const double b = view_mean(r, p.grazing->name, id, &ResultRow::silhouette_px);
        if (std::isfinite(a)) iou.push_back({id, a});
        if (std::isfinite(b)) sil.push_back({id, b});
    }
    auto less = [](const Value& x, const Value& y) { return x.v < y.v; };
    std::string s;
    if (iou.size() >= 2) {
        const auto [lo, hi] = std::minmax_element(iou.begin(), iou.end(), less);
        s += "At " + p.grazing->name + " the coverage IoU against the ray caster ranges from " + fixed(lo->v, 4) +
             " (" + lo->id + ") to " + fixed(hi->v, 4) + " (" + hi->id + ")";
    }
    if (sil.size() >= 2) {
        const auto [lo, hi] = std::minmax_element(sil.begin(), sil.end(), less);
        s += std::string(s.empty() ? "At " + p.grazing->name + " the" : "; the") + " silhouette lies on average from " +
             fixed(lo->v, 2) + " px (" + lo->id + ") to " + fixed(hi->v, 2) + " px (" + hi->id + ") from the truth's";
    }
    if (!s.empty()) s += ".";
    return s;
}

std::string iterations_sentence(const CompareResults& r) {
    std::map<std::string, std::vector<double>> per_id;
    std::map<std::string, std::string> method_of;
    for (const ResultRow& row : r.rows)
        if (std::isfinite(row.iterations_mean) && !row.curved()) {
            per_id[row.method_id].push_back(row.iterations_mean);
            method_of[row.method_id] = row.method;
        }
    if (per_id.empty()) return {};
    std::map<std::string, const SummaryRow*> summary;
    const std::vector<SummaryRow> all = overall(r);
    for (const SummaryRow& s : all) summary[s.method_id] = &s;
    std::vector<std::string> parts;
    for (const auto& [id, v] : per_id) {
        const auto it = summary.find(id);
        parts.push_back(id + " " + fixed(mean(v), 1) +
                        (it != summary.end() ? " at RMSE " + fixed(it->second->rmse, 2) : std::string()));
    }
    std::string s = "Search iterations per pixel (mean over views): " + join(parts) + ".";
    // Interval mapping's claim (Risser, Shah and Pattanaik 2006): fewer iterations than relief mapping at the same
    // error. Each interval-mapping setting against the relief-mapping setting closest in RMSE, if within 10%.
    std::vector<std::string> pairs;
    int holds = 0;
    for (const auto& [im, iv] : per_id) {
        if (method_of[im] != "interval-mapping" || !summary.count(im)) continue;
        const double e = summary[im]->rmse;
        std::string best;
        for (const auto& [rm, rv] : per_id) {
            if (method_of[rm] != "relief-mapping" || !summary.count(rm) || !std::isfinite(summary[rm]->rmse)) continue;
            if (best.empty() || std::abs(summary[rm]->rmse - e) < std::abs(summary[best]->rmse - e)) best = rm;
        }
        if (best.empty() || !std::isfinite(e) || std::abs(summary[best]->rmse - e) > 0.1 * std::max(e, 1e-9)) continue;
        const bool fewer = mean(iv) < mean(per_id[best]);
        holds += fewer;
        pairs.push_back(im + " " + fixed(mean(iv), 1) + " against " + best + " " + fixed(mean(per_id[best]), 1));
    }
    if (!pairs.empty())
        s += " At about the same RMSE (within 10%): " + join(pairs) + "; interval mapping needed fewer iterations in " +
             std::to_string(holds) + " of " + std::to_string(pairs.size()) + " such pairs.";
    return s;
}

// What the quadrics gain on a curved base ("curved": the cylinder patch, "sphere"): each quadric-silhouettes setting
// against the same setting without the quadrics ("no-quadric-" + setting), both measured against the base's curved
// micro-polygon mesh, over every source and view: the coverage IoU and the silhouette distance (where the quadrics
// act), the RMSE over the common pixels and the frame time; and the same at the most grazing view.
std::string curved_sentence(const CompareResults& r, const std::string& base) {
    struct Pair {
        std::string with, without;
    };
    std::vector<Pair> pairs;
    for (const ResultMethod& m : r.methods) {
        if (m.base != base || m.family == "truth" || m.setting.rfind("no-quadric-", 0) == 0) continue;
        for (const ResultMethod& b : r.methods)
            if (b.base == base && b.method == m.method && b.setting == "no-quadric-" + m.setting)
                pairs.push_back({m.id, b.id});
    }
    if (pairs.empty()) return {};
    auto mean_of = [&](const std::string& id, double ResultRow::*field, const std::string& view) {
        std::vector<double> v;
        for (const ResultRow& row : r.rows)
            if (row.method_id == id && (view.empty() || row.view == view) && std::isfinite(row.*field))
                v.push_back(row.*field);
        return mean(v);
    };
    auto median_ms = [&](const std::string& id) {
        std::vector<double> v;
        for (const ResultRow& row : r.rows)
            if (row.method_id == id && std::isfinite(row.ms)) v.push_back(row.ms);
        return median_or_nan(v);
    };
    std::vector<std::string> parts;
    int better_iou = 0, better_sil = 0, compared = 0;
    for (const Pair& p : pairs) {
        const double iq = mean_of(p.with, &ResultRow::iou, ""), ib = mean_of(p.without, &ResultRow::iou, "");
        const double sq = mean_of(p.with, &ResultRow::silhouette_px, "");
        const double sb = mean_of(p.without, &ResultRow::silhouette_px, "");
        const double rq = mean_of(p.with, &ResultRow::rmse, ""), rb = mean_of(p.without, &ResultRow::rmse, "");
        if (!std::isfinite(iq) || !std::isfinite(ib)) continue;
        ++compared;
        better_iou += iq > ib;
        better_sil += std::isfinite(sq) && std::isfinite(sb) && sq < sb;
        std::string part = p.with + " IoU " + fixed(iq, 4) + " against " + fixed(ib, 4);
        if (std::isfinite(sq) && std::isfinite(sb))
            part += ", silhouette " + fixed(sq, 2) + " against " + fixed(sb, 2) + " px";
        if (std::isfinite(rq) && std::isfinite(rb)) part += ", RMSE " + fixed(rq, 2) + " against " + fixed(rb, 2);
        const double tq = median_ms(p.with), tb = median_ms(p.without);
        if (tq > 0 && tb > 0) part += ", " + fixed(tq / tb, 2) + " times the frame time";
        parts.push_back(part);
    }
    if (parts.empty()) return {};
    std::string s = std::string("On the ") + (base == "sphere" ? "sphere" : "cylinder") +
                    " patch (the relief bent over " + (base == "sphere" ? "a sphere" : "a cylinder") +
                    ", every row measured against its curved micro-polygon mesh, " +
                    curved_truth_id(base, "micromesh") +
                    "), the quadrics against the same search without them (means over the sources and views): ";
    for (size_t i = 0; i < parts.size(); ++i) s += (i ? "; " : "") + parts[i];
    s += ". The quadrics raised the coverage IoU at " + std::to_string(better_iou) + " of " + std::to_string(compared) +
         " settings and brought the silhouette closer at " + std::to_string(better_sil) +
         (better_iou > 0 ? " (rays that leave the quadric shell are background: the relief's own outline instead of "
                           "the base mesh's)."
                         : ".");
    const ViewPick v = pick_views(r);
    if (v.grazing) {
        std::vector<std::string> at;
        for (const Pair& p : pairs) {
            const double iq = mean_of(p.with, &ResultRow::iou, v.grazing->name);
            const double ib = mean_of(p.without, &ResultRow::iou, v.grazing->name);
            if (std::isfinite(iq) && std::isfinite(ib))
                at.push_back(p.with + " " + fixed(iq, 4) + " against " + fixed(ib, 4));
        }
        if (!at.empty()) s += " At the most grazing view, " + v.grazing->name + ", the IoU: " + join(at) + ".";
    }
    // The paper's exact distance (equation 6) against the approximate one (equation 7) at the same steps.
    std::vector<std::string> exact;
    for (const ResultMethod& m : r.methods) {
        if (m.base != base || m.setting.rfind("exact-", 0) != 0) continue;
        for (const ResultMethod& b : r.methods) {
            if (b.base != base || b.method != m.method || b.setting != m.setting.substr(6)) continue;
            const double ie = mean_of(m.id, &ResultRow::iou, ""), ia = mean_of(b.id, &ResultRow::iou, "");
            const double re = mean_of(m.id, &ResultRow::rmse, ""), ra = mean_of(b.id, &ResultRow::rmse, "");
            if (!std::isfinite(ie) || !std::isfinite(ia)) continue;
            std::string part = m.id + " IoU " + fixed(ie, 4) + " against " + fixed(ia, 4) + " (" + b.id + ")";
            if (std::isfinite(re) && std::isfinite(ra)) part += ", RMSE " + fixed(re, 2) + " against " + fixed(ra, 2);
            const double te = median_ms(m.id), ta = median_ms(b.id);
            if (te > 0 && ta > 0) part += ", " + fixed(te / ta, 2) + " times the frame time";
            exact.push_back(part);
        }
    }
    if (!exact.empty())
        s += " The paper's exact ray-quadric distance (its equation 6) against the approximate one it uses (equation "
             "7): " +
             join(exact) +
             " (the paper reports the approximation twice as fast; equation 6 measures along the direction "
             "perpendicular to the ray, the depth divided by the sine of the ray's angle from the normal on a flat "
             "base, so it draws the relief too shallow: docs/PERPIXEL.md).";
    return s;
}

std::string missing_sentence(const CompareResults& r) {
    int psnr = 0, rmse = 0, iou = 0, ms = 0;
    for (const ResultRow& row : r.rows) {
        psnr += !std::isfinite(row.psnr);
        rmse += !std::isfinite(row.rmse);
        iou += !std::isfinite(row.iou);
        ms += !std::isfinite(row.ms);
    }
    if (!psnr && !rmse && !iou && !ms) return {};
    std::vector<std::string> parts;
    if (psnr) parts.push_back(std::to_string(psnr) + " without a PSNR (an image identical to the truth has none)");
    if (rmse) parts.push_back(std::to_string(rmse) + " without an RMSE");
    if (iou) parts.push_back(std::to_string(iou) + " without an IoU");
    if (ms) parts.push_back(std::to_string(ms) + " without a time");
    return "Of the " + std::to_string(r.rows.size()) + " rows, " + join(parts) +
           ": those values are left out of the figures above and shown as a dash.";
}

}  // namespace

std::vector<std::string> compare_reading(const CompareResults& r) {
    std::vector<std::string> out;
    for (std::string s :
         {front_sentence(r), prewarp_cost_sentence(r), grazing_sentence(r), silhouette_sentence(r),
          iterations_sentence(r), curved_sentence(r, "curved"), curved_sentence(r, "sphere"), missing_sentence(r)}) {
        while (!s.empty() && s.back() == ' ') s.pop_back();
        if (!s.empty()) out.push_back(std::move(s));
    }
    return out;
}

}  // namespace rtm
