#include "fuzz_util.h"

#include <sanitizer/common_interface_defs.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <typeinfo>

#include "formats/image_io.h"

namespace rtm::fuzz {

namespace fs = std::filesystem;

void init_reports() {
    static const int fd = ::dup(STDERR_FILENO);
    if (fd >= 0) __sanitizer_set_report_fd(reinterpret_cast<void*>(static_cast<intptr_t>(fd)));
}

const std::string& scratch_dir() {
    // Never destroyed: the exit handler that removes the folder runs after static destructors would have.
    static const std::string* dir = [] {
        std::string tmpl = (fs::temp_directory_path() / "rtm-fuzz-XXXXXX").string();
        if (!::mkdtemp(tmpl.data())) {
            std::perror("rtm fuzz: mkdtemp");
            std::abort();
        }
        std::atexit([] {
            std::error_code ignore;
            fs::remove_all(*dir, ignore);
        });
        return new std::string(tmpl);
    }();
    return *dir;
}

std::string scratch_file(const std::string& name) { return (fs::path(scratch_dir()) / name).string(); }

void write_file(const std::string& path, std::string_view bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) {
        std::fprintf(stderr, "rtm fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
}

bool expect_ok_or_io_error(const std::string& path, const std::function<void()>& fn) {
    try {
        fn();
        return true;
    } catch (const IoError& e) {
        const std::string msg = e.what();
        if (msg.rfind(path + ": ", 0) == 0 && msg.find('\n') == std::string::npos) return false;
        std::fprintf(stderr, "FINDING: rtm::IoError message is not one line starting with \"%s: \": %s\n", path.c_str(),
                     msg.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "FINDING: exception other than rtm::IoError (%s): %s\n", typeid(e).name(), e.what());
    } catch (...) {
        std::fprintf(stderr, "FINDING: exception of an unknown type\n");
    }
    std::abort();
}

}  // namespace rtm::fuzz
