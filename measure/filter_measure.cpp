#include "measure/filter_measure.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "measure/compare.h"
#include "procedural/procedural_media.h"
#include "warp/timing.h"
#include "objects/relief_quad.h"

namespace rtm {

namespace {

double median_ms(const ReliefTexture& t, const PrewarpCoefficients& k, const PrewarpOptions& o, int repeat,
                 ImageRGBA8& out) {
    PrewarpWorkspace ws;
    prewarp(t, k, o, ws, out);  // warm-up
    std::vector<double> ms;
    for (int i = 0; i < repeat; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        prewarp(t, k, o, ws, out);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    return median(ms);
}

}  // namespace

std::vector<FilterMeasurement> measure_filters(const FilterMeasureOptions& opt) {
    std::vector<FilterMeasurement> rows;
    for (const std::string& name : opt.reliefs) {
        ReliefQuad quad(to_relief(make_procedural(name, opt.size)));
        const ReliefTexture& t = quad.relief();
        for (const CompareView& v : default_compare_views()) {
            const glm::dvec3 eye = compare_camera(quad, v, 512, 512).eye;
            const PrewarpCoefficients k = compute_coefficients(t.geometry, eye);
            PrewarpOptions base;
            base.keep_outliers = true;
            base.threads = opt.threads;
            const PrewarpExtent e = prewarp_extent(t, k, base);
            PrewarpTruthOptions to;
            to.samples = opt.samples;
            const ImageRGBA8 truth = prewarp_truth(t, eye, e, to);
            if (opt.on_image) opt.on_image(name, v.name, "truth", truth);
            for (Filter f : {Filter::point, Filter::coverage}) {
                FilterMeasurement m;
                m.relief = name;
                m.view = v.name;
                m.filter = to_string(f);
                PrewarpOptions o = base;
                o.filter = f;
                o.isa = Isa::generic;
                ImageRGBA8 out;
                m.ms = median_ms(t, k, o, opt.repeat, out);
                m.error = prewarp_error(out, truth, e);
                if (opt.on_image) opt.on_image(name, v.name, m.filter, out);
                o.isa = Isa::automatic;
                ImageRGBA8 fast_out;
                m.fast_ms = median_ms(t, k, o, opt.repeat, fast_out);
                rows.push_back(m);
                if (opt.progress) {
                    char line[256];
                    std::snprintf(line, sizeof line, "%s %s %-8s %7.3f ms  rmse %6.2f  coverage %.4f  IoU %.4f",
                                  name.c_str(), v.name.c_str(), m.filter.c_str(), m.ms, m.error.color_rmse,
                                  m.error.coverage_mae, m.error.iou);
                    opt.progress(line);
                }
            }
        }
    }
    return rows;
}

std::string filter_table_markdown(const std::vector<FilterMeasurement>& rows) {
    std::string s =
        "| relief | view | point ms (fast) | point ms | coverage ms | cost | point RMSE | coverage RMSE | "
        "point coverage err | coverage coverage err | point IoU | coverage IoU |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    char line[512];
    struct Sum {
        double fms = 0, pms = 0, cms = 0, prm = 0, crm = 0, pce = 0, cce = 0;
        int n = 0;
    };
    std::map<std::string, Sum> sums;
    for (size_t i = 0; i + 1 < rows.size(); i += 2) {
        const FilterMeasurement &p = rows[i], &c = rows[i + 1];
        std::snprintf(line, sizeof line,
                      "| %s | %s | %.3f | %.3f | %.3f | %.2fx | %.2f | %.2f | %.4f | %.4f | %.4f | %.4f |\n",
                      p.relief.c_str(), p.view.c_str(), p.fast_ms, p.ms, c.ms, c.ms / p.ms, p.error.color_rmse,
                      c.error.color_rmse, p.error.coverage_mae, c.error.coverage_mae, p.error.iou, c.error.iou);
        s += line;
        for (const std::string& key : {p.relief, std::string("all")}) {
            Sum& u = sums[key];
            u.fms += p.fast_ms;
            u.pms += p.ms;
            u.cms += c.ms;
            u.prm += p.error.color_rmse;
            u.crm += c.error.color_rmse;
            u.pce += p.error.coverage_mae;
            u.cce += c.error.coverage_mae;
            ++u.n;
        }
    }
    s += "\n| relief | mean point ms (fast) | mean point ms | mean coverage ms | point RMSE | coverage RMSE | "
         "point coverage err | coverage coverage err |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& [key, u] : sums) {
        std::snprintf(line, sizeof line, "| %s | %.3f | %.3f | %.3f | %.2f | %.2f | %.4f | %.4f |\n", key.c_str(),
                      u.fms / u.n, u.pms / u.n, u.cms / u.n, u.prm / u.n, u.crm / u.n, u.pce / u.n, u.cce / u.n);
        s += line;
    }
    return s;
}

}  // namespace rtm
