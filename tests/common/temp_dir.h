// Test helpers for tests/objects: a fresh temporary folder per test, removed afterwards, and small file writers.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace rtm::objects_testing {

// A folder under the system's temporary directory, unique per process, test and instance.
class TempDir {
public:
    TempDir() {
        static std::atomic<unsigned> counter{0};
        std::string test = "test";
        if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
            test = std::string(info->test_suite_name()) + "." + info->name();
        for (char& ch : test)
            if (ch == '/') ch = '_';
        path_ = std::filesystem::temp_directory_path() /
                ("rtm-objects-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1)) + "-" + test);
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

inline void write_file(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
    ASSERT_TRUE(out.good()) << "cannot write " << path;
}

inline std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace rtm::objects_testing
