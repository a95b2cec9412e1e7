// The SIMD pre-warp kernels (warp/simd/schedule.h) against the generic implementation, pixel by pixel, on every
// target this machine supports (warp/isa.h), each chosen in turn (PrewarpOptions::isa): random
// reliefs (smooth, mostly flat with steps, noisy and foldover-heavy, with empty texels), sizes from 1x1 through
// 1xN, Nx1, odd sizes and sizes around multiples of 16, views with the epipole inside, outside, on texel centres and
// boundaries, far, near, grazing, below the highest texels, margins on and off, one and two threads.
// The seed is printed on failure; RTM_SEED overrides it, and RTM_SWEEP_CASES shortens the random sweeps (qemu).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <random>
#include <sstream>
#include <initializer_list>
#include <vector>

#include "test_util.h"
#include "warp/simd/pipelined_job.h"
#include "warp/simd/schedule.h"
#include "warp/simd/two_pass_job.h"
#include "warp/simd/kernel_policy.h"
#include "warp/line_warp.h"
#include "warp/prewarp.h"

// Counts every allocation of the test program (for the steady-state test below; harmless elsewhere).
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
namespace {
std::atomic<long long> g_allocations{0};
}
void* operator new(std::size_t n) {
    ++g_allocations;
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace rtm {
namespace {

struct Case {
    ReliefTexture relief;
    glm::dvec3 eye;
    PrewarpOptions options;
    std::string describe;
};

double hash01(int x, int y, uint32_t s) {
    uint32_t h = uint32_t(x) * 0x9E3779B1u ^ (uint32_t(y) * 0x85EBCA77u + s * 0x27d4eb2du);
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return double(h >> 8) / 16777216.0;
}

// Square texels, the relief 1 unit wide, centred on the origin's x and y: the geometry of the large and
// foldover-heavy test reliefs.
ReliefGeometry unit_width_geometry(int w) {
    ReliefGeometry g;
    g.a = {1.0 / w, 0, 0};
    g.b = {0, 1.0 / w, 0};
    g.origin = {-0.5, -0.5, 0};
    return g;
}

Case random_case(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto pick = [&](int n) { return int(rng() % uint64_t(n)); };
    int w, h;
    switch (pick(8)) {
        case 0: w = h = 1; break;
        case 1:
            w = 1;
            h = 1 + pick(80);
            break;
        case 2:
            w = 1 + pick(80);
            h = 1;
            break;
        case 3:
            w = 15 + pick(4);
            h = 31 + pick(4);
            break;  // around multiples of 16
        case 4:
            w = 64 + pick(150);
            h = 64 + pick(150);
            break;
        default:
            w = 1 + pick(70);
            h = 1 + pick(70);
            break;
    }
    const ReliefGeometry g = test::random_geometry(rng);
    const double size = std::max(glm::length(g.a) * w, glm::length(g.b) * h);
    const double amp = size * (0.02 + U(rng) * (pick(3) == 0 ? 1.0 : 0.2));
    const uint32_t salt = uint32_t(rng());
    const int kind = pick(5);
    const double fx = 0.05 + U(rng) * 0.5, fy = 0.05 + U(rng) * 0.5;
    auto displ = [&](int x, int r) -> double {
        switch (kind) {
            case 0: return amp * (0.5 + 0.5 * std::sin(x * fx) * std::cos(r * fy));  // smooth bumps
            case 1: return ((x % 9) == 0 || (r % 5) == 0) ? -amp * 0.3 : 0.0;  // bricks: mostly 0, recessed mortar
            case 2: return amp * hash01(x, r, salt);                           // noise: foldovers everywhere
            case 3: return amp * std::abs(std::sin(x * fx * 3));               // ridges
            default: return amp * 0.5;                                         // constant
        }
    };
    const double lo = kind == 1 ? -amp * 0.3 : 0.0, hi = kind == 1 ? 0.0 : amp;
    Case c{test::make_test_relief(w, h, lo, hi, displ, g), {}, {}, {}};
    const int empties = pick(4);
    if (empties == 1)
        for (size_t i = 0; i < c.relief.texels.size(); i += 3) c.relief.texels.edit()[i].q = kEmptyIndex;
    if (empties == 2)
        for (size_t i = 0; i < c.relief.texels.size(); ++i)
            if (hash01(int(i), 7, salt) < 0.3) c.relief.texels.edit()[i].q = kEmptyIndex;

    // The eye: epipole position in texels, distance along f.
    double eu = U(rng) * 3 * w - w, ev = U(rng) * 3 * h - h;
    std::string where = "anywhere";
    switch (pick(6)) {
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
        case 3:
            eu = -w * (1 + U(rng) * 20);
            where = "outside";
            break;
        default: break;
    }
    double dist;
    switch (pick(6)) {
        case 0:
            dist = size * (20 + U(rng) * 1000);
            where += ", far";
            break;
        case 1:
            dist = amp * (1.05 + U(rng));
            where += ", near";
            break;
        case 2:
            dist = amp * U(rng);
            where += ", below the highest texels";
            break;
        case 3: {
            const double off = size * (2 + U(rng) * 20);
            eu = w * 0.5 + off / glm::length(g.a);
            dist = off * std::tan(0.002 + U(rng) * 0.08);
            where = "grazing";
            break;
        }
        case 4:
            dist = -size * (0.1 + U(rng));
            where += ", behind";
            break;
        default: dist = size * (0.2 + U(rng) * 3); break;
    }
    c.eye = g.origin + g.a * eu + g.b * ev + g.f() * dist;
    c.options.keep_outliers = pick(3) == 0;
    if (pick(4) == 0) c.options.max_margin = pick(20);
    std::ostringstream s;
    s << w << "x" << h << " kind " << kind << " empties " << empties << " eye " << where << " (" << c.eye.x << ", "
      << c.eye.y << ", " << c.eye.z << ") outliers " << c.options.keep_outliers << " max_margin "
      << c.options.max_margin;
    c.describe = s.str();
    return c;
}

// First differing pixel, or "" when the images are equal.
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

// A reconstruction and a SIMD target that implements it (instantiated below for every target of this machine).
struct MethodTarget {
    Reconstruction method;
    Isa isa;
};

class FastKernels : public ::testing::TestWithParam<MethodTarget> {
protected:
    Reconstruction method() const { return GetParam().method; }
    Isa isa() const { return GetParam().isa; }
};

TEST_P(FastKernels, MatchTheReferencePixelByPixel) {
    const uint64_t seed = test::test_seed(80001);
    std::mt19937_64 rng(seed);
    const int cases = test::sweep_cases(2000);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    int covered = 0;
    for (int i = 0; i < cases; ++i) {
        Case c = random_case(rng);
        c.options.method = method();
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + ": " + c.describe);
        const PrewarpCoefficients k = compute_coefficients(c.relief.geometry, c.eye);
        PrewarpOptions o = c.options;
        o.isa = Isa::generic;
        o.threads = 1;
        const PrewarpStats sr = prewarp(c.relief, k, o, ws_ref, ref);
        for (int threads : {1, 2}) {
            o.isa = isa();
            o.threads = threads;
            const PrewarpStats sf = prewarp(c.relief, k, o, ws_fast, fast);
            const std::string diff = first_difference(ref, fast);
            ASSERT_EQ(diff, "") << "threads " << threads << " " << k.to_string();
            ASSERT_EQ(sf.texels, sr.texels);
            ASSERT_EQ(sf.dropped, sr.dropped);
            ASSERT_EQ(sf.extent, sr.extent);
        }
        covered += fast_prewarp_covers(isa(), c.relief, k, o, sr.extent, nullptr);
    }
    // Everything but the eye in the relief's plane goes through the fast kernels.
    EXPECT_GT(covered, cases * 9 / 10);
}

TEST_P(FastKernels, LargeReliefsAndManyThreadsMatch) {
    // Long lines (several 32-sample windows, gathers under minification), and all threads.
    const uint64_t seed = test::test_seed(80002);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    // 8 cases, fewer in proportion when RTM_SWEEP_CASES shortens the sweeps (at least 1).
    const int cases = std::max(1, test::sweep_cases(2000) * 8 / 2000);
    for (int i = 0; i < cases; ++i) {
        const int w = 300 + int(rng() % 300), h = 250 + int(rng() % 300);
        const ReliefGeometry g = unit_width_geometry(w);
        const uint32_t salt = uint32_t(rng());
        const bool noisy = i % 3 == 2;
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, 0.2,
            [&](int x, int r) {
                return noisy ? 0.2 * hash01(x / 3, r / 3, salt) : 0.1 + 0.1 * std::sin(x * 0.03) * std::sin(r * 0.05);
            },
            g);
        const double az = (U(rng) - 0.5) * 2.6, el = 0.1 + U(rng) * 1.4, d = 0.8 + U(rng) * 3;
        const glm::dvec3 eye{d * std::cos(el) * std::sin(az), d * std::sin(el) * 0.5, d * std::cos(el) * std::cos(az)};
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        PrewarpOptions o;
        o.method = method();
        o.keep_outliers = i % 2 == 0;
        o.isa = Isa::generic;
        o.threads = 1;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + " " + std::to_string(w) + "x" +
                     std::to_string(h) + " " + k.to_string());
        prewarp(t, k, o, ws_ref, ref);
        for (int threads : {1, 2, 0}) {
            o.isa = isa();
            o.threads = threads;
            prewarp(t, k, o, ws_fast, fast);
            ASSERT_EQ(first_difference(ref, fast), "") << "threads " << threads;
        }
    }
}

