// Copying runs of still texels (PrewarpOptions::copy_still_runs, paper section 5: zero-displacement texels do not
// move, so the brick wall pre-warps much faster when they skip the warp arithmetic). The copy must be invisible:
// the same pixels, bit for bit, with it on and off, over bricks-like reliefs, both reconstructions, the exact and
// the lookup-table paths, margins, discontinuity marks and epipoles anywhere. The seed is printed on failure;
// RTM_SEED overrides it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "test_util.h"
#include "warp/line_warp.h"
#include "warp/prewarp.h"
#include "warp/tables.h"

namespace rtm {
namespace {

double hash01(int x, int y, uint32_t s) {
    uint32_t h = uint32_t(x) * 0x9E3779B1u ^ (uint32_t(y) * 0x85EBCA77u + s * 0x27d4eb2du);
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return double(h >> 8) / 16777216.0;
}

struct Case {
    ReliefTexture relief;
    glm::dvec3 eye;
    PrewarpOptions options;
    bool with_displ = false;
    std::string describe;
};

// A brick wall: bricks at zero displacement (runs of still texels), mortar recessed; optionally raised studs on
// some bricks, bricks at a tiny displacement that quantizes to the zero level (still for the tables, not for
// --exact), a range in which zero is no quantization level, and empty texels.
Case random_case(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto pick = [&](int n) { return int(rng() % uint64_t(n)); };
    int w, h;
    switch (pick(6)) {
        case 0:
            w = 1 + pick(3);
            h = 1 + pick(40);
            break;
        case 1:
            w = 1 + pick(40);
            h = 1 + pick(3);
            break;
        case 2:
            w = 60 + pick(60);
            h = 60 + pick(60);
            break;
        default:
            w = 2 + pick(50);
            h = 2 + pick(50);
            break;
    }
    const ReliefGeometry g = test::random_geometry(rng);
    const double size = std::max(glm::length(g.a) * w, glm::length(g.b) * h);
    const double amp = size * (0.02 + U(rng) * (pick(3) == 0 ? 0.8 : 0.15));
    const uint32_t salt = uint32_t(rng());
    const int bw = 3 + pick(10), bh = 2 + pick(5);  // brick size with its mortar line
    const int kind = pick(5);
    auto mortar = [&](int x, int r) {
        const int row = r / bh;
        return r % bh == 0 || (x + (row % 2) * (bw / 2)) % bw == 0;
    };
    double lo = -amp, hi = 0.0;
    if (kind == 1 || kind == 3) hi = amp * 0.5;
    if (kind == 2) hi = amp * (0.137 + U(rng));  // zero is (most likely) no level: min + q*qs != 0
    auto displ = [&](int x, int r) -> double {
        if (mortar(x, r)) return -amp * (0.3 + 0.7 * hash01(x, r, salt));
        switch (kind) {
            case 1: return hash01(x / bw, r / bh, salt) < 0.3 ? amp * 0.5 * hash01(x, r, salt + 1) : 0.0;  // studs
            case 3: return amp * 1e-7;  // quantizes to the zero level (qs/2 >> amp*1e-7) but is not 0.0
            default: return 0.0;
        }
    };
    Case c{test::make_test_relief(w, h, lo, hi, displ, g), {}, {}, false, {}};
    const int empties = pick(4);
    if (empties == 1)
        for (size_t i = 0; i < c.relief.texels.size(); i += 7) c.relief.texels.edit()[i].q = kEmptyIndex;
    if (empties == 2)
        for (size_t i = 0; i < c.relief.texels.size(); ++i)
            if (hash01(int(i), 3, salt) < 0.2) c.relief.texels.edit()[i].q = kEmptyIndex;
    const int marks = pick(3);
    if (marks > 0) mark_discontinuities(c.relief, amp * (marks == 1 ? 0.05 : 0.6));

    double eu = U(rng) * 3 * w - w, ev = U(rng) * 3 * h - h;
    std::string where = "anywhere";
    switch (pick(5)) {
        case 0:
            eu = std::floor(eu) + 0.5;
            ev = std::floor(ev) + 0.5;
            where = "over a texel centre";
            break;
        case 1:
            eu = std::floor(eu);
            ev = std::floor(ev);
            where = "on texel boundaries";
            break;
        case 2:
            eu = U(rng) * w;
            ev = U(rng) * h;
            where = "inside";
            break;
        default: break;
    }
    double dist;
    switch (pick(5)) {
        case 0:
            dist = size * (20 + U(rng) * 1000);
            where += ", far";
            break;
        case 1:
            dist = std::abs(lo) * U(rng) + hi * (1.05 + U(rng));
            where += ", near";
            break;
        case 2:
            dist = hi * U(rng);
            where += ", below the highest texels";
            break;
        case 3:
            dist = -size * (0.1 + U(rng));
            where += ", behind";
            break;
        default: dist = size * (0.2 + U(rng) * 3); break;
    }
    c.eye = g.origin + g.a * eu + g.b * ev + g.f() * dist;
    c.options.method = pick(2) ? Reconstruction::two_pass : Reconstruction::pipelined;
    c.options.exact = pick(2);
    c.options.keep_outliers = pick(2);
    if (pick(4) == 0) c.options.max_margin = pick(10);
    c.options.threads = 1 + pick(2);
    c.options.isa = Isa::generic;  // the reference kernels are what this tests (warp/simd/ always copy such spans)
    c.with_displ = pick(3) == 0;
    std::ostringstream s;
    s << w << "x" << h << " kind " << kind << " brick " << bw << "x" << bh << " empties " << empties << " marks "
      << marks << " eye " << where << " " << to_string(c.options.method) << (c.options.exact ? " exact" : " lut")
      << " outliers " << c.options.keep_outliers << " max_margin " << c.options.max_margin << " threads "
      << c.options.threads << " displ " << c.with_displ;
    c.describe = s.str();
    return c;
}

// The copies the row warp makes, counted independently of the kernel: every valid texel at zero displacement
// (a still level, or exactly 0.0 with --exact) is copied unless the texel before it in occlusion-compatible order
// (towards the epipole's column) is a valid, moving texel connected to it: then the span between them is drawn.
long long expected_copies(const ReliefTexture& t, const PrewarpCoefficients& k, bool exact) {
    if (k.side == ViewSide::on_plane || t.width == 0 || t.height == 0) return 0;
    const PrewarpTables tab = PrewarpTables::build(k, t.quant);
    const int w = t.width, split = split_index(k.epipole_u, w);
    long long n = 0;
    for (int r = 0; r < t.height; ++r) {
        auto still = [&](int x) {
            const ReliefTexel& tx = t.texel(x, r);
            return exact ? tx.q != kEmptyIndex && t.displ(x, r) == 0.0f : tab.still[tx.q] != 0;
        };
        auto valid = [&](int x) {  // as the kernels decide it, including a finite position
            const ReliefTexel& tx = t.texel(x, r);
            if (tx.q == kEmptyIndex) return false;
            if (exact) {
                const double d = t.displ(x, r), den = 1.0 + k.k3 * d;
                return den > 0.0 && std::isfinite((x + 0.5 + k.k1 * d) / den);
            }
            return tab.valid[tx.q] && std::isfinite((float(x) + 0.5f + tab.k1d[tx.q]) * tab.rcp[tx.q]);
        };
        for (int x = 0; x < w; ++x) {
            if (!still(x)) continue;
            const int pred = x < split ? x - 1 : x + 1;
            const bool span = pred >= 0 && pred < w && valid(pred) && !still(pred) &&
                              (t.breaks.empty() || !(t.breaks[size_t(r) * w + std::min(pred, x)] & kBreakRight));
            n += !span;
        }
    }
    return n;
}

std::string first_difference(const ImageRGBA8& ref, const ImageRGBA8& got) {
    if (ref.width != got.width || ref.height != got.height)
        return "size " + std::to_string(got.width) + "x" + std::to_string(got.height) + ", expected " +
               std::to_string(ref.width) + "x" + std::to_string(ref.height);
    for (int r = 0; r < ref.height; ++r)
        for (int x = 0; x < ref.width; ++x)
            if (!(ref.at(x, r) == got.at(x, r)))
                return "pixel (" + std::to_string(x) + ", " + std::to_string(r) + "): " + to_string(got.at(x, r)) +
                       ", expected " + to_string(ref.at(x, r));
    return "";
}

TEST(StillRuns, CopyIsBitIdenticalToTheWarp) {
    const uint64_t seed = test::test_seed(90001);
    std::mt19937_64 rng(seed);
    PrewarpWorkspace ws_on, ws_off;
    ImageRGBA8 on, off;
    Image2D<uint8_t> d_on, d_off;
    long long copied = 0, visited = 0;
    int with_marks = 0, lut = 0, exact = 0, pipelined = 0, margins = 0;
    for (int i = 0; i < 1500; ++i) {
        Case c = random_case(rng);
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + ": " + c.describe);
        const PrewarpCoefficients k = compute_coefficients(c.relief.geometry, c.eye);
        PrewarpOptions o = c.options;
        o.copy_still_runs = false;
        const PrewarpStats s_off = prewarp(c.relief, k, o, ws_off, off, c.with_displ ? &d_off : nullptr);
        o.copy_still_runs = true;
        const PrewarpStats s_on = prewarp(c.relief, k, o, ws_on, on, c.with_displ ? &d_on : nullptr);
        ASSERT_EQ(first_difference(off, on), "") << k.to_string();
        if (c.with_displ) {
            ASSERT_TRUE(d_on == d_off) << "depth-correction output differs";
        }
        ASSERT_EQ(s_on.texels, s_off.texels);
        ASSERT_EQ(s_on.dropped, s_off.dropped);
        ASSERT_EQ(s_on.extent, s_off.extent);
        ASSERT_EQ(s_off.still_copied, 0);
        ASSERT_EQ(s_on.still_copied, expected_copies(c.relief, k, o.exact)) << k.to_string();
        copied += s_on.still_copied;
        visited += s_on.texels;
        with_marks += !c.relief.breaks.empty();
        (o.exact ? exact : lut) += s_on.still_copied > 0;
        pipelined += o.method == Reconstruction::pipelined && s_on.still_copied > 0;
        margins += (s_on.extent.left + s_on.extent.right + s_on.extent.bottom + s_on.extent.top) > 0 &&
                   s_on.still_copied > 0;
    }
    // The sweep exercised what it claims to: copies on both paths, both reconstructions, margins and marks.
    EXPECT_GT(copied, visited / 5);
    EXPECT_GT(with_marks, 300);
    EXPECT_GT(lut, 200);
    EXPECT_GT(exact, 200);
    EXPECT_GT(pipelined, 200);
    EXPECT_GT(margins, 200);
}

TEST(StillRuns, AFlatReliefIsCopiedWhole) {
    // Zero displacement everywhere: every non-empty texel is copied, and the pre-warp is the identity.
    ReliefTexture t = test::make_test_relief(37, 23, 0.0, 0.1, [](int, int) { return 0.0; });
    for (size_t i = 0; i < t.texels.size(); i += 5) t.texels.edit()[i].q = kEmptyIndex;
    long long nonempty = 0;
    for (const ReliefTexel& x : t.texels) nonempty += x.q != kEmptyIndex;
    EXPECT_EQ(count_still_texels(t, false), nonempty);
    EXPECT_EQ(count_still_texels(t, true), nonempty);
    const glm::dvec3 c = t.geometry.origin + t.geometry.a * 18.3 + t.geometry.b * 11.7;  // epipole inside
    for (Reconstruction m : {Reconstruction::two_pass, Reconstruction::pipelined})
        for (bool exact : {false, true}) {
            SCOPED_TRACE(to_string(m) + (exact ? " exact" : " lut"));
            PrewarpOptions o{.method = m, .exact = exact, .isa = Isa::generic};
            PrewarpWorkspace ws;
            ImageRGBA8 out;
            const PrewarpStats s = prewarp(t, compute_coefficients(t.geometry, c + t.geometry.f() * 0.3), o, ws, out);
            EXPECT_EQ(s.still_copied, nonempty);
            for (int r = 0; r < t.height; ++r)
                for (int x = 0; x < t.width; ++x) {
                    const ReliefTexel& tx = t.texel(x, r);
                    const Rgba8 want = tx.q == kEmptyIndex ? Rgba8{} : Rgba8{tx.r, tx.g, tx.b, 255};
                    ASSERT_EQ(out.at(x, r), want) << x << ", " << r;
                }
        }
}

TEST(StillRuns, ExactMeansExactlyZero) {
    // Bricks at 1e-9 world units: the tables round them to the zero level and copy them; --exact does not.
    const ReliefTexture t = test::make_test_relief(40, 12, -0.05, 0.0, [](int x, int r) {
        return (x % 8 == 0 || r % 4 == 0) ? -0.05 : -1e-9;
    });
    const PrewarpCoefficients k = compute_coefficients(t.geometry, glm::dvec3(0.7, 0.3, 0.5));
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    PrewarpOptions o{.isa = Isa::generic};
    EXPECT_GT(prewarp(t, k, o, ws, out).still_copied, 40 * 12 / 2);
    EXPECT_EQ(count_still_texels(t, false), 35 * 9);  // the bricks: columns x % 8 != 0, rows r % 4 != 0
    o.exact = true;
    EXPECT_EQ(prewarp(t, k, o, ws, out).still_copied, 0);
    EXPECT_EQ(count_still_texels(t, true), 0);
}

}  // namespace
}  // namespace rtm
