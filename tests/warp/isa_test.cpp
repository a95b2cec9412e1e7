// The choice of SIMD target (warp/isa.h): names, what this CPU supports, RTM_ISA, and PrewarpStats::isa naming the
// target that ran.
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "test_util.h"
#include "warp/isa.h"
#include "warp/prewarp.h"
#include "warp/simd/hwy_two_pass.h"

namespace rtm {
namespace {

// Restores RTM_ISA and Highway's supported targets at the end of a test.
class IsaTest : public ::testing::Test {
protected:
    void SetUp() override {
        const char* v = std::getenv("RTM_ISA");
        had_ = v != nullptr;
        if (v) saved_ = v;
        unsetenv("RTM_ISA");
    }
    void TearDown() override {
        if (had_)
            setenv("RTM_ISA", saved_.c_str(), 1);
        else
            unsetenv("RTM_ISA");
        set_hwy_targets_for_test(0);  // 0: the CPU's own again
    }
    bool had_ = false;
    std::string saved_;
};

TEST_F(IsaTest, NamesRoundTrip) {
    for (Isa i : {Isa::automatic, Isa::avx512, Isa::avx3, Isa::avx2, Isa::sse4, Isa::neon, Isa::sve, Isa::generic}) {
        Isa back = Isa::generic;
        ASSERT_TRUE(parse_isa(isa_name(i), back)) << isa_name(i);
        EXPECT_EQ(back, i);
    }
    Isa x = Isa::sse4;
    EXPECT_FALSE(parse_isa("avx", x));
    EXPECT_FALSE(parse_isa("", x));
    EXPECT_FALSE(parse_isa("AVX2", x));
    EXPECT_FALSE(parse_isa("avx512-hwy",
                           x));  // the Highway AVX-512 target's name while hand-written kernels were avx512
    EXPECT_EQ(x, Isa::sse4);
    EXPECT_FALSE(parse_isa("AVX3", x));
    EXPECT_EQ(isa_names(), "avx512, avx3, avx2, sse4, neon, sve, generic");
}

TEST_F(IsaTest, GenericIsAlwaysSupportedAndLast) {
    const std::vector<Isa> v = supported_isas();
    ASSERT_FALSE(v.empty());
    EXPECT_EQ(v.back(), Isa::generic);
    for (Isa i : v) EXPECT_TRUE(isa_supported(i)) << isa_name(i);
    EXPECT_EQ(default_isa(), v.front());
    EXPECT_EQ(resolve_isa(Isa::automatic), v.front());
    EXPECT_EQ(resolve_isa(Isa::generic), Isa::generic);
#if defined(__x86_64__)
    EXPECT_FALSE(isa_supported(Isa::neon));
    EXPECT_THROW(resolve_isa(Isa::neon), std::invalid_argument);
#elif defined(__aarch64__)
    EXPECT_FALSE(isa_supported(Isa::avx2));
    EXPECT_FALSE(isa_supported(Isa::avx512));  // not compiled on ARM
    EXPECT_FALSE(isa_supported(Isa::avx3));
    EXPECT_THROW(resolve_isa(Isa::avx2), std::invalid_argument);
    EXPECT_TRUE(isa_supported(Isa::neon));  // every 64-bit ARM CPU has NEON
#endif
}

TEST_F(IsaTest, ForcedHighwayTargetsRestrictTheChoice) {
#if defined(__x86_64__)
    if (!isa_supported(Isa::avx2)) GTEST_SKIP() << "no AVX2 on this CPU";
    const bool avx512 = isa_supported(Isa::avx512);
    const bool avx3 = isa_supported(Isa::avx3);
    // AVX3_DL's CPUs have AVX3 (where the build has the avx3 target: the sanitizer build leaves it out).
    EXPECT_TRUE(!avx512 || avx3 || !(simd::hwy_compiled_targets() & HWY_AVX3));
    set_hwy_targets_for_test(HWY_SSE4);        // as on a CPU with SSE4 but no AVX2
    EXPECT_FALSE(isa_supported(Isa::avx512));  // a Highway target too (AVX3_DL)
    EXPECT_FALSE(isa_supported(Isa::avx3));
    EXPECT_FALSE(isa_supported(Isa::avx2));
    EXPECT_TRUE(isa_supported(Isa::sse4));
    EXPECT_EQ(default_isa(), Isa::sse4);
    if (avx3) {
        // As on Skylake-X or Cascade Lake: AVX-512 without VBMI/VNNI, the avx3 target first.
        set_hwy_targets_for_test(HWY_AVX3 | HWY_AVX2 | HWY_SSE4);
        EXPECT_FALSE(isa_supported(Isa::avx512));
        EXPECT_TRUE(isa_supported(Isa::avx3));
        EXPECT_EQ(default_isa(), Isa::avx3);
        EXPECT_EQ(supported_isas(), (std::vector<Isa>{Isa::avx3, Isa::avx2, Isa::sse4, Isa::generic}));
    }
    set_hwy_targets_for_test(0);
    EXPECT_TRUE(isa_supported(Isa::avx2));
    EXPECT_EQ(isa_supported(Isa::avx512), avx512);
    EXPECT_EQ(isa_supported(Isa::avx3), avx3);
#elif defined(__aarch64__)
    if (!isa_supported(Isa::sve)) GTEST_SKIP() << "no SVE on this CPU";
    set_hwy_targets_for_test(HWY_NEON);  // as on a CPU with NEON but no SVE
    EXPECT_FALSE(isa_supported(Isa::sve));
    EXPECT_TRUE(isa_supported(Isa::neon));
    EXPECT_EQ(default_isa(), Isa::neon);
    set_hwy_targets_for_test(0);
    EXPECT_TRUE(isa_supported(Isa::sve));
    // With both, automatic keeps neon (warp/isa.cpp: SVE's instruction counts do not favour it); sve when asked.
    EXPECT_EQ(default_isa(), Isa::neon);
    EXPECT_EQ(supported_isas(), (std::vector<Isa>{Isa::neon, Isa::sve, Isa::generic}));
    EXPECT_EQ(resolve_isa(Isa::sve), Isa::sve);
#else
    GTEST_SKIP() << "x86-64 and ARM targets";
#endif
}

TEST_F(IsaTest, EnvironmentChoosesForAutomatic) {
    setenv("RTM_ISA", "generic", 1);
    EXPECT_EQ(default_isa(), Isa::generic);
    setenv("RTM_ISA", "auto", 1);
    EXPECT_EQ(default_isa(), supported_isas().front());
    setenv("RTM_ISA", "", 1);
    EXPECT_EQ(default_isa(), supported_isas().front());
    setenv("RTM_ISA", "mmx", 1);
    try {
        default_isa();
        FAIL() << "RTM_ISA=mmx accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("RTM_ISA"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("mmx"), std::string::npos) << e.what();
    }
#if defined(__x86_64__)
    setenv("RTM_ISA", "neon", 1);
    EXPECT_THROW(default_isa(), std::invalid_argument);
#endif
}

TEST_F(IsaTest, StatsNameTheTargetThatRan) {
    const ReliefTexture t = test::make_test_relief(40, 30, 0.0, 0.2, [](int x, int) { return 0.02 * (x % 5); });
    const PrewarpCoefficients k = compute_coefficients(t.geometry, {0.3, 0.2, 0.8});
    PrewarpWorkspace ws;
    ImageRGBA8 out;
    for (Isa isa : supported_isas()) {
        PrewarpOptions o;
        o.isa = isa;
        EXPECT_EQ(prewarp(t, k, o, ws, out).isa, isa) << isa_name(isa);
        o.exact = true;  // the reference kernels' path on every target
        EXPECT_EQ(prewarp(t, k, o, ws, out).isa, Isa::generic) << isa_name(isa);
        o.exact = false;
        o.method = Reconstruction::pipelined;
        EXPECT_EQ(prewarp(t, k, o, ws, out).isa, isa) << isa_name(isa);
    }
    // RTM_ISA chooses for automatic.
    setenv("RTM_ISA", "generic", 1);
    EXPECT_EQ(prewarp(t, k, PrewarpOptions{}, ws, out).isa, Isa::generic);
}

// AVX2's masked store is microcoded on AMD's and Hygon's cores up to Zen 4 (family 0x19), fast on Intel's and on Zen 5
// (family 0x1A): the avx2 kernels' choice of stores (warp/isa.h).
TEST(Avx2MaskedStore, SlowOnAmdAndHygonUpToZen4) {
    EXPECT_TRUE(avx2_masked_store_slow("AuthenticAMD", 0x15));   // Excavator
    EXPECT_TRUE(avx2_masked_store_slow("AuthenticAMD", 0x17));   // Zen, Zen 2
    EXPECT_TRUE(avx2_masked_store_slow("HygonGenuine", 0x18));   // Dhyana (Zen)
    EXPECT_TRUE(avx2_masked_store_slow("AuthenticAMD", 0x19));   // Zen 3, Zen 4
    EXPECT_FALSE(avx2_masked_store_slow("AuthenticAMD", 0x1A));  // Zen 5
    EXPECT_FALSE(avx2_masked_store_slow("GenuineIntel", 6));
    EXPECT_FALSE(avx2_masked_store_slow("CentaurHauls", 6));
    EXPECT_FALSE(avx2_masked_store_slow("", 0));
}

// This CPU's answer (CPUID read by avx2_masked_store_slow()) is the rule's for the vendor and display family Linux
// reports in /proc/cpuinfo, which it computes from the same CPUID words independently: checks the decoding of the
// vendor string and of the extended family.
TEST(Avx2MaskedStore, ThisCpuMatchesProcCpuinfo) {
#if defined(__x86_64__) || defined(__i386__)
    std::ifstream in("/proc/cpuinfo");
    if (!in) GTEST_SKIP() << "no /proc/cpuinfo";
    std::string line, vendor;
    long family = -1;
    while (std::getline(in, line) && (vendor.empty() || family < 0)) {
        const size_t colon = line.find(": ");
        if (colon == std::string::npos) continue;
        if (line.rfind("vendor_id", 0) == 0) vendor = line.substr(colon + 2);
        if (line.rfind("cpu family", 0) == 0) family = std::stol(line.substr(colon + 2));
    }
    if (vendor.empty() || family < 0) GTEST_SKIP() << "/proc/cpuinfo names no vendor_id or cpu family";
    EXPECT_EQ(avx2_masked_store_slow(), avx2_masked_store_slow(vendor, unsigned(family))) << vendor << " " << family;
#else
    EXPECT_FALSE(avx2_masked_store_slow());  // AVX2 is x86's
#endif
}

}  // namespace
}  // namespace rtm