TEST_P(FastKernels, SteepReliefsAndLongSpansMatch) {
    // The paths of the Highway kernels that only wide, steep reliefs reach (warp/simd/hwy_columns-inl.h,
    // hwy_row-inl.h, hwy_pipelined.cpp): column spans of 5 pixels and more drawn row by row over the lanes, with
    // lanes far apart from the others alone; columns that receive several pixels from a row (foldovers), the
    // pipelined kernel's runs of groups cut where a group writes over the pending run; rows whose spans are drawn a
    // vector of pixels at a time; row set-up with gathers, and widths that are not a multiple of the lanes (the
    // last vector of every task lane by lane). Relief widths 48 to 300, heights of a fifth to 1.5 times the width,
    // eyes near and far, the epipole inside and outside.
    const uint64_t seed = test::test_seed(80006);
    std::mt19937_64 rng(seed);
    std::printf("seed %llu\n", (unsigned long long)seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    const int cases = std::max(4, test::sweep_cases(2000) / 20);
    for (int i = 0; i < cases; ++i) {
        const int w = 48 + int(rng() % 253), h = std::max(8, int(w * (0.2 + U(rng) * 1.3)));
        const ReliefGeometry g = unit_width_geometry(w);
        const uint32_t salt = uint32_t(rng());
        const int kind = int(rng() % 4);
        const double amp = 0.05 + U(rng) * 0.6, f = 0.02 + U(rng) * 0.3, cell = 1 + int(rng() % 6);
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, amp,
            [&](int x, int r) {
                switch (kind) {
                    case 0: return amp * hash01(int(x / cell), int(r / cell), salt);             // blocky noise
                    case 1: return amp * std::abs(std::sin(x * f)) * (r % 7 == 0 ? 0.2 : 1);     // ridges, steps
                    case 2: return amp * (0.5 + 0.5 * std::sin(x * f) * std::cos(r * f * 0.7));  // bumps
                    default: return (x / int(cell + 2) + r / 3) % 4 == 0 ? amp : 0.0;            // towers
                }
            },
            g);
        const double az = (U(rng) - 0.5) * 3.0, el = 0.05 + U(rng) * 1.45, d = 0.3 + U(rng) * (rng() % 2 ? 1 : 6);
        const glm::dvec3 eye{d * std::cos(el) * std::sin(az) + (U(rng) - 0.5) * 0.8,
                             d * std::cos(el) * std::cos(az) * 0.5 + (U(rng) - 0.5) * 0.8, d * std::sin(el)};
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        PrewarpOptions o;
        o.method = method();
        o.keep_outliers = i % 2 == 0;
        o.isa = Isa::generic;
        o.threads = 1;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + " " + std::to_string(w) + "x" +
                     std::to_string(h) + " kind " + std::to_string(kind) + " " + k.to_string());
        const PrewarpStats sr = prewarp(t, k, o, ws_ref, ref);
        for (int threads : {1, 2}) {
            o.isa = isa();
            o.threads = threads;
            const PrewarpStats sf = prewarp(t, k, o, ws_fast, fast);
            ASSERT_EQ(first_difference(ref, fast), "") << "threads " << threads;
            ASSERT_EQ(sf.dropped, sr.dropped);
        }
    }
}

TEST_P(FastKernels, ExtremeConfigurationsMatch) {
    // World scales from 1e-4 to 1e4, eyes a hair above the plane, far outside, grazing, below the highest texels,
    // huge and tiny coefficients: positions far outside the output, non-finite ones, spans of zero length.
    const uint64_t seed = test::test_seed(80003);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    const int cases = test::sweep_cases(3000);
    for (int i = 0; i < cases; ++i) {
        const int w = 1 + int(rng() % 40), h = 1 + int(rng() % 40);
        const double scale = std::pow(10.0, U(rng) * 8 - 4);
        ReliefGeometry g = test::random_geometry(rng);
        g.origin *= scale * 100;
        g.a *= scale * 100;
        g.b *= scale * 100;
        const double size = std::max(glm::length(g.a) * w, glm::length(g.b) * h);
        const double lo = -size * U(rng) * 0.5, hi = size * U(rng) * 2;
        double eu = U(rng) * 3 * w - w, ev = U(rng) * 3 * h - h, dist = size * (0.05 + U(rng) * 5);
        switch (rng() % 5) {
            case 0: eu *= 1e6; break;
            case 1: dist = size * std::pow(10.0, -12 + U(rng) * 10); break;
            case 2: dist = size * std::pow(10.0, 3 + U(rng) * 9); break;
            case 3: dist = hi * U(rng); break;
            default: eu = std::floor(eu) + 0.5; break;
        }
        const glm::dvec3 eye = g.origin + g.a * eu + g.b * ev + g.f() * dist;
        const ReliefTexture t = test::make_test_relief(
            w, h, lo, hi, [&](int x, int r) { return lo + (hi - lo) * (((x * 31 + r * 17) % 13) / 12.0); }, g);
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        PrewarpOptions o;
        o.method = method();
        o.keep_outliers = i % 3 == 0;
        o.isa = Isa::generic;
        o.threads = 1;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + " " + std::to_string(w) + "x" +
                     std::to_string(h) + " " + k.to_string());
        const PrewarpStats sr = prewarp(t, k, o, ws_ref, ref);
        o.isa = isa();
        const PrewarpStats sf = prewarp(t, k, o, ws_fast, fast);
        ASSERT_EQ(first_difference(ref, fast), "");
        ASSERT_EQ(sf.dropped, sr.dropped);
    }
}

TEST_P(FastKernels, BandsAndThreadsMatch) {
    // The two-pass kernels take the rows in bands of 32 through a pipeline when there are threads, in bands of 16 on
    // one thread: heights around multiples of the bands, the epipole's row (where the vertical pass turns from the
    // bottom part to the top one) on band boundaries and inside bands, one to four threads.
    const uint64_t seed = test::test_seed(80005);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    for (int h : {15, 16, 17, 31, 32, 33, 48, 49, 64, 65, 96, 97, 130}) {
        const int w = 20 + int(rng() % 120);
        const ReliefGeometry g = unit_width_geometry(w);
        const uint32_t salt = uint32_t(rng());
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, 0.2,
            [&](int x, int r) {
                return hash01(x, r, salt) < 0.05 ? 0.2 * hash01(r, x, salt)
                                                 : 0.1 + 0.08 * std::sin(x * 0.2) * std::sin(r * 0.15);
            },
            g);
        for (double ev : {-10.0, 0.0, 16.0, 31.5, 32.0, 32.5, 40.0, h - 0.5, h + 20.0}) {
            const double eu = U(rng) * w * 1.4 - w * 0.2;
            const glm::dvec3 eye = g.origin + g.a * eu + g.b * ev + g.f() * (0.3 + U(rng));
            const PrewarpCoefficients k = compute_coefficients(g, eye);
            PrewarpOptions o;
            o.method = method();
            o.keep_outliers = rng() % 2;
            o.isa = Isa::generic;
            o.threads = 1;
            SCOPED_TRACE("seed " + std::to_string(seed) + " " + std::to_string(w) + "x" + std::to_string(h) +
                         " epipole row " + std::to_string(ev) + " " + k.to_string());
            prewarp(t, k, o, ws_ref, ref);
            for (int threads : {1, 2, 3, 4, 0}) {
                o.isa = isa();
                o.threads = threads;
                prewarp(t, k, o, ws_fast, fast);
                ASSERT_EQ(first_difference(ref, fast), "") << "threads " << threads;
            }
        }
    }
}

TEST_P(FastKernels, StillRunCopiesAreInvisible) {
    // PrewarpOptions::copy_still_runs on the fast path: 16 consecutive spans one pixel wide on pixel centres (zero
    // displacement) are copied or, with the option off, interpolated; the output is the same either way (and the
    // copies are not counted). Bricks 40 texels wide.
    const ReliefTexture t = test::make_test_relief(150, 90, -0.05, 0.0, [](int x, int r) {
        return (x % 40 == 0 || r % 6 == 0) ? -0.05 : 0.0;
    });
    PrewarpWorkspace ws;
    ImageRGBA8 on, off, ref;
    for (const glm::dvec3 eye : {glm::dvec3(0.7, 0.3, 0.8), glm::dvec3(-0.2, 0.9, 0.5), glm::dvec3(0.4, 0.4, 2.0)}) {
        const PrewarpCoefficients k = compute_coefficients(t.geometry, eye);
        SCOPED_TRACE(k.to_string());
        PrewarpOptions o;
        o.method = method();
        o.isa = Isa::generic;
        prewarp(t, k, o, ws, ref);
        o.isa = isa();
        for (int threads : {1, 2}) {
            o.threads = threads;
            o.copy_still_runs = true;
            const PrewarpStats s_on = prewarp(t, k, o, ws, on);
            o.copy_still_runs = false;
            const PrewarpStats s_off = prewarp(t, k, o, ws, off);
            ASSERT_EQ(first_difference(ref, on), "") << "threads " << threads;
            ASSERT_EQ(first_difference(ref, off), "") << "threads " << threads;
            EXPECT_EQ(s_on.still_copied, 0);
            EXPECT_EQ(s_off.still_copied, 0);
        }
    }
}

