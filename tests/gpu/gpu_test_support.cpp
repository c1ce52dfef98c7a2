#include "gpu_test_support.h"

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

namespace punctual::testing {

TempFolder::TempFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "_" + info->name() : "punctual";
    for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    std::random_device random;
    path_ = (std::filesystem::temp_directory_path() / ("punctual_" + name + "_" + std::to_string(random()))).string();
    std::filesystem::create_directories(path_);
}

TempFolder::~TempFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

size_t lineCount(const std::string& text) { return size_t(std::count(text.begin(), text.end(), '\n')); }

RunResult runPunctual(const TempFolder& folder, const std::string& args) {
    const std::string outFile = folder.file("stdout.txt");
    const std::string errFile = folder.file("stderr.txt");
    const std::string command = cat(quoted(PUNCTUAL_BINARY), " ", args, " >", quoted(outFile), " 2>", quoted(errFile));
    const int status = std::system(command.c_str());
    RunResult result;
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = readText(outFile);
    result.err = readText(errFile);
    return result;
}

void expectOneClearError(const RunResult& run, const std::string& args, const std::string& mention) {
    EXPECT_NE(run.exitCode, 0) << args;
    EXPECT_NE(run.exitCode, 3) << args << ": internal error instead of a clear one: " << run.err;
    EXPECT_EQ(lineCount(run.err), 1u) << args << "\nstderr:\n" << run.err;
    EXPECT_EQ(run.err.rfind("punctual: error: ", 0), 0u) << args << ": " << run.err;
    EXPECT_NE(run.err.find(mention), std::string::npos) << args << ": stderr should name '" << mention << "': " << run.err;
}

void expectNothingLeftBehind(const TempFolder& folder, const std::string& args, const std::vector<std::string>& kept) {
    for (const auto& entry : std::filesystem::directory_iterator(folder.path())) {
        const std::string name = entry.path().filename().string();
        const bool isKept = name == "stdout.txt" || name == "stderr.txt" ||
                            std::any_of(kept.begin(), kept.end(),
                                        [&](const std::string& part) { return name.find(part) != std::string::npos; });
        EXPECT_TRUE(isKept) << "left behind: " << name << " after " << args;
    }
}

namespace {

template <typename T>
void append(std::string& bytes, const std::vector<T>& values) {
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

}  // namespace

std::string quadGltfBuffers(const std::vector<float>& uvs) {
    std::string buffer;
    append(buffer, std::vector<float>{-1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1});  // positions, 48 bytes
    append(buffer, std::vector<float>{0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0});      // normals, 48 bytes
    append(buffer, uvs);                                                         // uvs, 32 bytes
    append(buffer, std::vector<uint16_t>{0, 1, 2, 0, 2, 3});                     // indices, 12 bytes
    return R"(
  "buffers": [{"byteLength": 140, "uri": "data:application/octet-stream;base64,)" + base64(buffer) + R"("}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 128},
    {"buffer": 0, "byteOffset": 128, "byteLength": 12}
  ],
  "accessors": [
    {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
    {"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 0, "byteOffset": 96, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ])";
}

}  // namespace punctual::testing
