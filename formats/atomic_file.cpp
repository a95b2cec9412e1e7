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

// The file a path names once symbolic links are followed (a link's relative target is relative to the link's folder);
// the path itself when it is no link or does not exist. A chain of more than 40 links is left as it is (the rename
// then replaces the last link reached, as the kernel refuses such chains anyway).
std::string follow_links(const std::string& path) {
    fs::path p(path);
    std::error_code ec;
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        const fs::path target = fs::read_symlink(p, ec);
        if (ec) break;
        p = target.is_absolute() ? target : p.parent_path() / target;
    }
    return p.string();
}

}  // namespace

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), target_(follow_links(path_)), temp_(temp_name_for(target_)) {
    std::error_code ec;
    if (fs::is_directory(target_, ec)) throw_io_error(path_, "is a directory");
}

AtomicFile::~AtomicFile() {
    if (committed_) return;
    std::error_code ignore;
    fs::remove(temp_, ignore);
}

void AtomicFile::commit() {
    if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
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