TEST_P(FastKernels, UniformShiftsOffPixelCentresAreNotCopies) {
    // A relief at one displacement seen from very far along an oblique direction: 1 + k3*d rounds to 1 in float, so
    // every row is the one below it shifted by the same K2 texels, and each column's samples lie exactly one row
    // apart (|v - pv| == 1), as a still step's do, but off the pixel centres: the column spans interpolate (t =
    // the fraction) and must not be taken for copies (the pipelined kernels' StillStep also checks the centre).
    const int w = 96, h = 80;
    const ReliefGeometry g = unit_width_geometry(w);
    const double d = 0.05;
    const ReliefTexture t = test::make_test_relief(
        w, h, -d, d, [&](int, int) { return d; }, g);
    PrewarpWorkspace ws;
    ImageRGBA8 ref, fast;
    int shifted = 0;
    for (const double frac : {0.25, 0.5, -0.75, -0.3}) {
        // K2 = k2 * d = e_v * k3 * d texels, k3 = 1 / dot(c, f) = -1 / dist: e_v = -K2 * dist / d. Rows shifted
        // down (the eye far below: the top part, v decreasing along each column) and up (the bottom part).
        const double dist = 1e9, ev = (frac > 0 ? 2.0 + frac : frac - 2.0) * dist / d;
        const glm::dvec3 eye = g.origin + g.a * (0.4 * w) - g.b * ev + g.f() * dist;
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        SCOPED_TRACE("frac " + std::to_string(frac) + " " + k.to_string());
        ASSERT_EQ(float(1.0 / (1.0 + k.k3 * d)), 1.0f);  // the premise: R is 1 in the kernels' float tables
        const double shift = std::abs(k.k2 * d);
        shifted += std::abs(shift - std::round(shift)) > 0.1;
        PrewarpOptions o;
        o.method = method();
        o.isa = Isa::generic;
        o.threads = 1;
        prewarp(t, k, o, ws, ref);
        o.isa = isa();
        for (int threads : {1, 2}) {
            o.threads = threads;
            prewarp(t, k, o, ws, fast);
            ASSERT_EQ(first_difference(ref, fast), "") << "threads " << threads;
        }
    }
    // Every view shifts the rows by a fraction of a texel: the fractions above are 0.25 or more from a whole texel,
    // so 0.1 only absorbs the double-precision rounding of k2 * d.
    EXPECT_EQ(shifted, 4);
}

TEST_P(FastKernels, StillBlocksMatchTheReference) {
    // The paper's brick wall (section 5): bricks at zero displacement, wider than a group of 16 columns and often
    // taller than a band of 32 rows, between recessed mortar (max <= 0), or with a few texels raised above zero
    // (max > 0, raised texels that overwrite still ones) and empty texels; eyes in front and behind, near, far and
    // grazing, the epipole inside (both parts of the vertical pass) and outside; margins on and off; 1 to 3
    // threads. The two-pass vertical pass copies such still pixels in blocks (warp/simd/schedule.cpp,
    // vertical_with_still), the pipelined kernels a vector of columns at a time: the output must stay the
    // reference's, and the two-pass copy must happen.
    const uint64_t seed = test::test_seed(80031);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto pick = [&](int n) { return int(rng() % uint64_t(n)); };
    // The pipelined kernel copies still steps a vector of columns at a time (StillStep in
    // warp/simd/hwy_columns-inl.h), forwards and in reverse mode.
    const int cases = test::sweep_cases(method() == Reconstruction::two_pass ? 240 : 160);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    const long long copies_before = simd::testing::vertical_still_copies();
    for (int i = 0; i < cases; ++i) {
        const int w = 16 + pick(280), h = 16 + pick(280);
        const int bw = 17 + pick(90), bh = 4 + pick(70), mortar = 1 + pick(6);
        const bool raised = pick(4) == 0, empties = pick(5) == 0;
        // Levels are multiples of 2^-k with 0 among them (decoded exactly): 254 below zero, or 200 below and 54
        // above.
        const double q = std::ldexp(1.0, -(9 + pick(4)));
        const double lo = raised ? -200 * q : -254 * q, hi = raised ? 54 * q : 0.0;
        const uint32_t salt = uint32_t(rng());
        const int phase = pick(200);  // where the courses and joints start (the top row a brick's or mortar)
        const ReliefGeometry g = unit_width_geometry(w);
        ReliefTexture t = test::make_test_relief(
            w, h, lo, hi,
            [&](int x, int r) {
                const int rs = r + phase, course = rs / bh, xs = x + phase + (course % 2) * (bw / 2);
                if (xs % bw < mortar || rs % bh < mortar) return lo * (0.3 + 0.7 * hash01(x, r, salt));
                if (raised && hash01(r, x, salt) < 0.003) return hi * hash01(x, x + r, salt);
                return 0.0;
            },
            g);
        if (empties)
            for (size_t j = 0; j < t.texels.size(); ++j)
                if (hash01(int(j), 11, salt) < 0.01) t.texels.edit()[j].q = kEmptyIndex;
        double eu = U(rng) * 3 * w - w, ev = U(rng) * 3 * h - h, dist = 0.05 + U(rng) * 2;
        std::string where = "anywhere";
        bool prime = false;  // first a view whose top part starts 8 rows lower, in the same workspace
        switch (pick(6)) {
            case 0:
                eu = U(rng) * w, ev = U(rng) * h;
                where = "inside";
                break;
            case 4:
                // The top part's first step on a band's first (bands of 32 steps, 16 on one thread; split_index
                // gives row 32k).
                eu = U(rng) * w, ev = h > 32 ? 32.0 * (1 + pick((h - 1) / 32)) : 0.0;
                where = "inside, epipole row on a band boundary";
                prime = true;
                break;
            case 1:
                dist = 5 + U(rng) * 100;
                where = "far";
                break;
            case 2:
                dist = -dist;
                where = "behind";
                break;
            case 3:
                eu = w * (3 + U(rng) * 20);
                dist = (eu / w) * std::tan(0.005 + U(rng) * 0.1);
                where = "grazing";
                break;
            default: break;
        }
        const glm::dvec3 eye = g.origin + g.a * eu + g.b * ev + g.f() * dist;
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        PrewarpOptions o;
        o.method = method();
        o.keep_outliers = pick(3) == 0;
        o.isa = Isa::generic;
        o.threads = 1;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + ": " + std::to_string(w) + "x" +
                     std::to_string(h) + " bricks " + std::to_string(bw) + "x" + std::to_string(bh) + " mortar " +
                     std::to_string(mortar) + " raised " + std::to_string(raised) + " empties " +
                     std::to_string(empties) + " eye " + where + " outliers " + std::to_string(o.keep_outliers) + " " +
                     k.to_string());
        prewarp(t, k, o, ws_ref, ref);
        o.isa = isa();
        for (int threads : {1, 2, 3}) {
            o.threads = threads;
            // The kernels keep the bottom part's last samples for the seam in the workspace: a band that starts
            // the top part must not find the last view's there (nor copy its first step).
            if (prime) prewarp(t, compute_coefficients(g, eye - g.b * 8.0), o, ws_fast, fast);
            prewarp(t, k, o, ws_fast, fast);
            ASSERT_EQ(first_difference(ref, fast), "") << "threads " << threads;
        }
        if (i % 8 == 0) {
            o.copy_still_runs = false;
            prewarp(t, k, o, ws_fast, fast);
            ASSERT_EQ(first_difference(ref, fast), "") << "copy_still_runs off";
        }
    }
    const long long copies = simd::testing::vertical_still_copies() - copies_before;
    std::printf("seed %llu: %lld still pixels copied by the vertical pass\n", (unsigned long long)seed, copies);
    if (method() == Reconstruction::two_pass) {
        EXPECT_GT(copies, (long long)cases * 1000);
    }
}

TEST_P(FastKernels, SteadyStateAllocatesNothing) {
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.01, 0};
    const ReliefTexture t = test::make_test_relief(
        300, 200, 0.0, 0.2, [](int x, int r) { return 0.1 + 0.1 * std::sin(x * 0.1 + r * 0.07); }, g);
    PrewarpOptions o;
    o.method = method();
    o.isa = isa();
    o.threads = 1;
    o.keep_outliers = true;
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    // Two threads too, the epipole inside the rows and below them (the pipelined kernel's row chunks: one part).
    for (int threads : {1, 2})
        for (double ey : {0.8, -0.8}) {
            o.threads = threads;
            const PrewarpCoefficients k = compute_coefficients(g, {1.2, ey, 1.5});
            prewarp(t, k, o, ws, out);  // warm-up: buffers grow to size
            const long long before = g_allocations.load();
            for (int i = 0; i < 3; ++i) prewarp(t, compute_coefficients(g, {1.2 + 0.01 * i, ey, 1.5}), o, ws, out);
            EXPECT_EQ(g_allocations.load() - before, 0) << "threads " << threads << " eye y " << ey;
        }
}

