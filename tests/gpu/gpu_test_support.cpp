#include "gpu_test_support.h"

#include <cstdlib>
#include <filesystem>
#include <random>

namespace punctual::testing {

void saveTestImage(const std::string& name, const ImageRgba8& image) {
    const char* folder = std::getenv("PUNCTUAL_TEST_OUTPUT_DIR");
    if (!folder || !*folder) return;
    std::string file = name;
    for (char& c : file) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
    }
    writePng(std::string(folder) + "/" + file + ".png", image);
}

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

}  // namespace punctual::testing
