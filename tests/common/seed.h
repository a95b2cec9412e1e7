// The seed of a random sweep: RTM_SEED from the environment when set (to reproduce a failure), else the test's own
// fixed seed. Tests print the seed they use (SCOPED_TRACE) so a failure names it.
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

}  // namespace rtm::test