// lerp8 (warp/line_warp.h) moved from the float formula uint8_t(a * (1 - t) + b * t + 0.5) to fixed point (14-bit
// weights, integer dot products in the fast kernels). The bound its comment derives: at most 1 level from the
// float formula, only where the exact value a + (b - a) * t lies within 255 / 2^14 of a rounding boundary, and
// t = 0, t = 1 exact. Every pair of levels, t on a grid of 1/512 (the quantization steps and the points between
// them) and random t.
TEST(Lerp8, FixedPointWithinOneLevelOfTheFloatFormula) {
    const uint64_t seed = test::test_seed(80004);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    std::vector<float> ts;
    for (int k = 0; k <= 512; ++k) ts.push_back(float(k) / 512.0f);
    for (int k = 0; k < 100; ++k) ts.push_back(U(rng));
    long long differ = 0, total = 0;
    for (int a = 0; a < 256; ++a)
        for (int b = 0; b < 256; ++b) {
            ASSERT_EQ(lerp8(uint8_t(a), uint8_t(b), 0.0f), a);
            ASSERT_EQ(lerp8(uint8_t(a), uint8_t(b), 1.0f), b);
            ASSERT_EQ(lerp8(uint8_t(a), uint8_t(b), 0.0), a);
            ASSERT_EQ(lerp8(uint8_t(a), uint8_t(b), 1.0), b);
            for (float t : ts) {
                const int old_float = int(uint8_t(float(a) * (1.0f - t) + float(b) * t + 0.5f));
                const int fixed = lerp8(uint8_t(a), uint8_t(b), t);
                ASSERT_EQ(fixed, int(lerp8(uint8_t(a), uint8_t(b), double(t)))) << a << " " << b << " t " << t;
                ++total;
                if (fixed == old_float) continue;
                ++differ;
                ASSERT_LE(std::abs(fixed - old_float), 1) << "seed " << seed << ": " << a << " " << b << " t " << t;
                const double exact = a + (b - a) * double(t);
                const double to_boundary = std::abs(exact + 0.5 - std::round(exact + 0.5));
                ASSERT_LE(to_boundary, 255.0 / 16384.0 + 1e-6) << a << " " << b << " t " << t;
            }
        }
    // 0.65% of these cases differ (at most 2 * 255 / 2^14 = 3% could: the band around a boundary).
    EXPECT_LT(differ, total / 50);
}

// The pipelined kernel's reverse mode (warp/simd/hwy_pipelined.cpp, RunRows: each pixel written once, by the last
// emission of the forward order) forced on for whole parts, and off, against the reference, on every SIMD target
// (PipelinedReverseFastKernels): the random cases above, and foldover-heavy reliefs (noise and steep ridges seen at
// grazing angles: spans far longer than a pixel, columns whose written rows are not one interval), still texels
// (samples on pixel centres, spans on both sides of one), empty texels (columns whose runs restart with points), one to
// three threads (column ranges). The relief of the steady-state allocation tests: 300x200 texels of 0.01, sine ridges
// across the rows, which fold over from the views they use.
ReliefTexture steady_state_relief() {
    ReliefGeometry g;
    g.a = {0.01, 0, 0};
    g.b = {0, 0.01, 0};
    return test::make_test_relief(
        300, 200, 0.0, 0.5, [](int x, int) { return 0.5 * std::abs(std::sin(x * 0.3)); }, g);
}

// The suites of the scheduling policies (warp/simd/kernel_policy.h) run on every SIMD target this machine supports,
// each chosen in turn.
class PipelinedReverseFastKernels : public ::testing::TestWithParam<Isa> {
protected:
    Isa isa() const { return GetParam(); }
};
class TwoPassReverseFastKernels : public ::testing::TestWithParam<Isa> {
protected:
    Isa isa() const { return GetParam(); }
};

// The policy sweeps run every case once per policy (and the row-chunk sweep at three thread counts, twice): where
// RTM_SWEEP_CASES shortens the sweeps (the qemu runs of scripts/arm.sh, which must stay a few minutes: at a tenth
// these sweeps took 41 to 49 s each a target emulated), a fortieth of its cases, at most `full`.
int policy_cases(int full) {
    const int shortened = test::sweep_cases(1 << 30);
    return shortened < (1 << 30) ? std::clamp(shortened / 40, 1, full) : full;
}
// The same for the loops over large foldover-heavy reliefs (tens of times a random case's work each): a fortieth.
int large_cases(int full) {
    const int shortened = test::sweep_cases(1 << 30);
    return shortened < (1 << 30) ? std::clamp(shortened / 40, 1, full) : full;
}
bool sweeps_shortened() { return test::sweep_cases(1 << 30) < (1 << 30); }

const char* choice_name(KernelChoice c) {
    return c == KernelChoice::always ? "always" : c == KernelChoice::never ? "never" : "automatic";
}

// Scheduling policies of the avx512 kernels (the test seam warp/simd/kernel_policy.h), with names for the messages.
struct NamedPolicy {
    const char* name;
    FastKernelPolicy policy;
};
FastKernelPolicy pipelined_policy(KernelChoice reverse, KernelChoice row_chunks = KernelChoice::automatic) {
    FastKernelPolicy p;
    p.pipelined_reverse = reverse;
    p.pipelined_row_chunks = row_chunks;
    return p;
}
FastKernelPolicy two_pass_policy(KernelChoice reverse, bool redo_forwards = false) {
    FastKernelPolicy p;
    p.two_pass_reverse = reverse;
    p.two_pass_redo_forwards = redo_forwards;
    return p;
}
const NamedPolicy kPipelinedReverse[] = {{"reverse mode always", pipelined_policy(KernelChoice::always)},
                                         {"reverse mode never", pipelined_policy(KernelChoice::never)},
                                         {"reverse mode automatic", pipelined_policy(KernelChoice::automatic)}};
const NamedPolicy kTwoPassReverse[] = {{"backward rows always", two_pass_policy(KernelChoice::always)},
                                       {"backward rows always, redone forwards",
                                        two_pass_policy(KernelChoice::always, true)},
                                       {"backward rows automatic", two_pass_policy(KernelChoice::automatic)},
                                       {"backward rows never", two_pass_policy(KernelChoice::never)}};

// The random cases above against the reference, the fast kernel run with each of `policies`, on one and two
// threads, copies of still runs alternating; the dropped counts must agree too.
template <size_t N>
void random_cases_with_policies(Isa isa, Reconstruction method, const NamedPolicy (&policies)[N], int cases,
                                uint64_t seed_fallback) {
    const uint64_t seed = test::test_seed(seed_fallback);
    std::mt19937_64 rng(seed);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    for (int i = 0; i < cases; ++i) {
        Case c = random_case(rng);
        c.options.method = method;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + ": " + c.describe);
        const PrewarpCoefficients k = compute_coefficients(c.relief.geometry, c.eye);
        PrewarpOptions o = c.options;
        o.isa = Isa::generic;
        o.threads = 1;
        const PrewarpStats sr = prewarp(c.relief, k, o, ws_ref, ref);
        o.isa = isa;
        for (const NamedPolicy& policy : policies) {
            const simd::testing::ScopedKernelPolicy scope(policy.policy);
            for (int threads : {1, 2}) {
                o.threads = threads;
                o.copy_still_runs = (i + threads) % 2 == 0;
                const PrewarpStats sf = prewarp(c.relief, k, o, ws_fast, fast);
                ASSERT_EQ(first_difference(ref, fast), "") << policy.name << ", threads " << threads;
                ASSERT_EQ(sf.dropped, sr.dropped);
            }
        }
    }
}

// The avx2 kernels' two ways of storing some lanes of a vector they own (FastKernelPolicy::avx2_blend_stores: a load,
// blend and store, or AVX2's masked store; this CPU's automatic choice runs in every other test), each with the
// reconstructions' own policies: the same output to the bit.
FastKernelPolicy blend_policy(bool blend, FastKernelPolicy p) {
    p.avx2_blend_stores = blend ? KernelChoice::always : KernelChoice::never;
    return p;
}
const NamedPolicy kBlendPipelined[] = {
    {"blend stores, reverse mode always", blend_policy(true, pipelined_policy(KernelChoice::always))},
    {"blend stores, reverse mode never", blend_policy(true, pipelined_policy(KernelChoice::never))},
    {"blend stores, row chunks always",
     blend_policy(true, pipelined_policy(KernelChoice::automatic, KernelChoice::always))},
    {"masked stores, reverse mode always", blend_policy(false, pipelined_policy(KernelChoice::always))},
    {"masked stores, reverse mode never", blend_policy(false, pipelined_policy(KernelChoice::never))}};
const NamedPolicy kBlendTwoPass[] = {
    {"blend stores, backward rows always", blend_policy(true, two_pass_policy(KernelChoice::always))},
    {"blend stores, backward rows never", blend_policy(true, two_pass_policy(KernelChoice::never))},
    {"masked stores, backward rows always", blend_policy(false, two_pass_policy(KernelChoice::always))},
    {"masked stores, backward rows never", blend_policy(false, two_pass_policy(KernelChoice::never))}};

