// readRegularFile: the one reader of input files. Regular files only, refused by their type
// or size before anything is opened, never blocking on a FIFO.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "gltf_test_files.h"
#include "scene/input_file.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;
using unit_testing::TempDir;

std::string problemReading(const fs::path& path, uint64_t maxBytes = 1 << 20) {
    std::vector<unsigned char> bytes;
    return readRegularFile(path.string(), maxBytes, bytes);
}

TEST(InputFile, ReadsRegularFilesAndLinksToThem) {
    TempDir dir;
    unit_testing::writeFile(dir.path() / "a.bin", std::string("hello"));
    fs::create_symlink("a.bin", dir.path() / "link.bin");
    for (const char* name : {"a.bin", "link.bin"}) {
        std::vector<unsigned char> bytes{1, 2, 3};
        EXPECT_EQ(readRegularFile((dir.path() / name).string(), 5, bytes), "") << name;
        EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "hello") << name;
    }
    unit_testing::writeFile(dir.path() / "empty.bin", std::string());
    std::vector<unsigned char> bytes{1};
    EXPECT_EQ(readRegularFile((dir.path() / "empty.bin").string(), 5, bytes), "");
    EXPECT_TRUE(bytes.empty());
}

TEST(InputFile, RefusesEverythingElseByName) {
    TempDir dir;
    fs::create_directory(dir.path() / "folder");
    ASSERT_EQ(::mkfifo((dir.path() / "pipe").c_str(), 0600), 0);
    fs::create_symlink("nowhere", dir.path() / "dangling");
    unit_testing::writeFile(dir.path() / "six.bin", std::string("123456"));
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(problemReading(dir.path() / "folder"), "a directory, not a regular file");
    EXPECT_EQ(problemReading(dir.path() / "pipe"), "a named pipe (FIFO), not a regular file");
    EXPECT_EQ(problemReading("/dev/null"), "a device, not a regular file");
    EXPECT_EQ(problemReading(dir.path() / "missing"), "no such file");
    EXPECT_EQ(problemReading(dir.path() / "dangling"), "a broken symbolic link");
    EXPECT_EQ(problemReading(dir.path() / "six.bin" / "x"), "no such file (a folder on its path is a file)");
    EXPECT_EQ(problemReading(dir.path() / "six.bin", 5), "6 bytes, more than the 5 punctual can read");
    EXPECT_EQ(problemReading(""), "no such file (the path is empty)");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));  // nothing blocked
    EXPECT_EQ(regularFileProblem((dir.path() / "pipe").string(), 100), "a named pipe (FIFO), not a regular file");
    EXPECT_EQ(regularFileProblem((dir.path() / "six.bin").string(), 100), "");
}

}  // namespace
}  // namespace punctual
