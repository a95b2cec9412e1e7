// The seed of a random sweep: RTM_SEED from the environment when set (to reproduce a failure), else the test's own
// fixed seed. Tests print the seed they use (SCOPED_TRACE) so a failure names it. And its length: RTM_SWEEP_CASES
// caps the number of cases (the first cases of the same sequence), for slow runs such as the ARM tests under qemu
// (scripts/arm.sh).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace rtm::test {

// RTM_SEED if set (a decimal number; anything else throws std::invalid_argument naming it), else `fallback`.
inline uint64_t test_seed(uint64_t fallback) {
    const char* s = std::getenv("RTM_SEED");
    if (!s) return fallback;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(s, &end, 10);
    if (*s == '\0' || *s == '-' || *end != '\0')
        throw std::invalid_argument(std::string("RTM_SEED: expected a decimal number, found \"") + s + "\"");
    return v;
}

// `full`, or RTM_SWEEP_CASES when that is set and smaller (a positive decimal number; anything else throws
// std::invalid_argument naming it).
inline int sweep_cases(int full) {
    const char* s = std::getenv("RTM_SWEEP_CASES");
    if (!s) return full;
    char* end = nullptr;
    const long v = std::strtol(s, &end, 10);
    if (*s == '\0' || *end != '\0' || v <= 0)
        throw std::invalid_argument(std::string("RTM_SWEEP_CASES: expected a positive decimal number, found \"") + s +
                                    "\"");
    return v < full ? int(v) : full;
}

}  // namespace rtm::test