// Every case of the sweep, also under the sanitizers (their RTM_SWEEP_CASES: 300), where the other suites leave most of
// the load, blend and store path to the Release run (this CPU's automatic choice may be the masked store): a whole
// vector loaded and stored at the end of a row or buffer is what they would catch.
TEST(Avx2Stores, PipelinedBlendedAndMaskedMatchTheReference) {
    if (!isa_supported(Isa::avx2)) GTEST_SKIP() << "no AVX2 on this CPU";
    random_cases_with_policies(Isa::avx2, Reconstruction::pipelined, kBlendPipelined, test::sweep_cases(1500), 80021);
}
TEST(Avx2Stores, TwoPassBlendedAndMaskedMatchTheReference) {
    if (!isa_supported(Isa::avx2)) GTEST_SKIP() << "no AVX2 on this CPU";
    random_cases_with_policies(Isa::avx2, Reconstruction::two_pass, kBlendTwoPass, test::sweep_cases(1500), 80022);
}

TEST_P(PipelinedReverseFastKernels, RandomCasesMatchTheReference) {
    random_cases_with_policies(isa(), Reconstruction::pipelined, kPipelinedReverse, policy_cases(1500), 80011);
}

TEST_P(PipelinedReverseFastKernels, FoldoversStillTexelsAndGapsMatchTheReference) {
    const uint64_t seed = test::test_seed(80012);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    for (int i = 0, n = large_cases(60); i < n; ++i) {
        const int w = 40 + int(rng() % 200), h = 40 + int(rng() % 200);
        const ReliefGeometry g = unit_width_geometry(w);
        const uint32_t salt = uint32_t(rng());
        const int kind = i % 5;
        const double f = 0.2 + U(rng);
        ReliefTexture t = test::make_test_relief(
            w, h, -0.1, 0.3,
            [&](int x, int r) -> double {
                switch (kind) {
                    case 0: return 0.3 * hash01(x, r, salt);                                     // noise
                    case 1: return 0.3 * std::abs(std::sin(x * f)) * std::abs(std::sin(r * f));  // steep ridges
                    case 2: return (x % 7 == 0 || r % 5 == 0) ? -0.1 : 0.0;                      // still texels, mortar
                    case 3: return hash01(x / 4, r / 4, salt) < 0.5 ? 0.0 : 0.3;                 // steps onto still
                    default: return 0.3 * std::abs(std::sin(r * f));                             // ridges along rows
                }
            },
            g);
        if (i % 3 == 1)
            for (size_t q = 0; q < t.texels.size(); ++q)
                if (hash01(int(q), 3, salt) < 0.15) t.texels.edit()[q].q = kEmptyIndex;
        // Grazing, near, and from above; epipole inside and outside.
        const double az = (U(rng) - 0.5) * 6.0, el = i % 2 ? 0.03 + U(rng) * 0.3 : 0.3 + U(rng) * 1.2;
        const double d = 0.4 + U(rng) * 2;
        const glm::dvec3 eye{d * std::cos(el) * std::sin(az), d * std::cos(el) * std::cos(az), d * std::sin(el)};
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        PrewarpOptions o;
        o.method = Reconstruction::pipelined;
        o.keep_outliers = i % 4 != 0;
        o.isa = Isa::generic;
        o.threads = 1;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + " kind " + std::to_string(kind) +
                     " " + std::to_string(w) + "x" + std::to_string(h) + " " + k.to_string());
        prewarp(t, k, o, ws_ref, ref);
        o.isa = isa();
        for (KernelChoice reverse : {KernelChoice::always, KernelChoice::automatic}) {
            const simd::testing::ScopedKernelPolicy scope(pipelined_policy(reverse));
            for (int threads : {1, 3}) {
                o.threads = threads;
                for (bool copy : {true, false}) {
                    o.copy_still_runs = copy;
                    prewarp(t, k, o, ws_fast, fast);
                    ASSERT_EQ(first_difference(ref, fast), "")
                        << "reverse mode " << choice_name(reverse) << " threads " << threads << " copy " << copy;
                }
            }
        }
    }
}

// The Highway pipelined kernel's reverse-mode buffers belong to the workspace's task and are shared by the targets,
// whose vectors differ in length: a target with longer vectors after one with shorter ones must not write past the log
// the shorter ones grew (it did: heap corruption in `rtm bench --isa avx2,sse4`, caught by valgrind; under the
// sanitizer build this test catches it). The targets by vector length, short first, each in reverse mode on one
// thread, against the reference.
TEST(FastKernelsReverseBuffers, SharedByTargetsOfEveryVectorLength) {
    const ReliefTexture t = steady_state_relief();
    const PrewarpCoefficients k = compute_coefficients(t.geometry, {1.2, 0.3, 0.4});
    PrewarpOptions o;
    o.method = Reconstruction::pipelined;
    o.isa = Isa::generic;
    o.threads = 1;
    PrewarpWorkspace ws_ref, ws;
    ImageRGBA8 ref, fast;
    prewarp(t, k, o, ws_ref, ref);
    const simd::testing::ScopedKernelPolicy scope(pipelined_policy(KernelChoice::always));
    std::vector<Isa> isas = supported_isas();
    std::reverse(isas.begin(), isas.end());  // the slowest (shortest vectors) first
    for (Isa isa : isas) {
        if (isa == Isa::generic) continue;
        o.isa = isa;
        prewarp(t, k, o, ws, fast);
        EXPECT_EQ(first_difference(ref, fast), "") << isa_name(isa);
    }
}

// Row chunks (warp/simd/schedule.cpp, FastKernelPolicy::pipelined_row_chunks always: every part split into chunks of
// consecutive rows, one per thread, each starting from the row before it warped without drawing, composited in row
// order) against the reference, 2 to 4 threads, reverse mode off, forced and automatic: the random cases above (one
// part and two, heights from 1 row), reliefs of 1 to 3 rows (fewer rows than threads) seen with the epipole inside and
// outside the rows, and foldover-heavy reliefs whose chunks switch to reverse mode on their own; the dropped counts
// too. Row chunks balanced by time (warp/simd/schedule.cpp): exact cases worked by hand, then a sweep where each
// chunk's time is the sum of fixed random costs of its rows: the bounds stay increasing from 0 to the row count
// and within 40 rounds bring every chunk to the mean time within two of the costliest rows (the bounds move by
// whole rows, and half-way each round).
TEST(BalanceRowChunks, MovesHalfWayToEqualTimes) {
    auto balanced = [](std::vector<int> b, std::vector<double> ms) {
        balance_row_chunks(b, ms.data());
        return b;
    };
    // Chunk 0 takes 3 of 4 ms: equal times put the bound at 2/3 of its 50 rows (33.3); half-way from 50: 41.7.
    EXPECT_EQ(balanced({0, 50, 100}, {3, 1}), (std::vector<int>{0, 42, 100}));
    EXPECT_EQ(balanced({0, 50, 100}, {1, 1}), (std::vector<int>{0, 50, 100}));
    // Targets 2 and 4 of 6 ms: row 20 (the end of chunk 1) and 25 (half of chunk 2); half-way: 15, 22.5 -> 23.
    EXPECT_EQ(balanced({0, 10, 20, 30}, {1, 1, 4}), (std::vector<int>{0, 15, 23, 30}));
    // Every chunk keeps a row.
    EXPECT_EQ(balanced({0, 1, 2, 3}, {100, 1, 1}), (std::vector<int>{0, 1, 2, 3}));
    // Times that cannot be right change nothing.
    EXPECT_EQ(balanced({0, 5, 10}, {0, 1}), (std::vector<int>{0, 5, 10}));
    EXPECT_EQ(balanced({0, 5, 10}, {std::nan(""), 1}), (std::vector<int>{0, 5, 10}));
    EXPECT_EQ(balanced({0, 10}, {1}), (std::vector<int>{0, 10}));
}

TEST(BalanceRowChunks, ConvergesToEqualTimes) {
    const uint64_t seed = test::test_seed(80023);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int iter = 0; iter < 300; ++iter) {
        const int n = 2 + int(rng() % 7), rows = n + int(rng() % 500);
        std::vector<double> cost(static_cast<size_t>(rows));
        const double skew = 4.0 * U(rng);  // rows get costlier (or cheaper) along the part, with noise
        for (int r = 0; r < rows; ++r) cost[size_t(r)] = 0.1 + std::pow(double(r) / rows, skew) + 0.3 * U(rng);
        std::vector<int> b(size_t(n) + 1);
        for (int i = 0; i <= n; ++i) b[size_t(i)] = rows * i / n;
        std::vector<double> ms(static_cast<size_t>(n));
        auto times = [&] {
            for (int i = 0; i < n; ++i) {
                ms[size_t(i)] = 0.0;
                for (int r = b[size_t(i)]; r < b[size_t(i) + 1]; ++r) ms[size_t(i)] += cost[size_t(r)];
            }
        };
        for (int round = 0; round < 40; ++round) {
            times();
            balance_row_chunks(b, ms.data());
            ASSERT_EQ(b.front(), 0);
            ASSERT_EQ(b.back(), rows);
            for (int i = 0; i < n; ++i) ASSERT_LT(b[size_t(i)], b[size_t(i) + 1]) << "round " << round;
        }
        times();
        double total = 0.0, costliest = 0.0;
        for (double m : ms) total += m;
        for (double c : cost) costliest = std::max(costliest, c);
        for (int i = 0; i < n; ++i)
            ASSERT_NEAR(ms[size_t(i)], total / n, 2.0 * costliest)
                << "iteration " << iter << ": chunk " << i << " of " << n << ", " << rows << " rows";
    }
}

