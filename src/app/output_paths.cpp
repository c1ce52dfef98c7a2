#include "app/output_paths.h"

#include <filesystem>

#include "core/error.h"

namespace punctual::app {

void checkOutputPath(const std::optional<std::string>& path) {
    if (!path) return;
    namespace fs = std::filesystem;
    if (path->empty()) throw Error("output", "empty file name");
    const fs::path file(*path);
    std::error_code ec;
    if (fs::is_directory(file, ec)) throw Error(*path, "is a folder, expected a file name");
    const fs::path folder = file.has_parent_path() ? file.parent_path() : fs::path(".");
    if (!fs::is_directory(folder, ec)) throw Error(*path, "folder '" + folder.string() + "' does not exist");
}

void checkOutputFolder(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(path, ec) && !fs::is_directory(path, ec)) throw Error(path, "exists and is not a folder");
    const fs::path folder(path);
    const fs::path parent = folder.has_parent_path() ? folder.parent_path() : fs::path(".");
    if (!fs::is_directory(parent, ec)) throw Error(path, "folder '" + parent.string() + "' does not exist");
}

}  // namespace punctual::app
