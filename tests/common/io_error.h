// The check every reader's hostile-input test makes: fn throws rtm::IoError with one line that starts with the
// file's path and names what is wrong (every substring of `parts`).
#pragma once

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <functional>
#include <string>
#include <vector>

#include "formats/image_io.h"  // IoError

namespace rtm::objects_testing {

inline void expect_io_error(const std::function<void()>& fn, const std::string& path,
                            const std::vector<std::string>& parts, const std::string& label) {
    SCOPED_TRACE(label);
    try {
        fn();
        ADD_FAILURE() << "no exception for " << label;
    } catch (const IoError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << "message does not start with the path: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "message is not one line: " << msg;
        for (const std::string& p : parts)
            EXPECT_NE(msg.find(p), std::string::npos) << "missing \"" << p << "\" in: " << msg;
    } catch (const std::exception& e) {
        ADD_FAILURE() << label << ": expected rtm::IoError, got another exception: " << e.what();
    }
}

// A reader of a small text file (a manifest, a planes file, a camera path) refuses what is not a regular file without
// opening it: a FIFO (a read would wait for a writer for ever), a device (/dev/zero never ends), a folder and a
// missing file, each with one line naming the path. `read(path)` reads the file; `dir` is an empty temporary folder.
inline void expect_refuses_non_regular_files(const std::function<void(const std::string&)>& read,
                                             const std::string& dir) {
    const std::string fifo = dir + "/fifo.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::pair<std::string, std::string> cases[] = {{fifo, "is not a regular file"},
                                                         {"/dev/zero", "is not a regular file"},
                                                         {dir, "is a directory"},
                                                         {dir + "/none.json", "No such file"}};
    for (const auto& [path, want] : cases) expect_io_error([&, p = path] { read(p); }, path, {want}, path);
}

}  // namespace rtm::objects_testing