TEST_P(PipelinedReverseFastKernels, RowChunksMatchTheReference) {
    const uint64_t seed = test::test_seed(80013);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    auto compare = [&](const ReliefTexture& t, const glm::dvec3& eye, PrewarpOptions o) {
        const PrewarpCoefficients k = compute_coefficients(t.geometry, eye);
        SCOPED_TRACE(k.to_string());
        o.method = Reconstruction::pipelined;
        o.isa = Isa::generic;
        o.threads = 1;
        const PrewarpStats sr = prewarp(t, k, o, ws_ref, ref);
        o.isa = isa();
        for (const NamedPolicy& policy : kPipelinedReverse) {
            FastKernelPolicy chunks = policy.policy;
            chunks.pipelined_row_chunks = KernelChoice::always;
            const simd::testing::ScopedKernelPolicy scope(chunks);
            for (int threads : {2, 3, 4}) {
                o.threads = threads;
                // Chunks as the last pre-warp's times balanced them, then at random bounds (the part's row count
                // and number of chunks kept from the first call).
                for (int split = 0; split < 2; ++split) {
                    if (split)
                        for (std::vector<int>& b : ws_fast.chunk_bounds)
                            for (size_t i = 1; i + 1 < b.size(); ++i) {
                                const int lo = b[i - 1] + 1, hi = b.back() - int(b.size() - 1 - i);
                                b[i] = lo + int(rng() % uint64_t(hi - lo + 1));
                            }
                    const PrewarpStats sf = prewarp(t, k, o, ws_fast, fast);
                    ASSERT_EQ(first_difference(ref, fast), "")
                        << policy.name << ", threads " << threads << " split " << split;
                    ASSERT_EQ(sf.dropped, sr.dropped) << policy.name << ", threads " << threads;
                }
            }
        }
    };
    for (int i = 0, n = policy_cases(400); i < n; ++i) {
        const Case c = random_case(rng);
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + ": " + c.describe);
        compare(c.relief, c.eye, c.options);
        if (HasFatalFailure()) return;
    }
    for (int h : {1, 2, 3}) {
        for (int i = 0, n = policy_cases(20); i < n; ++i) {
            const int w = 1 + int(rng() % 100);
            const ReliefGeometry g = unit_width_geometry(w);
            const uint32_t salt = uint32_t(rng());
            const ReliefTexture t = test::make_test_relief(
                w, h, 0.0, 0.3, [&](int x, int r) { return 0.3 * hash01(x, r, salt); }, g);
            // The epipole's row: inside the rows (two parts), on a row boundary, below and above them (one part).
            const double ev = i % 4 == 0   ? U(rng) * h
                              : i % 4 == 1 ? double(int(rng() % uint64_t(h + 1)))
                              : i % 4 == 2 ? -1.0 - U(rng) * 5 * h
                                           : h + 1.0 + U(rng) * 5 * h;
            const glm::dvec3 eye = g.origin + g.a * (U(rng) * 1.4 * w - 0.2 * w) + g.b * ev + g.f() * (0.05 + U(rng));
            PrewarpOptions o;
            o.keep_outliers = i % 2 == 0;
            SCOPED_TRACE("seed " + std::to_string(seed) + " " + std::to_string(w) + "x" + std::to_string(h) +
                         " epipole row " + std::to_string(ev));
            compare(t, eye, o);
            if (HasFatalFailure()) return;
        }
    }
    for (int i = 0, n = large_cases(12); i < n; ++i) {
        const int w = 60 + int(rng() % 120), h = 60 + int(rng() % 120);
        const ReliefGeometry g = unit_width_geometry(w);
        const double f = 0.2 + U(rng);
        const ReliefTexture t = test::make_test_relief(
            w, h, 0.0, 0.3, [&](int x, int r) { return 0.3 * std::abs(std::sin(x * f)) * std::abs(std::sin(r * f)); },
            g);
        const double ev = i % 2 ? U(rng) * h : -h * (0.5 + U(rng) * 3);
        const glm::dvec3 eye = g.origin + g.a * (U(rng) * w) + g.b * ev + g.f() * (0.03 + U(rng) * 0.3);
        PrewarpOptions o;
        o.keep_outliers = i % 3 == 0;
        SCOPED_TRACE("seed " + std::to_string(seed) + " foldovers " + std::to_string(w) + "x" + std::to_string(h) +
                     " epipole row " + std::to_string(ev));
        compare(t, eye, o);
        if (HasFatalFailure()) return;
    }
}

TEST_P(PipelinedReverseFastKernels, RowChunksRecoverFromAnInterruptedPrewarp) {
    // The scratch images of the row chunks are all 0 between pre-warps (the composite clears what it copies); one
    // left with pixels by a pre-warp interrupted between its chunks and its composite is cleared before use.
    const ReliefGeometry g = unit_width_geometry(200);
    const ReliefTexture t = test::make_test_relief(
        200, 150, 0.0, 0.3,
        [](int x, int r) { return 0.3 * std::abs(std::sin(x * 0.2)) * std::abs(std::cos(r * 0.1)); }, g);
    const PrewarpCoefficients k = compute_coefficients(g, g.origin + g.a * 80.0 - g.b * 100.0 + g.f() * 0.8);
    PrewarpOptions o;
    o.method = Reconstruction::pipelined;
    o.isa = Isa::generic;
    o.threads = 1;
    PrewarpWorkspace ws_ref, ws;
    ImageRGBA8 ref, fast;
    prewarp(t, k, o, ws_ref, ref);
    o.isa = isa();
    o.threads = 2;
    FastKernelPolicy chunks;
    chunks.pipelined_row_chunks = KernelChoice::always;
    const simd::testing::ScopedKernelPolicy scope(chunks);
    prewarp(t, k, o, ws, fast);
    ASSERT_EQ(first_difference(ref, fast), "");
    ASSERT_FALSE(ws.chunk_scratch.empty());
    EXPECT_FALSE(ws.chunk_scratch_dirty);
    for (ImageRGBA8& img : ws.chunk_scratch) std::fill(img.pixels.begin(), img.pixels.end(), Rgba8{9, 9, 9, 255});
    ws.chunk_scratch_dirty = true;  // as an exception out of a chunk would leave it
    prewarp(t, k, o, ws, fast);
    EXPECT_EQ(first_difference(ref, fast), "");
    EXPECT_FALSE(ws.chunk_scratch_dirty);
}

TEST_P(PipelinedReverseFastKernels, AllocatesNothingInSteadyState) {
    const ReliefTexture t = steady_state_relief();
    const ReliefGeometry& g = t.geometry;
    PrewarpOptions o;
    o.isa = isa();
    o.method = Reconstruction::pipelined;
    o.threads = 1;
    o.keep_outliers = true;
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    // Two threads, the epipole inside the rows (two parts: column ranges) and below them (one part: row chunks and
    // their scratch images). The buffers belong to the task, whichever thread runs it: while reverse mode's were the
    // thread's, this failed now and then on a loaded machine (2 to 64 allocations), where the warm-up had run both
    // parts on one thread and the other grew its buffers in a later pre-warp.
    for (int threads : {1, 2})
        for (double ey : {0.3, -0.3})
            for (KernelChoice reverse : {KernelChoice::always, KernelChoice::automatic}) {
                const simd::testing::ScopedKernelPolicy scope(pipelined_policy(reverse));
                o.threads = threads;
                const PrewarpCoefficients k = compute_coefficients(g, {1.2, ey, 0.4});
                prewarp(t, k, o, ws, out);  // warm-up: buffers grow to size
                const long long before = g_allocations.load();
                // Three pre-warps, one where the sweeps are shortened (qemu: each takes seconds emulated).
                for (int i = 0, n = sweeps_shortened() ? 1 : 3; i < n; ++i)
                    prewarp(t, compute_coefficients(g, {1.2 + 0.01 * i, ey, 0.4}), o, ws, out);
                EXPECT_EQ(g_allocations.load() - before, 0)
                    << "reverse mode " << choice_name(reverse) << " threads " << threads << " eye y " << ey;
            }
}

// The two-pass kernel's backward rows (warp/simd/hwy_row-inl.h, WarpRowBackward: a row's items in the reverse of the
// forward order, each pixel shaded once) against the reference, on every SIMD target (TwoPassReverseFastKernels), with
// each FastKernelPolicy::two_pass_reverse: always takes every row whose samples all take part backwards (also rows
// without foldovers: copies, spans of one, two and more pixels, clipped on either side of the pixels already written),
// with two_pass_redo_forwards then redoes the row forwards (the fallback), automatic takes only rows that fold over,
// never none. Rows with empty texels or texels that cannot be pre-warped always go forwards.
TEST_P(TwoPassReverseFastKernels, RandomCasesMatchTheReference) {
    random_cases_with_policies(isa(), Reconstruction::two_pass, kTwoPassReverse, policy_cases(1200), 80021);
}

