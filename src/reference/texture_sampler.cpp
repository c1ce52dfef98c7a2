#include "reference/texture_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace punctual::reference {
namespace {

// The 256 decoded values, computed once in double and rounded to float: exact to the last bit,
// which is as close as any GPU's decoder can be.
const std::array<float, 256>& srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> values{};
        for (int code = 0; code < 256; ++code) {
            const double c = code / 255.0;
            values[size_t(code)] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        return values;
    }();
    return table;
}

// REPEAT: the texel index `index` (a whole number, possibly negative or huge) modulo the size,
// reduced in double so no integer conversion can overflow.
uint32_t wrapRepeat(double index, uint32_t size) {
    const double n = double(size);
    const double wrapped = index - n * std::floor(index / n);
    return std::min(uint32_t(wrapped), size - 1);  // rounding can give exactly n for tiny negatives
}

glm::vec4 texel(const Texture& texture, uint32_t x, uint32_t y) {
    const uint8_t* p = &texture.rgba[(size_t(y) * texture.width + x) * 4];
    const std::array<float, 256>& table = srgbTable();
    return {table[p[0]], table[p[1]], table[p[2]], float(p[3]) / 255.0f};
}

}  // namespace

float srgbToLinear(uint8_t code) { return srgbTable()[code]; }

glm::vec4 sampleBilinearRepeat(const Texture& texture, glm::vec2 uv) {
    if (texture.width == 0 || texture.height == 0 ||
        texture.rgba.size() < size_t(texture.width) * texture.height * 4) {
        return glm::vec4(1.0f);  // nothing to sample: behave as no texture
    }
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec4(0.0f);
    // Texel centres sit at half-integer coordinates, hence the -0.5.
    const double u = double(uv.x) * texture.width - 0.5;
    const double v = double(uv.y) * texture.height - 0.5;
    const double u0 = std::floor(u);
    const double v0 = std::floor(v);
    const float alpha = float(u - u0);
    const float beta = float(v - v0);
    const uint32_t x0 = wrapRepeat(u0, texture.width);
    const uint32_t x1 = (x0 + 1) % texture.width;
    const uint32_t y0 = wrapRepeat(v0, texture.height);
    const uint32_t y1 = (y0 + 1) % texture.height;
    const glm::vec4 top = glm::mix(texel(texture, x0, y0), texel(texture, x1, y0), alpha);
    const glm::vec4 bottom = glm::mix(texel(texture, x0, y1), texel(texture, x1, y1), alpha);
    return glm::mix(top, bottom, beta);
}

}  // namespace punctual::reference
