#pragma once
// Output files are checked before any work starts (so a typo in a folder name fails in a
// second, not after a long render) and written atomically at the end.
#include <optional>
#include <string>

namespace punctual::app {

// Throws punctual::Error(path, ...) when the file's folder does not exist or the path is a folder.
void checkOutputPath(const std::optional<std::string>& path);
// An output folder: it may not exist yet (it is created when the outputs are written), but its
// parent must, and it must not be a file.
void checkOutputFolder(const std::string& path);

}  // namespace punctual::app
