#include "warp/isa.h"

#include <hwy/targets.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

#include "warp/simd/fast_tables.h"
#include "warp/simd/hwy_two_pass.h"

namespace rtm {

namespace {

// In the order `automatic` prefers them. On ARM neon comes before sve: counted under qemu (docs/BENCHMARKS.md, "ARM:
// instructions counted under qemu"), a pre-warp with 128-bit SVE (Neoverse V2 and N2, whose vector pipes are 128 bits
// wide for either) runs 1.09x to 1.24x NEON's instructions; with 256-bit SVE (Neoverse V1) 0.64x to 0.73x, but V1's
// two 256-bit pipes run four 128-bit NEON operations a cycle or two SVE ones, the same bits, so the count does not
// favour it there either.
constexpr Isa kAll[] = {Isa::avx512, Isa::avx3, Isa::avx2, Isa::sse4, Isa::neon, Isa::sve, Isa::generic};

// The Highway targets that stand for `isa` (0 for generic).
int64_t hwy_bits(Isa isa) {
    switch (isa) {
        case Isa::avx512: return HWY_AVX3_DL;
        case Isa::avx3: return HWY_AVX3;
        case Isa::avx2: return HWY_AVX2;
        case Isa::sse4: return HWY_SSE4;
        case Isa::neon: return HWY_NEON;
        case Isa::sve: return HWY_SVE | HWY_SVE2;
        default: return 0;
    }
}

std::atomic<int64_t> g_hwy_targets{0};  // 0: not detected (Highway always supports at least one target)

}  // namespace

int64_t hwy_supported_targets() {
    int64_t t = g_hwy_targets.load(std::memory_order_relaxed);
    if (!t) {
        t = hwy::SupportedTargets();
        g_hwy_targets.store(t, std::memory_order_relaxed);
    }
    return t;
}

bool avx2_masked_store_slow(std::string_view vendor, unsigned family) {
    return (vendor == "AuthenticAMD" || vendor == "HygonGenuine") && family <= 0x19;
}

bool avx2_masked_store_slow() {
    static const bool slow = [] {
#if defined(__x86_64__) || defined(__i386__)
        unsigned a = 0, b = 0, c = 0, d = 0;
        if (!__get_cpuid(0, &a, &b, &c, &d)) return false;
        char vendor[12];
        std::memcpy(vendor, &b, 4);
        std::memcpy(vendor + 4, &d, 4);
        std::memcpy(vendor + 8, &c, 4);
        if (!__get_cpuid(1, &a, &b, &c, &d)) return false;
        const unsigned base = (a >> 8) & 0xF, family = base == 0xF ? base + ((a >> 20) & 0xFF) : base;
        return avx2_masked_store_slow(std::string_view(vendor, 12), family);
#else
        return false;
#endif
    }();
    return slow;
}

void set_hwy_targets_for_test(int64_t targets) {
    hwy::SetSupportedTargetsForTest(targets);
    g_hwy_targets.store(0, std::memory_order_relaxed);
}

const char* isa_name(Isa isa) {
    switch (isa) {
        case Isa::automatic: return "auto";
        case Isa::avx512: return "avx512";
        case Isa::avx3: return "avx3";
        case Isa::avx2: return "avx2";
        case Isa::sse4: return "sse4";
        case Isa::neon: return "neon";
        case Isa::sve: return "sve";
        case Isa::generic: return "generic";
    }
    return "?";
}

bool parse_isa(std::string_view name, Isa& isa) {
    if (name == "auto") {
        isa = Isa::automatic;
        return true;
    }
    for (Isa i : kAll)
        if (name == isa_name(i)) {
            isa = i;
            return true;
        }
    return false;
}

std::string isa_names() {
    std::string s;
    for (Isa i : kAll) s += std::string(s.empty() ? "" : ", ") + isa_name(i);
    return s;
}

bool isa_supported(Isa isa) {
    switch (isa) {
        case Isa::automatic:
        case Isa::generic: return true;
        // Highway's AVX3_DL target on a CPU with what the kernels use besides: AVX-512 VNNI, which Highway 1.0.3's
        // AVX3_DL does not enable (it names avxvnni), and BMI2, both checked by fast::cpu_supported.
        case Isa::avx512:
            if (!fast::cpu_supported()) return false;
            [[fallthrough]];
        default: return (hwy_supported_targets() & simd::hwy_compiled_targets() & hwy_bits(isa)) != 0;
    }
}

std::vector<Isa> supported_isas() {
    std::vector<Isa> v;
    for (Isa i : kAll)
        if (isa_supported(i)) v.push_back(i);
    return v;
}

Isa default_isa() {
    const char* env = std::getenv("RTM_ISA");
    if (env && *env) {
        Isa isa;
        if (!parse_isa(env, isa))
            throw std::invalid_argument(std::string("RTM_ISA: unknown target \"") + env + "\"; known: auto, " +
                                        isa_names());
        if (isa != Isa::automatic) {
            if (!isa_supported(isa)) {
                std::string have;
                for (Isa i : supported_isas()) have += std::string(have.empty() ? "" : ", ") + isa_name(i);
                throw std::invalid_argument(std::string("RTM_ISA: this CPU cannot run target \"") + env +
                                            "\"; it runs: " + have);
            }
            return isa;
        }
    }
    for (Isa i : kAll)  // the first of supported_isas(), without allocating (prewarp() calls this every time)
        if (isa_supported(i)) return i;
    return Isa::generic;
}

Isa resolve_isa(Isa isa) {
    if (isa == Isa::automatic) return default_isa();
    if (!isa_supported(isa))
        throw std::invalid_argument(std::string("isa: this CPU cannot run target \"") + isa_name(isa) + "\"");
    return isa;
}

}  // namespace rtm
