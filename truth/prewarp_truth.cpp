#include "truth/prewarp_truth.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "truth/raycast.h"
#include "warp/task_arenas.h"

namespace rtm {

ImageRGBA8 prewarp_truth(const ReliefTexture& t, const glm::dvec3& eye, const PrewarpExtent& e,
                         const PrewarpTruthOptions& options) {
    if (options.samples < 1 || options.samples > 64)
        throw std::invalid_argument("prewarp_truth: samples per side must be 1..64, found " +
                                    std::to_string(options.samples));
    const int ow = t.width + e.left + e.right, oh = t.height + e.bottom + e.top;
    ImageRGBA8 out(ow, oh);
    const ReliefRaycaster caster(t);
    const ReliefGeometry& g = t.geometry;
    const int S = options.samples;
    std::atomic<int> rows_done{0};
    auto body = [&](int r0, int r1) {
        for (int row = r0; row < r1; ++row) {
            const double v0 = double(oh - 1 - row - e.bottom);
            for (int x = 0; x < ow; ++x) {
                const double u0 = double(x - e.left);
                double r = 0, gg = 0, b = 0;
                int hits = 0;
                for (int j = 0; j < S; ++j)
                    for (int i = 0; i < S; ++i) {
                        const double u = u0 + (i + 0.5) / S, v = v0 + (j + 0.5) / S;
                        const glm::dvec3 p = g.origin + g.a * u + g.b * v;
                        const ReliefRayHit hit = caster.cast(eye, p - eye);
                        if (!hit.hit) continue;
                        ++hits;
                        r += hit.color.r;
                        gg += hit.color.g;
                        b += hit.color.b;
                    }
                if (hits == 0) continue;
                auto ch = [&](double s) { return uint8_t(std::lround(s / hits)); };
                out.at(x, row) = {ch(r), ch(gg), ch(b), uint8_t(std::lround(255.0 * hits / (S * S)))};
            }
            rows_done.fetch_add(1, std::memory_order_relaxed);
        }
    };
    auto loop = [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, oh, 4),
                          [&](const tbb::blocked_range<int>& rg) { body(rg.begin(), rg.end()); });
    };
    if (options.progress) options.progress(0.0);
    if (options.threads > 0) {
        task_arena_for(options.threads).execute(loop);
    } else {
        loop();
    }
    if (options.progress) options.progress(1.0);
    return out;
}

PrewarpError prewarp_error(const ImageRGBA8& est, const ImageRGBA8& truth, const PrewarpExtent& e, int border) {
    if (est.width != truth.width || est.height != truth.height)
        throw std::invalid_argument("prewarp_error: sizes differ (" + std::to_string(est.width) + "x" +
                                    std::to_string(est.height) + " against " + std::to_string(truth.width) + "x" +
                                    std::to_string(truth.height) + ")");
    PrewarpError r;
    double se = 0, ae = 0;
    long long covered = 0, both = 0, either = 0;
    const int x0 = e.left + border, x1 = est.width - e.right - border;
    const int y0 = e.top + border, y1 = est.height - e.bottom - border;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const Rgba8 a = est.at(x, y), b = truth.at(x, y);
            if (a.a == 0 && b.a == 0) continue;
            ++covered;
            ae += std::abs(double(a.a) - double(b.a)) / 255.0;
            const bool ia = a.a >= 128, ib = b.a >= 128;
            either += ia || ib;
            both += ia && ib;
            if (!(ia && ib)) continue;
            const double dr = double(a.r) - b.r, dg = double(a.g) - b.g, db = double(a.b) - b.b;
            se += (dr * dr + dg * dg + db * db) / 3.0;
            ++r.pixels;
        }
    r.color_rmse = r.pixels ? std::sqrt(se / double(r.pixels)) : 0.0;
    r.coverage_mae = covered ? ae / double(covered) : 0.0;
    r.iou = either ? double(both) / double(either) : 1.0;
    return r;
}

}  // namespace rtm
