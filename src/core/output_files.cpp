#include "core/output_files.h"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/error.h"

namespace punctual {

void OutputFiles::add(const std::string& path, std::string contents) {
    files_.emplace_back(path, std::move(contents));
}

void OutputFiles::commit() {
    namespace fs = std::filesystem;
    std::vector<std::string> temporaries;
    std::vector<std::string> published;
    auto rollback = [&] {
        std::error_code ec;
        for (const std::string& t : temporaries) fs::remove(t, ec);
        for (const std::string& p : published) fs::remove(p, ec);
    };
    for (const auto& [path, contents] : files_) {
        const std::string temporary = path + ".partial";
        temporaries.push_back(temporary);
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out.write(contents.data(), std::streamsize(contents.size()));
        out.close();
        if (!out) {
            rollback();
            throw Error(path, "cannot write file (is the folder there and writable?)");
        }
    }
    for (size_t i = 0; i < files_.size(); ++i) {
        std::error_code ec;
        fs::rename(temporaries[i], files_[i].first, ec);
        if (ec) {
            rollback();
            throw Error(files_[i].first, "cannot write file: " + ec.message());
        }
        published.push_back(files_[i].first);
    }
    files_.clear();
}

}  // namespace punctual
