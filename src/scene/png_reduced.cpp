#include "scene/png_reduced.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstring>

namespace punctual {
namespace {

// libpng reads from memory through this cursor.
struct MemoryReader {
    const unsigned char* bytes = nullptr;
    size_t size = 0;
    size_t offset = 0;
};

void readFromMemory(png_structp png, png_bytep out, size_t count) {
    auto* reader = static_cast<MemoryReader*>(png_get_io_ptr(png));
    if (count > reader->size - reader->offset) png_error(png, "the PNG data ends early");
    std::memcpy(out, reader->bytes + reader->offset, count);
    reader->offset += count;
}

// libpng's errors end in a longjmp back to decodeRows' setjmp; the message is kept for the caller.
void onError(png_structp png, png_const_charp message) {
    auto* failure = static_cast<std::string*>(png_get_error_ptr(png));
    *failure = message ? message : "corrupt PNG data";
    png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}  // a warning still decodes: nothing to report

// sRGB <-> linear, the IEC 61966-2-1 curve (as stb_image_resize's STBIR_COLORSPACE_SRGB).
float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
float linearToSrgb(float c) { return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }

uint8_t toByte(float unit) { return uint8_t(std::lround(std::clamp(unit, 0.0f, 1.0f) * 255.0f)); }

// The k x k block sums of one output row: colour weighted by alpha, alpha, colour unweighted
// (for a block whose alpha is all 0, whose colour is then the plain average), and texel counts.
struct BlockSums {
    std::vector<std::array<double, 8>> sums;  // weighted rgb, alpha, plain rgb, count

    explicit BlockSums(uint32_t blocks) : sums(blocks) {}

    void add(const uint8_t* row, uint32_t width, uint32_t k, const std::array<float, 256>& linear) {
        for (uint32_t x = 0; x < width; ++x) {
            std::array<double, 8>& block = sums[x / k];
            const uint8_t* texel = row + size_t(x) * 4;
            const double alpha = texel[3] / 255.0;
            for (int c = 0; c < 3; ++c) {
                const double value = double(linear[texel[c]]);
                block[size_t(c)] += alpha * value;
                block[size_t(c) + 4] += value;
            }
            block[3] += alpha;
            block[7] += 1.0;
        }
    }

    // Appends the averages to `out` as sRGB bytes and clears the sums.
    void emit(std::vector<uint8_t>& out) {
        for (std::array<double, 8>& block : sums) {
            const bool anyAlpha = block[3] > 0.0;
            for (int c = 0; c < 3; ++c) {
                const double colour = anyAlpha ? block[size_t(c)] / block[3] : block[size_t(c) + 4] / block[7];
                out.push_back(toByte(linearToSrgb(float(colour))));
            }
            out.push_back(toByte(float(block[3] / block[7])));
            block.fill(0.0);
        }
    }
};

// Sets libpng up to deliver 8-bit RGBA rows, whatever the file stores.
void requestRgba8(png_structp png, png_infop info) {
    const int colourType = png_get_color_type(png, info);
    if (colourType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (colourType == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    png_set_strip_16(png);
    if (colourType == PNG_COLOR_TYPE_GRAY || colourType == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
    png_set_filler(png, 0xFF, PNG_FILLER_AFTER);  // adds alpha only where there is none
    png_read_update_info(png, info);
}

// The part with setjmp: no object with a destructor lives here, since libpng's longjmp would skip
// it. Everything it fills belongs to the caller.
bool decodeRows(png_structp png, png_infop info, TextureSize wanted, ReducedImage& image, std::vector<uint8_t>& row,
                BlockSums*& sums, std::string& failure) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_info(png, info);
    image.original = {png_get_image_width(png, info), png_get_image_height(png, info)};
    if (png_get_interlace_type(png, info) != PNG_INTERLACE_NONE) {
        failure = "an interlaced PNG this large cannot be decoded row by row";
        return false;
    }
    requestRgba8(png, info);
    const uint32_t k = reductionFactor(image.original, wanted);
    image.size = {(image.original.width + k - 1) / k, (image.original.height + k - 1) / k};
    row.resize(size_t(image.original.width) * 4);
    sums = new BlockSums(image.size.width);
    image.rgba.reserve(size_t(image.size.width) * image.size.height * 4);
    static const std::array<float, 256> linear = [] {
        std::array<float, 256> table{};
        for (int i = 0; i < 256; ++i) table[size_t(i)] = srgbToLinear(float(i) / 255.0f);
        return table;
    }();
    for (uint32_t y = 0; y < image.original.height; ++y) {
        png_read_row(png, row.data(), nullptr);
        sums->add(row.data(), image.original.width, k, linear);
        if ((y + 1) % k == 0 || y + 1 == image.original.height) sums->emit(image.rgba);
    }
    return true;
}

}  // namespace

bool isPng(const unsigned char* bytes, size_t size) { return bytes != nullptr && size >= 8 && png_sig_cmp(bytes, 0, 8) == 0; }

uint32_t reductionFactor(TextureSize original, TextureSize wanted) {
    uint32_t k = 1;
    const auto reduced = [](uint32_t side, uint32_t factor) { return (uint64_t(side) + factor - 1) / factor; };
    while (k < (1u << 30) && reduced(original.width, k * 2) >= wanted.width &&
           reduced(original.height, k * 2) >= wanted.height)
        k *= 2;
    return k;
}

bool decodePngReduced(const unsigned char* bytes, size_t size, TextureSize wanted, ReducedImage& image,
                      std::string& failure) {
    image = ReducedImage{};
    if (!isPng(bytes, size)) {
        failure = "not a PNG file";
        return false;
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &failure, &onError, &onWarning);
    if (!png) {
        failure = "libpng could not start";
        return false;
    }
    png_infop info = png_create_info_struct(png);
    MemoryReader reader{bytes, size, 0};
    std::vector<uint8_t> row;
    BlockSums* sums = nullptr;
    bool decoded = false;
    if (info) {
        png_set_read_fn(png, &reader, &readFromMemory);
        // libpng refuses images wider or taller than 1,000,000 by default; any larger side is the
        // caller's to bound (the header is read before anything is allocated).
        png_set_user_limits(png, 0x7fffffff, 0x7fffffff);
        decoded = decodeRows(png, info, wanted, image, row, sums, failure);
    }
    delete sums;
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    if (!decoded) image = ReducedImage{};
    return decoded;
}

}  // namespace punctual
