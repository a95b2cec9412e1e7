// Environment variables set for one scope, and unset at its end (the readers' limits: RTM_MESH_READER_SECONDS, ...).
#pragma once

#include <cstdlib>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace rtm::test {

struct ScopedEnv {
    std::vector<std::string> names;
    ScopedEnv(std::initializer_list<std::pair<const char*, const char*>> vars) {
        for (const auto& [k, v] : vars) {
            setenv(k, v, 1);
            names.emplace_back(k);
        }
    }
    ~ScopedEnv() {
        for (const std::string& k : names) unsetenv(k.c_str());
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;
};

}  // namespace rtm::test
