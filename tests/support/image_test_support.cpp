#include "image_test_support.h"

#include <cctype>
#include <cstdlib>

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

}  // namespace punctual::testing
