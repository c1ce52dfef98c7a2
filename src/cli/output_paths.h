#pragma once
// Output paths are checked before any work starts, so a typo in a folder name, a read-only
// folder or two options naming one file fail in a second, not after a long render. The rules
// (what a symbolic link, /dev/null or a FIFO means) are core/output_target.h's; the files are
// written all or nothing at the end by OutputFiles (core/output_files.h).
#include <optional>
#include <string>
#include <vector>

namespace punctual::cli {

// An output file and the option that named it, for messages ("--stats").
struct NamedOutput {
    std::string option;
    std::optional<std::string> path;  // absent: the option was not given
};

// Throws punctual::Error(path, ...) when a given path cannot be written (a missing folder, a
// file used as a folder, a folder, a name too long, a read-only folder or file, a block device),
// or when two of them name the same file, however spelt (./x.png, a symbolic link, a hard link).
void checkOutputPaths(const std::vector<NamedOutput>& outputs);
// One output file; see checkOutputPaths.
void checkOutputPath(const std::optional<std::string>& path);

}  // namespace punctual::cli
