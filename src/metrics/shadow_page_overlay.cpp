#include "metrics/shadow_page_overlay.h"

#include <algorithm>
#include <string>

#include "lights/shadow_resolution.h"
#include "lights/virtual_pages.h"
#include "metrics/text_overlay.h"
#include "shadow_pages.h"

namespace punctual {

std::vector<int8_t> shadowPageLevels(const Scene& scene, const FrameLights& lights, const ShadowPlan& plan,
                                     uint32_t width, uint32_t height, const ShadowSettings& settings) {
    std::vector<int8_t> levels(size_t(width) * height, -1);
    const uint32_t spotsAndPoints = lights.spotCount + lights.pointCount;
    forEachVisibleReceiver(scene, width, height, 1, [&](uint32_t x, uint32_t y, const ReceiverSample& sample) {
        int8_t& finest = levels[size_t(y) * width + x];
        for (uint32_t i = 0; i < spotsAndPoints; ++i) {
            const auto read = virtualReadOnCpu(plan, lights.packed[i], sample.position, sample.normal, settings);
            if (read && (finest < 0 || int(read->level) < finest)) finest = int8_t(read->level);
        }
    });
    return levels;
}

namespace {

// Level 0 (16384 texels) red through orange, yellow, green and cyan to level 9 (32 texels) blue.
glm::vec3 levelColour(int level) {
    const float t = float(level) / float(PUNCTUAL_VIRTUAL_SHADOW_LEVELS - 1);
    const glm::vec3 stops[5] = {{1.0f, 0.15f, 0.1f}, {1.0f, 0.8f, 0.1f}, {0.2f, 0.9f, 0.2f}, {0.1f, 0.8f, 1.0f},
                                {0.3f, 0.3f, 1.0f}};
    const float at = t * 4.0f;
    const int i = std::min(int(at), 3);
    return glm::mix(stops[i], stops[i + 1], at - float(i));
}

}  // namespace

ImageRgba8 shadowPageOverlay(const ImageRgba8& frame, const std::vector<int8_t>& levels) {
    ImageRgba8 image = frame;
    std::vector<bool> used(PUNCTUAL_VIRTUAL_SHADOW_LEVELS, false);
    for (size_t i = 0; i < levels.size() && i * 4 + 3 < image.pixels.size(); ++i) {
        if (levels[i] < 0) continue;
        used[size_t(levels[i])] = true;
        const glm::vec3 tint = levelColour(levels[i]);
        for (int c = 0; c < 3; ++c) {
            // Half the frame's own brightness (so the shadows stay readable), half the tint.
            const float value = 0.5f * float(image.pixels[i * 4 + size_t(c)]) + 127.0f * tint[c];
            image.pixels[i * 4 + size_t(c)] = uint8_t(std::min(value, 255.0f));
        }
    }
    // The legend: one swatch and label per level the frame reads, top left.
    const uint32_t scale = image.height >= 512 ? 2 : 1;
    int64_t y = 4;
    for (uint32_t level = 0; level < PUNCTUAL_VIRTUAL_SHADOW_LEVELS; ++level) {
        if (!used[level]) continue;
        const std::string label = "level " + std::to_string(level) + ": " +
                                  std::to_string(PUNCTUAL_VIRTUAL_SHADOW_SIZE >> level) + " texels";
        const int64_t line = textLineHeight(scale);
        fillRect(image, 4, y, int64_t(textWidth(label, scale)) + line + 8, line + 2, glm::u8vec3(0));
        fillRect(image, 6, y + 1, line - 2, line - 2, glm::u8vec3(levelColour(int(level)) * 255.0f));
        drawText(image, 6 + line, y + 2, label, scale, glm::u8vec3(255));
        y += line + 2;
    }
    return image;
}

}  // namespace punctual
