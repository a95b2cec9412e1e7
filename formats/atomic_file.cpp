#include "formats/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace rtm {

namespace fs = std::filesystem;

namespace {

std::string temp_name_for(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const fs::path p(path);
    // Built with += : GCC 12 gives a false -Wrestrict warning for "." + std::string&&.
    std::string name = ".";
    name += p.filename().string();
    name += ".tmp";
    name += std::to_string(::getpid());
    name += "-";
    name += std::to_string(counter.fetch_add(1));
    return (p.parent_path() / name).string();
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), temp_(temp_name_for(path_)) {}

AtomicFile::~AtomicFile() {
    if (committed_) return;
    std::error_code ignore;
    fs::remove(temp_, ignore);
}

void AtomicFile::commit() {
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
        const int err = errno;
        std::error_code ignore;
        fs::remove(temp_, ignore);
        throw_io_error(path_, std::string("cannot write: rename from temporary file failed: ") + std::strerror(err));
    }
    committed_ = true;
}

void write_text_atomically(const std::string& path, const std::string& text) {
    AtomicFile file(path);
    {
        std::ofstream out(file.temp_path(), std::ios::binary | std::ios::trunc);
        if (!out) throw_io_error(path, std::string("cannot write: ") + std::strerror(errno));
        out << text;
        out.flush();
        if (!out) throw_io_error(path, std::string("cannot write: ") + std::strerror(errno));
    }
    file.commit();
}

}  // namespace rtm
