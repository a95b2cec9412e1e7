// What the libFuzzer targets share: a private scratch folder, file writers, and the rule for what counts as a
// finding.
//
// The readers under test must reject bad input by throwing rtm::IoError with one line naming the file. Anything else
// is a finding: a crash, a sanitizer report, a hang or an out-of-memory (libFuzzer's -timeout and -rss_limit_mb),
// an exception of another type, or an IoError whose message is not one line starting with the file's path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

namespace rtm::fuzz {

// Once per process: points sanitizer reports at a duplicate of the original stderr. A program that opts in to
// set_quiet_image_library_stderr (formats/image_io.h) sends stderr to /dev/null while OpenImageIO runs, which would
// otherwise swallow a report from inside it.
void init_reports();

// A folder of its own under $TMPDIR, created on first use and removed at exit.
const std::string& scratch_dir();
std::string scratch_file(const std::string& name);

// Writes the bytes, or aborts: failing to write the scratch folder is a broken setup, not a finding.
void write_file(const std::string& path, std::string_view bytes);

// Runs fn. An rtm::IoError whose message is one line starting with "<path>: " is the expected outcome of bad input
// (returns false); fn returning normally returns true. Everything else prints what happened and aborts, which
// libFuzzer records as a crash with the input that caused it.
bool expect_ok_or_io_error(const std::string& path, const std::function<void()>& fn);

}  // namespace rtm::fuzz
