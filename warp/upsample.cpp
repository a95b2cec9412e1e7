#include "warp/upsample.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rtm {

namespace {

// Connectivity of two source texels (storage coordinates) that are 4-neighbours: the marks of
// mark_discontinuities, or always connected when the relief carries none.
bool connected(const ReliefTexture& t, int x0, int r0, int x1, int r1) {
    if (t.breaks.empty() || (x0 == x1 && r0 == r1)) return true;
    if (r0 == r1) return !(t.breaks[size_t(r0) * size_t(t.width) + size_t(std::min(x0, x1))] & kBreakRight);
    // Same column: kBreakUp is stored at the lower texel (the larger storage row).
    return !(t.breaks[size_t(std::max(r0, r1)) * size_t(t.width) + size_t(x0)] & kBreakUp);
}

// The lower source index and weight of the upper one for fine centre X (in fine texels) along an axis of n source
// texels: the fine centre sits at (X + 0.5) / factor - 0.5 source texel centres, clamped to [0, n - 1].
void axis(int X, int factor, int n, int& i0, int& i1, double& t, int& nearest) {
    const double s = std::clamp((X + 0.5) / factor - 0.5, 0.0, double(n - 1));
    i0 = std::min(int(std::floor(s)), n - 1);
    i1 = std::min(i0 + 1, n - 1);
    t = s - i0;
    nearest = t < 0.5 ? i0 : i1;
}

}  // namespace

ReliefTexture upsample(const ReliefTexture& src, int factor) {
    if (factor < 1)
        throw std::invalid_argument("output scale: expected a factor >= 1, found " + std::to_string(factor));
    if (factor == 1) return src;
    const long long fw = (long long)src.width * factor, fh = (long long)src.height * factor;
    if (fw * fh > (1ll << 28))
        throw std::invalid_argument("output scale " + std::to_string(factor) + ": " + std::to_string(src.width) + "x" +
                                    std::to_string(src.height) + " texels would become " + std::to_string(fw) + "x" +
                                    std::to_string(fh) + ", over 2^28 texels");
    ReliefTexture o;
    o.width = int(fw);
    o.height = int(fh);
    o.quant = src.quant;
    o.geometry = src.geometry;
    o.geometry.a = src.geometry.a / double(factor);
    o.geometry.b = src.geometry.b / double(factor);
    std::vector<ReliefTexel>& texels = o.texels.edit();
    std::vector<float>& displ = o.displacement.edit();
    texels.assign(size_t(fw) * size_t(fh), ReliefTexel{});
    displ.assign(size_t(fw) * size_t(fh), 0.0f);
    const int w = src.width, h = src.height;
    for (int J = 0; J < o.height; ++J) {  // fine v-rows, counted from the bottom like v
        int j0, j1, jn;
        double tv;
        axis(J, factor, h, j0, j1, tv, jn);
        // Source storage rows (counted from the top) of v-rows j0, j1 and the nearest.
        const int r0 = h - 1 - j0, r1 = h - 1 - j1, rn = h - 1 - jn;
        const int row = o.height - 1 - J;
        for (int X = 0; X < o.width; ++X) {
            int x0, x1, xn;
            double tu;
            axis(X, factor, w, x0, x1, tu, xn);
            if (src.empty_at(xn, rn)) continue;
            const size_t i = size_t(row) * size_t(o.width) + size_t(X);
            const bool all_connected = connected(src, x0, r0, x1, r0) && connected(src, x0, r1, x1, r1) &&
                                       connected(src, x0, r0, x0, r1) && connected(src, x1, r0, x1, r1);
            if (!all_connected) {
                texels[i] = src.texel(xn, rn);
                displ[i] = src.displ(xn, rn);
                continue;
            }
            const int xs[4] = {x0, x1, x0, x1}, rs[4] = {r0, r0, r1, r1};
            const double ws[4] = {(1 - tu) * (1 - tv), tu * (1 - tv), (1 - tu) * tv, tu * tv};
            double sw = 0, sr = 0, sg = 0, sb = 0, sd = 0;
            for (int k = 0; k < 4; ++k) {
                if (ws[k] == 0.0 || src.empty_at(xs[k], rs[k])) continue;
                const ReliefTexel& tx = src.texel(xs[k], rs[k]);
                sw += ws[k];
                sr += ws[k] * tx.r;
                sg += ws[k] * tx.g;
                sb += ws[k] * tx.b;
                sd += ws[k] * src.displ(xs[k], rs[k]);
            }
            // sw > 0: the nearest texel is non-empty and has the largest weight (>= 1/4).
            const double d = sd / sw;
            displ[i] = float(d);
            texels[i] = {uint8_t(std::lround(sr / sw)), uint8_t(std::lround(sg / sw)), uint8_t(std::lround(sb / sw)),
                         o.quant.encode(d)};
        }
    }
    if (!src.breaks.empty()) mark_discontinuities(o, src.discontinuity_threshold);
    return o;
}

}  // namespace rtm
