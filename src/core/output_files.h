#pragma once
// A command's output files, written all or nothing: contents are collected while the command
// works, then commit() writes each to a temporary file beside its target and renames them all.
// If anything fails, the files already renamed are removed again, so an error never leaves a
// partial set of outputs behind.
#include <string>
#include <utility>
#include <vector>

namespace punctual {

class OutputFiles {
public:
    void add(const std::string& path, std::string contents);
    // Throws punctual::Error naming the file that could not be written.
    void commit();
    const std::vector<std::pair<std::string, std::string>>& pending() const { return files_; }

private:
    std::vector<std::pair<std::string, std::string>> files_;
};

}  // namespace punctual
