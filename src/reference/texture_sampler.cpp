#include "reference/texture_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "materials.h"

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

// The texel index `index` (a whole number, possibly negative or huge) wrapped into [0, size) by
// Vulkan's addressing, in double so no integer conversion can overflow.
uint32_t wrapIndex(double index, uint32_t size, TextureWrap wrap) {
    const double n = double(size);
    switch (wrap) {
        case TextureWrap::ClampToEdge: return uint32_t(std::clamp(index, 0.0, n - 1.0));
        case TextureWrap::MirroredRepeat: {
            // Vulkan: mirror(i) = i >= 0 ? i : -(1 + i), then (size - 1) - mirror((i mod 2n) - n).
            const double period = 2.0 * n;
            const double t = index - period * std::floor(index / period) - n;
            const double mirrored = t >= 0.0 ? t : -(1.0 + t);
            return std::min(uint32_t(std::max(n - 1.0 - mirrored, 0.0)), size - 1);
        }
        case TextureWrap::Repeat: break;
    }
    const double wrapped = index - n * std::floor(index / n);
    return std::min(uint32_t(wrapped), size - 1);  // rounding can give exactly n for tiny negatives
}

struct LevelView {
    uint32_t width;
    uint32_t height;
    const uint8_t* rgba;
};

LevelView level(const Texture& texture, uint32_t index) {
    if (index == 0) return {texture.width, texture.height, texture.rgba.data()};
    const TextureLevel& mip = texture.mipLevels[index - 1];
    return {mip.width, mip.height, mip.rgba.data()};
}

glm::vec4 texel(const LevelView& view, uint32_t x, uint32_t y) {
    const uint8_t* p = &view.rgba[(size_t(y) * view.width + x) * 4];
    const std::array<float, 256>& table = srgbTable();
    return {table[p[0]], table[p[1]], table[p[2]], float(p[3]) / 255.0f};
}

glm::vec4 filterLevel(const LevelView& view, TextureFilter filter, const TextureSampler& sampler, glm::vec2 uv) {
    const double u = double(uv.x) * view.width;
    const double v = double(uv.y) * view.height;
    if (filter == TextureFilter::Nearest) {
        return texel(view, wrapIndex(std::floor(u), view.width, sampler.wrapU),
                     wrapIndex(std::floor(v), view.height, sampler.wrapV));
    }
    // Texel centres sit at half-integer coordinates, hence the -0.5.
    const double u0 = std::floor(u - 0.5);
    const double v0 = std::floor(v - 0.5);
    const float alpha = float(u - 0.5 - u0);
    const float beta = float(v - 0.5 - v0);
    const uint32_t x0 = wrapIndex(u0, view.width, sampler.wrapU);
    const uint32_t x1 = wrapIndex(u0 + 1.0, view.width, sampler.wrapU);
    const uint32_t y0 = wrapIndex(v0, view.height, sampler.wrapV);
    const uint32_t y1 = wrapIndex(v0 + 1.0, view.height, sampler.wrapV);
    const glm::vec4 top = glm::mix(texel(view, x0, y0), texel(view, x1, y0), alpha);
    const glm::vec4 bottom = glm::mix(texel(view, x0, y1), texel(view, x1, y1), alpha);
    return glm::mix(top, bottom, beta);
}

bool usable(const Texture& texture) {
    return texture.width > 0 && texture.height > 0 && texture.rgba.size() >= size_t(texture.width) * texture.height * 4;
}

}  // namespace

float srgbToLinear(uint8_t code) { return srgbTable()[code]; }

glm::vec4 sampleBilinearRepeat(const Texture& texture, glm::vec2 uv) {
    if (!usable(texture)) return glm::vec4(1.0f);  // nothing to sample: behave as no texture
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec4(0.0f);
    return filterLevel(level(texture, 0), TextureFilter::Linear, TextureSampler{}, uv);
}

float textureLod(const Texture& texture, glm::vec2 uvDx, glm::vec2 uvDy) {
    const glm::vec2 size(float(texture.width), float(texture.height));
    // std::log2(0) is -inf, as a zero footprint should be.
    return gpu::isotropicLod(uvDx, uvDy, size);
}

glm::vec4 sampleTexture(const Texture& texture, const TextureSampler& sampler, glm::vec2 uv, float lod) {
    if (!usable(texture)) return glm::vec4(1.0f);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec4(0.0f);
    const float maxLod = sampler.mipmaps ? float(texture.levelCount() - 1) : 0.0f;
    if (std::isnan(lod)) lod = 0.0f;
    // Magnification or minification is decided on the unclamped lambda (Vulkan: lambda <= 0 is
    // magnification), then lambda is clamped to the levels there are.
    if (lod <= 0.0f) return filterLevel(level(texture, 0), sampler.magFilter, sampler, uv);
    const float clamped = std::min(lod, maxLod);
    if (sampler.mipFilter == TextureFilter::Nearest || clamped >= maxLod) {
        const uint32_t d = uint32_t(std::min(std::max(std::ceil(clamped + 0.5f) - 1.0f, 0.0f), maxLod));
        return filterLevel(level(texture, d), sampler.minFilter, sampler, uv);
    }
    const float base = std::floor(clamped);
    const uint32_t d = uint32_t(base);
    const glm::vec4 finer = filterLevel(level(texture, d), sampler.minFilter, sampler, uv);
    const glm::vec4 coarser = filterLevel(level(texture, d + 1), sampler.minFilter, sampler, uv);
    return glm::mix(finer, coarser, clamped - base);
}

}  // namespace punctual::reference
