// Writing a file atomically: the content goes to a temporary file in the destination's folder, under a name no other
// writer uses (the file's name, this process's id and a per-process counter), which is then renamed onto the
// destination. Readers see the old file or the new one, never a part; concurrent writers of one path do not collide
// (the last rename wins); a failed write removes its temporary file and leaves the destination as it was. A
// destination that is a symbolic link is written through: the file it points to is replaced and the link stays (a
// rename onto the link itself would replace the link with a file).
#pragma once

#include <string>

#include "formats/image_io.h"  // IoError

namespace rtm {

// The file `path` names once symbolic links are followed (a link's relative target is relative to the link's
// folder); the path itself when it is no link or does not exist. Throws IoError naming `path` for a chain of more
// than 40 links (a loop) or a link that cannot be read.
std::string output_target(const std::string& path);

class AtomicFile {
public:
    // Chooses the temporary name beside the file `path` names (following symbolic links); creates nothing. Throws
    // IoError "PATH: is a directory" when that is a folder, and IoError when it is another file than a regular one
    // (a device, a FIFO: replacing it would be wrong) or the links loop.
    explicit AtomicFile(std::string path);
    // Removes the temporary file unless commit() succeeded.
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::string& path() const { return path_; }
    // Where to write the content: ".NAME.tmpPID-N" in the destination's folder (the link target's, for a link).
    const std::string& temp_path() const { return temp_; }
    // Renames the temporary file onto path(). Throws IoError "PATH: cannot write: rename from temporary file
    // failed: REASON" (the temporary file is removed).
    void commit();

private:
    std::string path_, target_, temp_;
    bool committed_ = false;
};

// Writes `text` to `path` atomically. Throws IoError "PATH: cannot write: REASON"; the destination is untouched then.
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace rtm
