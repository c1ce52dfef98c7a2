#include "core/output_folder.h"

#include <fnmatch.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/check.h"
#include "core/concat.h"
#include "core/error.h"
#include "core/output_target.h"

namespace punctual {
namespace fs = std::filesystem;

namespace {

// No absolute path, no empty, "." or ".." part: a name that stays inside the folder.
bool isPlainRelativeName(const std::string& name) {
    if (name.empty() || name.front() == '/') return false;
    size_t start = 0;
    while (start <= name.size()) {
        const size_t end = std::min(name.find('/', start), name.size());
        const std::string part = name.substr(start, end - start);
        if (part.empty() || part == "." || part == "..") return false;
        start = end + 1;
    }
    return true;
}

// The files already in `folder` (and its subfolders) that the command would write over.
void checkExistingOutputs(const std::string& folder, const OutputFolderLayout& layout) {
    std::vector<std::string> places = {""};
    places.insert(places.end(), layout.subfolders.begin(), layout.subfolders.end());
    for (const std::string& place : places) {
        const fs::path path = place.empty() ? fs::path(folder) : fs::path(folder) / place;
        if (!place.empty()) {
            struct stat st {};
            if (::stat(path.c_str(), &st) != 0) {
                const int error = errno;
                if (error == ENOENT) continue;  // created at commit
                throw Error(path.string(), std::strerror(error));
            }
            if (!S_ISDIR(st.st_mode)) throw Error(path.string(), "is a file, not a folder");
            checkFolderWritable(path.string(), path);
        }
        std::error_code ec;
        for (fs::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string name = place.empty() ? it->path().filename().string()
                                                   : concat(place, "/", it->path().filename().string());
            if (!matchesOutputLayout(layout, name)) continue;
            checkOutputTargetWritable(resolveOutputTarget(it->path().string()));
        }
        if (ec) throw Error(path.string(), concat("cannot list the folder: ", ec.message()));
    }
}

}  // namespace

bool matchesOutputLayout(const OutputFolderLayout& layout, const std::string& name) {
    if (!isPlainRelativeName(name)) return false;
    return std::any_of(layout.patterns.begin(), layout.patterns.end(), [&](const std::string& pattern) {
        return ::fnmatch(pattern.c_str(), name.c_str(), FNM_PATHNAME | FNM_PERIOD) == 0;
    });
}

void checkOutputFolder(const std::string& folder, const OutputFolderLayout& layout) {
    if (folder.empty()) throw Error("output folder", "empty folder name");
    struct stat st {};
    if (::stat(folder.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
        checkFolderWritable(folder, folder);
        checkExistingOutputs(folder, layout);
        return;
    }
    // Not a folder (yet): a new name in an existing, writable folder, as an output file's is.
    // resolveOutputTarget names the problems: a missing parent, a file on the way, a long name.
    const OutputTarget target = resolveOutputTarget(folder);
    if (target.kind != OutputTarget::Kind::Missing) throw Error(folder, "is a file, not a folder");
    checkOutputTargetWritable(target);
}

std::vector<std::string> outputFolderFiles(const OutputFiles& outputs, const std::string& folder,
                                           const OutputFolderLayout& layout) {
    const std::string prefix = concat(folder, "/");
    std::vector<std::string> names;
    for (const auto& file : outputs.pending()) {
        if (file.first.rfind(prefix, 0) != 0) continue;
        names.push_back(file.first.substr(prefix.size()));
    }
    names.push_back(layout.manifest);
    for (const std::string& name : names) {
        PUNCTUAL_CHECK(matchesOutputLayout(layout, name), concat("output '", name, "' is missing from the folder's layout"));
    }
    return names;
}

std::vector<std::string> staleOutputFiles(const std::string& folder, const OutputFolderLayout& layout,
                                          const std::vector<std::string>& written) {
    std::ifstream in(fs::path(folder) / layout.manifest, std::ios::binary);
    if (!in) return {};
    const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
    if (!manifest.is_object() || !manifest.contains("files") || !manifest["files"].is_array()) return {};
    std::vector<std::string> stale;
    for (const nlohmann::json& entry : manifest["files"]) {
        if (!entry.is_string()) continue;
        const std::string name = entry.get<std::string>();
        if (!matchesOutputLayout(layout, name)) continue;
        if (std::find(written.begin(), written.end(), name) != written.end()) continue;
        if (std::find(stale.begin(), stale.end(), name) != stale.end()) continue;
        // lstat: a symbolic link (the user's, which an earlier run wrote through) is not ours.
        struct stat st {};
        if (::lstat((fs::path(folder) / name).c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
        stale.push_back(name);
    }
    return stale;
}

void prepareOutputFolder(OutputFiles& outputs, const std::string& folder, const OutputFolderLayout& layout,
                         const std::vector<std::string>& written) {
    outputs.addFolder(folder);
    for (const std::string& sub : layout.subfolders) outputs.addFolder(concat(folder, "/", sub));
    for (const std::string& name : staleOutputFiles(folder, layout, written)) {
        outputs.removeAfterCommit(concat(folder, "/", name));
    }
}

}  // namespace punctual
