// The check every reader's hostile-input test makes: fn throws rtm::IoError with one line that starts with the
// file's path and names what is wrong (every substring of `parts`).
#pragma once

#include <gtest/gtest.h>

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

}  // namespace rtm::objects_testing
