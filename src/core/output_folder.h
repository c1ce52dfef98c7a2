#pragma once
// An output folder (validate's and bench's --out-dir) and the files a command writes into it.
// A run into a folder an earlier run used must not leave the earlier run's files beside its own
// (mismatch maps of lights that no longer exist would pass for current ones), yet must never
// remove a file the user put there. So each run lists the files it wrote in its manifest
// (report.json, results.json: "files"), and the next run removes exactly those listed files it
// does not write again, provided they match the command's own name patterns and are plain
// regular files inside the folder. A file of the user's is never listed, so never touched.
#include <string>
#include <vector>

#include "core/output_files.h"

namespace punctual {

struct OutputFolderLayout {
    std::string manifest;                 // the JSON file whose "files" lists what a run wrote
    std::vector<std::string> patterns;    // every file the command may write, relative to the
                                          // folder; '*' stands for any characters but '/'
    std::vector<std::string> subfolders;  // created inside the folder, e.g. "images"
};

// Whether `name` (relative to the folder) is one the layout's patterns allow: a plain relative
// name (no "..", no leading '/'), not hidden.
bool matchesOutputLayout(const OutputFolderLayout& layout, const std::string& name);

// Before any work: throws punctual::Error unless `folder` can take the outputs. It is a folder
// (or missing, with an existing folder as parent: it is then created at commit), writable (a
// temporary file is created and removed at once), its subfolders are folders, and every file
// already there that the command would write over can be replaced (see resolveOutputTarget).
void checkOutputFolder(const std::string& folder, const OutputFolderLayout& layout);

// The names, relative to `folder`, of the files `outputs` will write there, then the manifest's:
// the manifest's "files" list. Every name must match the layout (an internal check).
std::vector<std::string> outputFolderFiles(const OutputFiles& outputs, const std::string& folder,
                                           const OutputFolderLayout& layout);

// The files that the previous manifest in `folder` lists, this run does not write (`written`),
// and that are regular files matching the layout. Empty when there is no readable manifest.
std::vector<std::string> staleOutputFiles(const std::string& folder, const OutputFolderLayout& layout,
                                          const std::vector<std::string>& written);

// Registers `folder` and its subfolders for creation and the stale files for removal after a
// successful commit. Call after every output is added.
void prepareOutputFolder(OutputFiles& outputs, const std::string& folder, const OutputFolderLayout& layout,
                         const std::vector<std::string>& written);

}  // namespace punctual
