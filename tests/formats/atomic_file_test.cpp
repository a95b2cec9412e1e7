// One atomic file writer (formats/atomic_file.h): whole files or nothing, a unique temporary name per write so that
// concurrent writers of one path do not collide, no temporary file left behind.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "common/temp_dir.h"
#include "formats/atomic_file.h"

namespace rtm {
namespace {

using objects_testing::read_file;
using objects_testing::TempDir;

size_t files_in(const std::filesystem::path& dir) {
    size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) n += e.is_regular_file() ? 1 : 0;
    return n;
}

TEST(AtomicFile, WritesTheWholeTextAndLeavesNoTemporaryFile) {
    TempDir dir;
    const std::string path = dir.file("a.txt");
    write_text_atomically(path, "first");
    write_text_atomically(path, "second, longer");
    EXPECT_EQ(read_file(path), "second, longer");
    EXPECT_EQ(files_in(dir.path()), 1u);
}

// Symbolic links are written through: the file a link names is replaced and the link stays, also for a chain of
// links and a link to a file in another folder (the temporary file goes beside the target, so the rename stays on
// its file system). A link to a folder, a FIFO and a loop of links are refused and left as they are.
TEST(AtomicFile, LinksAreWrittenThroughAndOtherFilesRefused) {
    namespace fs = std::filesystem;
    TempDir dir;
    fs::create_directory(dir.path() / "sub");
    write_text_atomically(dir.file("sub/target.json"), "old");
    fs::create_symlink("sub/target.json", dir.path() / "link1.json");
    fs::create_symlink("link1.json", dir.path() / "link2.json");
    write_text_atomically(dir.file("link2.json"), "through two links");
    EXPECT_TRUE(fs::is_symlink(dir.path() / "link1.json"));
    EXPECT_TRUE(fs::is_symlink(dir.path() / "link2.json"));
    EXPECT_EQ(read_file(dir.file("sub/target.json")), "through two links");
    EXPECT_EQ(files_in(dir.path() / "sub"), 1u);  // no temporary file left beside the target

    fs::create_symlink("sub", dir.path() / "folder_link");
    ASSERT_EQ(::mkfifo(dir.file("fifo").c_str(), 0600), 0);
    fs::create_symlink("loop_b", dir.path() / "loop_a");
    fs::create_symlink("loop_a", dir.path() / "loop_b");
    const std::pair<const char*, const char*> refused[] = {{"folder_link", "is a directory"},
                                                           {"fifo", "not a regular file"},
                                                           {"loop_a", "too many levels of symbolic links"}};
    for (const auto& [name, want] : refused) {
        try {
            write_text_atomically(dir.file(name), "x");
            ADD_FAILURE() << "wrote " << name;
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
        }
    }
    EXPECT_TRUE(fs::is_symlink(dir.path() / "folder_link"));
    EXPECT_TRUE(fs::is_fifo(dir.path() / "fifo"));
    EXPECT_TRUE(fs::is_symlink(dir.path() / "loop_a"));
}

TEST(AtomicFile, TemporaryNamesAreUniqueAndBesideTheFile) {
    TempDir dir;
    const std::string path = dir.file("b.json");
    const AtomicFile a(path), b(path);
    EXPECT_NE(a.temp_path(), b.temp_path());
    EXPECT_EQ(std::filesystem::path(a.temp_path()).parent_path(), dir.path());
}

TEST(AtomicFile, UncommittedTemporaryIsRemovedAndTheFileKept) {
    TempDir dir;
    const std::string path = dir.file("c.txt");
    write_text_atomically(path, "old");
    {
        AtomicFile f(path);
        std::ofstream(f.temp_path()) << "half";
        EXPECT_EQ(files_in(dir.path()), 2u);
    }  // a writer that failed before commit
    EXPECT_EQ(read_file(path), "old");
    EXPECT_EQ(files_in(dir.path()), 1u);
}

TEST(AtomicFile, FailureNamesTheFile) {
    TempDir dir;
    const std::string path = dir.file("missing/d.txt");
    try {
        write_text_atomically(path, "x");
        FAIL() << "no error";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path + ": cannot write: ", 0), 0u) << e.what();
    }
    EXPECT_EQ(files_in(dir.path()), 0u);
}

// Two writers of one path at once, in threads and in processes (a fixed "path.tmp" made them write into one
// temporary file and rename it under each other): every write succeeds and the file is always one whole text.
TEST(AtomicFile, ConcurrentWritersOfOnePathDoNotCollide) {
    TempDir dir;
    const std::string path = dir.file("shared.json");
    const std::string a(1 << 16, 'a'), b(1 << 17, 'b');
    constexpr int kWrites = 100;
    std::vector<std::string> errors(2);
    auto writer = [&](int id) {
        for (int i = 0; i < kWrites; ++i) {
            try {
                write_text_atomically(path, id == 0 ? a : b);
            } catch (const std::exception& e) {
                errors[size_t(id)] = e.what();
                return;
            }
            const std::string got = read_file(path);
            if (got != a && got != b) {
                errors[size_t(id)] = "a partial file of " + std::to_string(got.size()) + " bytes";
                return;
            }
        }
    };
    std::thread t0(writer, 0), t1(writer, 1);
    t0.join();
    t1.join();
    EXPECT_EQ(errors[0], "");
    EXPECT_EQ(errors[1], "");
    // Processes: the temporary names differ by process id.
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        int status = 0;
        for (int i = 0; i < kWrites; ++i) {
            try {
                write_text_atomically(path, a);
            } catch (...) {
                status = 1;
            }
        }
        ::_exit(status);
    }
    for (int i = 0; i < kWrites; ++i) {
        ASSERT_NO_THROW(write_text_atomically(path, b));
        const std::string got = read_file(path);
        ASSERT_TRUE(got == a || got == b) << got.size() << " bytes";
    }
    int status = -1;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
    EXPECT_EQ(files_in(dir.path()), 1u);
}

}  // namespace
}  // namespace rtm
