#pragma once
// Where an output path really leads, and whether punctual may write there. Shared by the checks
// that run before any work (src/cli/output_paths.h) and by OutputFiles, which writes at the end,
// so both agree on what a path means:
// - a regular file or a new name is replaced atomically: a temporary file beside it, renamed over it;
// - a symbolic link is written through: its final target gets the new contents (atomically, the
//   temporary beside the target), the link stays;
// - a character device (/dev/null) or a FIFO is written in place, never created or truncated;
// - anything else (a folder, a block device, a socket) is refused: never replaced.
#include <sys/types.h>

#include <filesystem>
#include <string>

namespace punctual {

struct OutputTarget {
    enum class Kind {
        Missing,  // nothing there yet: created atomically
        Regular,  // an existing regular file: replaced atomically
        Stream,   // a character device or a FIFO: written in place
    };
    std::string requested;       // the path as given, for messages
    std::filesystem::path file;  // Missing and Regular: symbolic links followed, folder canonical.
                                 // Stream: the path as given (open() follows /proc's magic links).
    Kind kind = Kind::Missing;
    dev_t device = 0;  // the file's identity when it exists (two names of one file collide)
    ino_t inode = 0;

    std::filesystem::path folder() const { return file.parent_path(); }
    // Equal when both name the same file: by identity if it exists, else by resolved path.
    bool sameFileAs(const OutputTarget& other) const;
};

// Throws punctual::Error(path, ...) naming the problem: empty name, a folder, a block device or
// socket, a missing folder, a file used as a folder ("'a.txt' is a file, not a folder"), a name
// longer than the file system allows, a symbolic link loop.
OutputTarget resolveOutputTarget(const std::string& path);

// Throws punctual::Error unless this process can write `target`: for Missing and Regular it
// creates and at once removes a temporary file in the folder (the same kind of file the commit
// writes, so a read-only folder, a read-only file system or a full disk shows now, not after
// the render); a Regular file must be writable too (a write-protected file is not replaced,
// as cp does not); a Stream must be writable. Leaves nothing behind.
void checkOutputTargetWritable(const OutputTarget& target);

// Throws punctual::Error naming `subject` unless a file can be created in the existing folder
// `folder` (found by creating and at once removing a temporary file there).
void checkFolderWritable(const std::string& subject, const std::filesystem::path& folder);

// Creates a new, empty file beside `file` (same folder, so a rename onto `file` is atomic),
// named ".<name>.XXXXXX" by mkstemp: a name no existing file has, since mkstemp only ever creates
// a new one. Returns its descriptor and sets `temporary`; throws punctual::Error naming
// `subject` on failure.
int createTemporaryBeside(const std::filesystem::path& file, const std::string& subject, std::string& temporary);

// "folder 'F' is not writable" and the like, for an errno of creating a file in `folder`.
std::string folderWriteProblem(const std::filesystem::path& folder, int error);

}  // namespace punctual
