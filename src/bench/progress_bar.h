#pragma once
// A progress line on stderr for the bench's long runs: drawn only on a terminal, so logs and
// tests see nothing.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace punctual::bench {

class ProgressBar {
public:
    explicit ProgressBar(size_t total) : total_(total), terminal_(isatty(2) != 0) {}
    void step(const std::string& what) {
        ++done_;
        if (!terminal_) return;
        const int width = 30;
        const int filled = int(double(done_) / double(std::max<size_t>(total_, 1)) * width);
        std::fprintf(stderr, "\r[%s%s] %zu/%zu %-40.40s", std::string(size_t(filled), '#').c_str(),
                     std::string(size_t(width - std::min(filled, width)), '.').c_str(), done_, total_, what.c_str());
        if (done_ == total_) std::fputc('\n', stderr);
    }

private:
    size_t total_;
    size_t done_ = 0;
    bool terminal_;
};

}  // namespace punctual::bench
