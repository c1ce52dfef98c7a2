#include "metrics/text_overlay.h"

#include <algorithm>
#include <cstring>
#include <vector>

// stb_easy_font.h is a C header of static functions; not every function is used here, and its
// C-style casts and int/float mixing are not ours to fix.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wcast-align"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace punctual {
namespace {

// stb_easy_font indexes its glyph table with (c - 32) and reads one entry past it, so only
// ' '..'~' are safe to hand it.
std::string printableAscii(const std::string& text) {
    std::string result = text;
    for (char& c : result) {
        if (c < ' ' || c > '~') c = '?';
    }
    return result;
}

// One quad as stb_easy_font emits it: four vertices of {float x, y, z; uint8 rgba[4]}.
constexpr size_t kBytesPerVertex = 16;
constexpr size_t kBytesPerQuad = 4 * kBytesPerVertex;
// The widest glyph in stb_easy_font is 11 quads; 16 leaves headroom so it never truncates.
constexpr size_t kMaxQuadsPerChar = 16;

float readFloat(const std::vector<char>& buffer, size_t offset) {
    float value = 0.0f;
    std::memcpy(&value, buffer.data() + offset, sizeof(value));
    return value;
}

}  // namespace

uint32_t textWidth(const std::string& text, uint32_t scale) {
    std::string printable = printableAscii(text);
    return static_cast<uint32_t>(stb_easy_font_width(printable.data())) * scale;
}

uint32_t textLineHeight(uint32_t scale) { return kTextLineUnits * scale; }

void fillRect(ImageRgba8& image, int64_t x, int64_t y, int64_t width, int64_t height,
              glm::u8vec3 color) {
    int64_t x0 = std::max<int64_t>(x, 0);
    int64_t y0 = std::max<int64_t>(y, 0);
    int64_t x1 = std::min<int64_t>(x + width, image.width);
    int64_t y1 = std::min<int64_t>(y + height, image.height);
    for (int64_t row = y0; row < y1; ++row) {
        for (int64_t column = x0; column < x1; ++column) {
            uint8_t* pixel = image.at(static_cast<uint32_t>(column), static_cast<uint32_t>(row));
            pixel[0] = color.r;
            pixel[1] = color.g;
            pixel[2] = color.b;
            pixel[3] = 255;
        }
    }
}

void drawText(ImageRgba8& image, int64_t x, int64_t y, const std::string& text, uint32_t scale,
              glm::u8vec3 color) {
    if (text.empty()) return;
    std::string printable = printableAscii(text);
    std::vector<char> vertices(printable.size() * kMaxQuadsPerChar * kBytesPerQuad);
    // Laid out at the origin in font units, then scaled and placed here, so the quad corners
    // stay small integers and scaling is exact.
    int quadCount = stb_easy_font_print(0.0f, 0.0f, printable.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size()));
    auto toPixels = [scale](float units) {
        return static_cast<int64_t>(units) * static_cast<int64_t>(scale);
    };
    for (size_t quad = 0; quad < static_cast<size_t>(quadCount); ++quad) {
        // Vertex 0 is the top-left corner and vertex 2 the bottom-right (quads are axis-aligned).
        size_t first = quad * kBytesPerQuad;
        size_t opposite = first + 2 * kBytesPerVertex;
        int64_t left = toPixels(readFloat(vertices, first));
        int64_t top = toPixels(readFloat(vertices, first + 4));
        int64_t right = toPixels(readFloat(vertices, opposite));
        int64_t bottom = toPixels(readFloat(vertices, opposite + 4));
        fillRect(image, x + left, y + top, right - left, bottom - top, color);
    }
}

}  // namespace punctual
