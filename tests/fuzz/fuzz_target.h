#pragma once
// The libFuzzer entry points every target in tests/fuzz defines. libFuzzer calls them itself;
// replay_main.cpp calls them on files in ordinary builds.
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv);
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace punctual::fuzzing {

// A private temporary folder for a target's input files, removed when the process exits; aborts
// (a harness failure, not a finding) when it cannot be made. `name` names the target.
inline std::string makeInputFolder(const char* name) {
    static std::string folder;
    std::string pattern = (std::filesystem::temp_directory_path() / (std::string("punctual-fuzz-") + name + "-XXXXXX")).string();
    if (mkdtemp(pattern.data()) == nullptr) {
        std::perror("fuzz: mkdtemp");
        std::abort();
    }
    folder = pattern;
    std::atexit([] {
        std::error_code ignored;
        std::filesystem::remove_all(folder, ignored);
    });
    return folder;
}

}  // namespace punctual::fuzzing
