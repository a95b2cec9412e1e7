// Which SIMD target runs the pre-warp kernels: the one user-facing choice of the kernels (PrewarpOptions::isa),
// its names on the command line (--isa) and in the RTM_ISA environment variable, and what this CPU and build
// support.
//
// Targets: the kernels written once over Google Highway (warp/simd/hwy_*) for avx512 (Highway's AVX3_DL target on a
// CPU with AVX-512 F/BW/DQ/VL/VBMI/VNNI and BMI2: Ice Lake and later, Zen 4 and later), avx3 (Highway's AVX3 target:
// AVX-512 F/BW/DQ/VL lacking VBMI or VNNI, as on Skylake-X and Cascade Lake; the byte-permute table lookups and
// VNNI colour products of avx512 are gathers and 16-bit products there), avx2 and sse4 on x86-64, neon and sve on
// ARM; and generic (the reference kernels, warp/reference/, which every other target matches bit for bit). A target
// covers what its kernels implement (fast_prewarp_covers, warp/simd/schedule.h); a pre-warp it does not cover runs on
// the reference kernels, and PrewarpStats::isa says which ran.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rtm {

enum class Isa { automatic, avx512, avx3, avx2, sse4, neon, sve, generic };

// "avx512", "avx3", "avx2", "sse4", "neon", "sve", "generic" ("auto" for automatic).
const char* isa_name(Isa isa);

// The target named `name` (one of isa_name's, "auto" included); false for any other name.
bool parse_isa(std::string_view name, Isa& isa);

// "avx512, avx3, avx2, sse4, neon, sve, generic": the names, for messages.
std::string isa_names();

// The targets this CPU and this build can run, fastest first (on ARM neon before sve: warp/isa.cpp), generic last.
// Honours set_hwy_targets_for_test (the tests force each Highway target in turn).
std::vector<Isa> supported_isas();
bool isa_supported(Isa isa);

// The target `automatic` stands for: RTM_ISA when it is set and not empty, else the first of supported_isas().
// Throws std::invalid_argument naming RTM_ISA and its value when that names no target or one this CPU lacks.
Isa default_isa();

// `isa` itself, or default_isa() for automatic. Throws std::invalid_argument naming the target when this CPU or
// build cannot run it.
Isa resolve_isa(Isa isa);

// Whether AVX2's masked store (vpmaskmovd, vmaskmovps to memory) is slow on this CPU: AMD's and Hygon's cores up to
// Zen 4 (CPUID family 0x19 and below) run it as 42 micro-ops that hold the store pipe for 12 cycles (uops.info's
// measurements; LLVM's znver3 and znver4 scheduling models), where Intel's cores and Zen 5 store in about a cycle.
// The avx2 kernels then load, blend and store whole vectors they own instead (warp/simd/hwy_columns-inl.h,
// StoreOwned); measured on a Zen 4 guest, the masked stores took 1.06x to 1.53x that time (docs/BENCHMARKS.md, "The
// SIMD targets on a Zen 4 guest"). From CPUID's vendor and family, detected once; false on other architectures.
bool avx2_masked_store_slow();
// The rule itself: `vendor` CPUID's 12-character vendor string, `family` the display family (base plus extended).
bool avx2_masked_store_slow(std::string_view vendor, unsigned family);

// hwy::SupportedTargets(), detected once: Highway 1.0.3 runs CPUID on every call unless a test set the targets, 5.6
// us a call in a virtual machine (where CPUID traps), and every pre-warp asks (2% of a 256^2 one, more of smaller).
int64_t hwy_supported_targets();
// hwy::SetSupportedTargetsForTest(targets) (0: the CPU's own again); hwy_supported_targets() then asks again.
void set_hwy_targets_for_test(int64_t targets);

}  // namespace rtm