TEST_P(TwoPassReverseFastKernels, FoldoversEmptyRowsAndMarksMatchTheReference) {
    // Foldover-heavy reliefs (steep ridges across and along the rows, noise, steps onto still texels) seen from
    // grazing angles, near, from above and from below the highest texels (texels that cannot be pre-warped), the
    // epipole inside the rows, on a texel boundary, on a texel centre and outside; empty texels in some rows only,
    // so that backward and forward rows meet in one band; and the same reliefs with discontinuity marks, whose
    // marked rows the fast kernels take forwards whatever the policy says (warp/simd/hwy_two_pass.h).
    const uint64_t seed = test::test_seed(80022);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    for (int i = 0, n = large_cases(80); i < n; ++i) {
        const int w = i % 8 == 0 ? 16 * (1 + int(rng() % 12)) : 20 + int(rng() % 220), h = 30 + int(rng() % 120);
        const ReliefGeometry g = unit_width_geometry(w);
        const uint32_t salt = uint32_t(rng());
        const int kind = i % 4;
        const double f = 0.2 + U(rng);
        ReliefTexture t = test::make_test_relief(
            w, h, 0.0, 0.3,
            [&](int x, int r) -> double {
                switch (kind) {
                    case 0: return 0.3 * std::abs(2.0 * ((x * f / 4) - std::floor(x * f / 4)) - 1.0);  // ridges
                    case 1: return 0.3 * hash01(x, r, salt);                                           // noise
                    case 2: return hash01(x / 5, r / 7, salt) < 0.5 ? 0.0 : 0.3;                       // steps
                    default: return 0.3 * std::abs(std::sin(x * f)) * std::abs(std::sin(r * f * 0.3));
                }
            },
            g);
        const int empty_rows = int(rng() % 3);  // none, every fourth row, a few random rows
        for (int r = 0; r < h; ++r) {
            const bool holes = empty_rows == 1 ? r % 4 == 1 : empty_rows == 2 && hash01(r, 5, salt) < 0.2;
            if (!holes) continue;
            const int x0 = int(hash01(r, 9, salt) * w), n = 1 + int(hash01(r, 11, salt) * 4);
            for (int x = x0; x < std::min(w, x0 + n); ++x)
                t.texels.edit()[size_t(r) * size_t(w) + size_t(x)].q = kEmptyIndex;
        }
        double eu = U(rng) * w;
        switch (i % 5) {
            case 0: eu = std::floor(eu); break;           // on a texel boundary
            case 1: eu = std::floor(eu) + 0.5; break;     // over a texel centre
            case 2: eu = -w * (0.5 + U(rng) * 3); break;  // outside, left
            case 3: eu = w * (1.5 + U(rng) * 3); break;   // outside, right
            default: break;
        }
        const double ev = U(rng) * 1.6 * h - 0.3 * h;
        double dist;
        switch (i % 3) {
            case 0: dist = 0.02 + U(rng) * 0.1; break;          // grazing
            case 1: dist = 0.5 + U(rng) * 2; break;             // from above
            default: dist = 0.3 * (0.3 + U(rng) * 0.6); break;  // below the highest texels
        }
        const glm::dvec3 eye = g.origin + g.a * eu + g.b * ev + g.f() * dist;
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        PrewarpOptions o;
        o.method = Reconstruction::two_pass;
        o.keep_outliers = i % 4 != 0;
        o.isa = Isa::generic;
        o.threads = 1;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + " kind " + std::to_string(kind) +
                     " empty rows " + std::to_string(empty_rows) + " " + std::to_string(w) + "x" + std::to_string(h) +
                     " " + k.to_string());
        const PrewarpStats sr = prewarp(t, k, o, ws_ref, ref);
        o.isa = isa();
        for (const NamedPolicy& policy : kTwoPassReverse) {
            const simd::testing::ScopedKernelPolicy scope(policy.policy);
            for (int threads : {1, 3}) {
                o.threads = threads;
                for (bool copy : {true, false}) {
                    o.copy_still_runs = copy;
                    const PrewarpStats sf = prewarp(t, k, o, ws_fast, fast);
                    ASSERT_EQ(first_difference(ref, fast), "")
                        << policy.name << ", threads " << threads << " copy " << copy;
                    ASSERT_EQ(sf.dropped, sr.dropped);
                }
            }
        }
        // Discontinuity marks: marked rows forwards whatever the policy says.
        mark_discontinuities(t, 0.05);
        o.isa = Isa::generic;
        o.threads = 1;
        prewarp(t, k, o, ws_ref, ref);
        o.isa = isa();
        EXPECT_TRUE(fast_prewarp_covers(isa(), t, k, o, sr.extent, nullptr));
        for (KernelChoice reverse : {KernelChoice::automatic, KernelChoice::always}) {
            const simd::testing::ScopedKernelPolicy scope(two_pass_policy(reverse));
            for (int threads : {1, 3}) {
                o.threads = threads;
                prewarp(t, k, o, ws_fast, fast);
                ASSERT_EQ(first_difference(ref, fast), "")
                    << "marks, backward rows " << choice_name(reverse) << ", threads " << threads;
            }
        }
    }
}

TEST_P(TwoPassReverseFastKernels, AllocatesNothingInSteadyState) {
    const ReliefTexture t = steady_state_relief();
    const ReliefGeometry& g = t.geometry;
    PrewarpOptions o;
    o.isa = isa();
    o.method = Reconstruction::two_pass;
    o.threads = 1;
    o.keep_outliers = true;
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    for (const NamedPolicy& policy : kTwoPassReverse) {
        if (policy.policy.two_pass_reverse == KernelChoice::never) continue;
        const simd::testing::ScopedKernelPolicy scope(policy.policy);
        const PrewarpCoefficients k = compute_coefficients(g, {1.2, 0.3, 0.4});
        prewarp(t, k, o, ws, out);  // warm-up: buffers grow to size
        const long long before = g_allocations.load();
        for (int i = 0; i < 3; ++i) prewarp(t, compute_coefficients(g, {1.2 + 0.01 * i, 0.3, 0.4}), o, ws, out);
        EXPECT_EQ(g_allocations.load() - before, 0) << policy.name;
    }
}

TEST(FastPrewarpCovers, OnlyOutputsItsKernelsCanAddress) {
    // The column kernels scatter by 32-bit pixel offsets (StoreRows, warp/simd/hwy_columns-inl.h): outputs of
    // 2^31 - 16 pixels or more, and sides over 2^22, go to the generic kernels, on every target. Only the decision is
    // tested: no image that size is allocated.
    const ReliefTexture t = test::make_test_relief(
        16, 16, 0.0, 0.1, [](int, int) { return 0.05; }, unit_width_geometry(16));
    const PrewarpCoefficients k = compute_coefficients(t.geometry, {0.1, 0.2, 2.0});
    PrewarpOptions o;
    Isa isa = Isa::generic;
    auto covers = [&](int ow, int oh) {
        PrewarpExtent e;
        e.right = ow - 16;
        e.top = oh - 16;
        return fast_prewarp_covers(isa, t, k, o, e, nullptr);
    };
    int targets = 0;
    for (const Isa target : supported_isas()) {
        if (target == Isa::generic) continue;
        isa = target;
        ++targets;
        SCOPED_TRACE(isa_name(isa));
        EXPECT_TRUE(covers(16, 16));
        EXPECT_TRUE(covers(46340, 46340));        // 2,147,395,600 pixels: 88,032 under the limit
        EXPECT_FALSE(covers(46341, 46341));       // 2,147,488,281 pixels: over 2^31 - 16
        EXPECT_TRUE(covers(1 << 22, 511));        // the longest side, 2,143,289,344 pixels
        EXPECT_FALSE(covers((1 << 22) + 1, 16));  // a side over 2^22
        EXPECT_FALSE(covers(16, (1 << 22) + 1));
    }
    if (!targets) GTEST_SKIP() << "no SIMD target on this CPU";
}

// Surface-discontinuity marks (paper section 4.1.1: ReliefTexture::breaks and discontinuity_threshold), which the
// two-pass kernels of every SIMD target handle (TwoPassJob::breaks, threshold): the random cases above with marks from
// mark_discontinuities at a random threshold, random kBreakRight / kBreakUp bits with and without a threshold, and
// a threshold without marks, against the reference pixel by pixel: every backward-row policy, one and two threads,
// copies of still runs on and off (the vertical pass's still copies are reached: printed).
void mark_randomly(ReliefTexture& t, std::mt19937_64& rng, int mode) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const double range = t.quant.max - t.quant.min;
    // Thresholds from a fraction of a level to most of the range (0 when the range is: every texel one level).
    const double threshold = range * (U(rng) < 0.3 ? U(rng) * 0.02 : U(rng) * 0.6);
    switch (mode) {
        case 0: mark_discontinuities(t, threshold); break;
        case 1:
        case 2: {
            const double p = U(rng) * 0.5;
            t.breaks.edit().assign(t.texels.size(), 0);
            for (uint8_t& b : t.breaks.edit())
                b = uint8_t((U(rng) < p ? kBreakRight : 0) | (U(rng) < p ? kBreakUp : 0));
            t.discontinuity_threshold = mode == 2 ? threshold : 0.0;
            break;
        }
        default:
            t.breaks.clear();
            t.discontinuity_threshold = threshold;
            break;
    }
}

