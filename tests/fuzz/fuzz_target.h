#pragma once
// The libFuzzer entry points every target in tests/fuzz defines. libFuzzer calls them itself;
// replay_main.cpp calls them on files in ordinary builds.
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv);
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
