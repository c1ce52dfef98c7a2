#pragma once
// A command's output files, written all or nothing, and never at the cost of a file the user
// owns. Contents are collected while the command works; commit() then writes them all:
// - every output is first written in full to a temporary file beside its target, created by
//   mkstemp (".<name>.XXXXXX": never a name a file already has, so no user file is overwritten
//   or deleted as "our" temporary), then renamed over the target: readers see the old file or
//   the new one, never half of one;
// - what a path means (symbolic links written through, /dev/null and FIFOs written in place,
//   folders and block devices refused) is OutputTarget's rule, see core/output_target.h;
// - two outputs that name one file (however spelt: ./x.png, a symbolic link, a hard link) are
//   refused before anything is written;
// - if anything fails, everything is put back as it was: files that existed keep their contents
//   and their inode (each is kept under a hard link until the commit succeeds, and renamed back
//   on failure), new files and temporaries are removed, folders the commit created are removed.
//   Bytes already written into a device or FIFO cannot be taken back, so those are written last.
#include <string>
#include <utility>
#include <vector>

namespace punctual {

class OutputFiles {
public:
    void add(const std::string& path, std::string contents);
    // A folder the outputs go into: created by commit() when missing (its parent must exist),
    // removed again if the commit fails. Folders are created in the order they were added.
    void addFolder(const std::string& path);
    // A file an earlier run wrote that this run does not write (see core/output_folder.h):
    // removed once every output is in place, never when the commit fails. A folder is not removed.
    void removeAfterCommit(const std::string& path);
    // Throws punctual::Error naming the file that could not be written; nothing has changed then.
    void commit();
    const std::vector<std::pair<std::string, std::string>>& pending() const { return files_; }

    // For tests only: called with the step's name after each step of commit() that changes the
    // file system ("folder", "temporary", "backup", "rename", "stream", "stale"), so a test can
    // inject a signal or a failure at each one. nullptr (the default) observes nothing.
    using StepObserver = void (*)(const char* step);
    static void observeStepsForTesting(StepObserver observer);

private:
    std::vector<std::pair<std::string, std::string>> files_;
    std::vector<std::string> folders_;
    std::vector<std::string> stale_;
};

}  // namespace punctual