// The random cases with marks (mark_randomly) against the reference on target `isa`, each of `policies`, one and two
// threads, copies of still runs on and off; every covered case reports the target that ran.
template <size_t N>
void marked_random_cases(Isa isa, Reconstruction method, const NamedPolicy (&policies)[N], uint64_t seed_fallback) {
    const uint64_t seed = test::test_seed(seed_fallback);
    std::mt19937_64 rng(seed);
    // Shortened sweeps (qemu, sanitizers): the pipelined cases are a policy sweep's (policy_cases); the two-pass ones
    // keep enough cases to reach still steps along the columns (copies, below).
    const int cases = method == Reconstruction::two_pass ? test::sweep_cases(600) : policy_cases(600);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    int covered = 0;
    const long long copies_before = simd::testing::vertical_still_copies();
    for (int i = 0; i < cases; ++i) {
        Case c = random_case(rng);
        const int mode = int(rng() % 4);
        mark_randomly(c.relief, rng, mode);
        c.options.method = method;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + ": " + c.describe + " marks " +
                     std::to_string(mode) + " threshold " + std::to_string(c.relief.discontinuity_threshold));
        const PrewarpCoefficients k = compute_coefficients(c.relief.geometry, c.eye);
        PrewarpOptions o = c.options;
        o.isa = Isa::generic;
        o.threads = 1;
        const PrewarpStats sr = prewarp(c.relief, k, o, ws_ref, ref);
        o.isa = isa;
        const bool covers = fast_prewarp_covers(isa, c.relief, k, o, sr.extent, nullptr);
        covered += covers;
        for (const NamedPolicy& policy : policies) {
            const simd::testing::ScopedKernelPolicy scope(policy.policy);
            for (int threads : {1, 2})
                for (bool copy : {true, false}) {
                    o.threads = threads;
                    o.copy_still_runs = copy;
                    const PrewarpStats sf = prewarp(c.relief, k, o, ws_fast, fast);
                    ASSERT_EQ(first_difference(ref, fast), "")
                        << policy.name << ", threads " << threads << ", copy " << copy << " " << k.to_string();
                    ASSERT_EQ(sf.dropped, sr.dropped);
                    ASSERT_EQ(sf.extent, sr.extent);
                    ASSERT_EQ(sf.isa, covers ? isa : Isa::generic);
                }
        }
    }
    // Everything but the eye in the relief's plane goes through the fast kernels.
    EXPECT_GT(covered, cases * 9 / 10);
    std::printf("seed %llu: %d of %d marked cases on the fast kernels\n", (unsigned long long)seed, covered, cases);
    if (method == Reconstruction::two_pass) {
        const long long copies = simd::testing::vertical_still_copies() - copies_before;
        std::printf("%lld still pixels copied by the two-pass vertical pass\n", copies);
        EXPECT_GT(copies, 0);
    }
}

TEST_P(TwoPassReverseFastKernels, MarkedReliefsMatchTheReference) {
    marked_random_cases(isa(), Reconstruction::two_pass, kTwoPassReverse, 80041);
}

TEST_P(PipelinedReverseFastKernels, MarkedReliefsMatchTheReference) {
    marked_random_cases(isa(), Reconstruction::pipelined, kPipelinedReverse, 80043);
}

// Large marked reliefs (two-pass: many bands, the two-thread band pipeline; pipelined: row chunks and column ranges,
// the reverse mode where there is no threshold): 256^2 to 700x300 steps and noise marked at a threshold, and the same
// marks without a threshold, seen from near and far, one to three threads.
void large_marked_cases(Isa isa, Reconstruction method, uint64_t seed_fallback) {
    const uint64_t seed = test::test_seed(seed_fallback);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    PrewarpWorkspace ws_ref, ws_fast;
    ImageRGBA8 ref, fast;
    for (int i = 0, n = large_cases(12); i < n; ++i) {
        const int w = 256 + int(rng() % 450), h = 256 + int(rng() % 50);
        const ReliefGeometry g = unit_width_geometry(w);
        const uint32_t salt = uint32_t(rng());
        const int kind = i % 3;
        ReliefTexture t = test::make_test_relief(
            w, h, 0.0, 0.3,
            [&](int x, int r) -> double {
                switch (kind) {
                    case 0: return hash01(x / 8, r / 8, salt) < 0.5 ? 0.0 : 0.3;  // steps onto still texels
                    case 1: return 0.3 * hash01(x, r, salt);                      // noise
                    default: return 0.15 + 0.15 * std::sin(x * 0.05) * std::cos(r * 0.07);
                }
            },
            g);
        mark_discontinuities(t, 0.3 * (0.05 + U(rng) * 0.5));
        if (i % 4 == 3) t.discontinuity_threshold = 0.0;  // the marks alone
        const double az = (U(rng) - 0.5) * 6.0, el = 0.1 + U(rng) * 1.3, d = 0.6 + U(rng) * 3;
        const glm::dvec3 eye{d * std::cos(el) * std::sin(az), d * std::cos(el) * std::cos(az), d * std::sin(el)};
        const PrewarpCoefficients k = compute_coefficients(g, eye);
        PrewarpOptions o;
        o.method = method;
        o.isa = Isa::generic;
        o.threads = 1;
        SCOPED_TRACE("seed " + std::to_string(seed) + " case " + std::to_string(i) + " kind " + std::to_string(kind) +
                     " " + std::to_string(w) + "x" + std::to_string(h) + " " + k.to_string());
        prewarp(t, k, o, ws_ref, ref);
        o.isa = isa;
        for (int threads : {1, 2, 3}) {
            o.threads = threads;
            const PrewarpStats sf = prewarp(t, k, o, ws_fast, fast);
            ASSERT_EQ(first_difference(ref, fast), "") << "threads " << threads;
            ASSERT_EQ(sf.isa, isa) << "threads " << threads;
        }
    }
}

TEST_P(TwoPassReverseFastKernels, LargeMarkedReliefsMatchTheReference) {
    large_marked_cases(isa(), Reconstruction::two_pass, 80042);
}

TEST_P(PipelinedReverseFastKernels, LargeMarkedReliefsMatchTheReference) {
    large_marked_cases(isa(), Reconstruction::pipelined, 80044);
}

// Marked reliefs go to the fast kernels of every SIMD target, both reconstructions; marks that do not match the texels
// (a malformed relief) to the reference.
TEST(FastKernelCoverage, MarkedReliefsOnTheFastKernels) {
    ReliefTexture t = test::make_test_relief(
        32, 32, 0.0, 0.1, [](int x, int) { return x < 16 ? 0.0 : 0.1; }, unit_width_geometry(32));
    mark_discontinuities(t, 0.05);
    ASSERT_FALSE(t.breaks.empty());
    const PrewarpCoefficients k = compute_coefficients(t.geometry, {0.1, 0.2, 2.0});
    PrewarpOptions o;
    const PrewarpExtent e = prewarp_extent(t, k, o);
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    for (Isa isa : supported_isas()) {
        if (isa == Isa::generic) continue;
        for (Reconstruction method : {Reconstruction::two_pass, Reconstruction::pipelined}) {
            SCOPED_TRACE(std::string(isa_name(isa)) + " " + to_string(method));
            o.method = method;
            o.isa = isa;
            EXPECT_TRUE(fast_prewarp_covers(isa, t, k, o, e, nullptr));
            EXPECT_EQ(prewarp(t, k, o, ws, out).isa, isa);
        }
    }
    t.breaks.edit().pop_back();
    for (Isa isa : supported_isas())
        for (Reconstruction method : {Reconstruction::two_pass, Reconstruction::pipelined}) {
            o.method = method;
            EXPECT_FALSE(fast_prewarp_covers(isa, t, k, o, e, nullptr)) << isa_name(isa) << " " << to_string(method);
        }
}

// Every SIMD target this machine supports with both reconstructions.
// A target's name as a test name (letters, digits and underscores: every name is one).
std::string test_name(Isa isa) { return isa_name(isa); }

std::vector<MethodTarget> method_targets() {
    std::vector<MethodTarget> v;
    for (Isa isa : supported_isas()) {
        if (isa == Isa::generic) continue;
        v.push_back({Reconstruction::two_pass, isa});
        v.push_back({Reconstruction::pipelined, isa});
    }
    return v;
}

INSTANTIATE_TEST_SUITE_P(Targets, FastKernels, ::testing::ValuesIn(method_targets()), [](const auto& info) {
    return std::string(info.param.method == Reconstruction::two_pass ? "TwoPass_" : "Pipelined_") +
           test_name(info.param.isa);
});

// Every SIMD target this machine supports.
std::vector<Isa> simd_targets() {
    std::vector<Isa> v;
    for (Isa isa : supported_isas())
        if (isa != Isa::generic) v.push_back(isa);
    return v;
}

INSTANTIATE_TEST_SUITE_P(Targets, PipelinedReverseFastKernels, ::testing::ValuesIn(simd_targets()),
                         [](const auto& info) { return test_name(info.param); });
INSTANTIATE_TEST_SUITE_P(Targets, TwoPassReverseFastKernels, ::testing::ValuesIn(simd_targets()),
                         [](const auto& info) { return test_name(info.param); });

}  // namespace
}  // namespace rtm
