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

std::string output_target(const std::string& path) {
    fs::path p(path);
    std::error_code ec;
    for (int hops = 0; fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        if (hops == 40) throw_io_error(path, "cannot write: too many levels of symbolic links (a loop?)");
        const fs::path target = fs::read_symlink(p, ec);
        if (ec) throw_io_error(path, "cannot write: cannot read the link: " + ec.message());
        p = target.is_absolute() ? target : p.parent_path() / target;
    }
    return p.string();
}

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), target_(output_target(path_)), temp_(temp_name_for(target_)) {
    std::error_code ec;
    const fs::file_status st = fs::status(target_, ec);
    if (fs::is_directory(st)) throw_io_error(path_, "is a directory");
    // A device, FIFO or socket would be replaced by a regular file (as root, --json /dev/null would replace the
    // system's /dev/null): rtm writes regular files only.
    if (fs::exists(st) && !fs::is_regular_file(st))
        throw_io_error(path_, "cannot write: it is not a regular file (a device, FIFO or socket); rtm writes files");
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
