#pragma once
// "Lights tested per pixel" heatmaps: turns the per-pixel counts a culling method produced into
// a colour-mapped picture with a legend (colour bar, integer ticks, title, mean and max), so the
// places where tiled / clustered / per-object culling over- or under-performs are visible.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/ext/vector_uint3_sized.hpp>

#include "core/image.h"

namespace punctual {

struct HeatmapOptions {
    uint32_t maxValue = 0;        // top of the colour scale; 0 = the largest coloured count (min 1)
    std::string title;            // e.g. "lights tested per pixel (tiled 16x16)"
    bool markBackground = true;   // background pixels drawn kHeatmapBackgroundColor, not colour 0
    // For scales that are not plain counts (e.g. a log scale): ticks at these values of the scale,
    // with these labels, instead of the integer ticks; and this line instead of "mean .. max ..".
    std::vector<std::pair<uint32_t, std::string>> ticks;
    std::string statsText;
};

// Where no geometry is (when HeatmapOptions::markBackground): a neutral dark grey, which the
// viridis scale never produces.
inline constexpr glm::u8vec3 kHeatmapBackgroundColor{48, 48, 48};
// The legend strip, and the padding right of the frame when the legend is wider than the frame.
inline constexpr glm::u8vec3 kHeatmapPanelColor{16, 16, 16};

// counts: width*height values, rows top to bottom. background: empty, or width*height flags that
// are non-zero where no geometry is. The result holds the frame 1:1 at its top-left (pixel (x, y)
// of the frame is pixel (x, y) of the image) with the legend strip below it; the image is wider
// than the frame when the frame is too narrow for a legible legend.
// Throws punctual::Error("heatmap", ...) on a zero-sized frame or mismatched vector sizes.
ImageRgba8 renderHeatmap(const std::vector<uint32_t>& counts, const std::vector<uint8_t>& background,
                         uint32_t width, uint32_t height, const HeatmapOptions& options);

// The viridis colour of `value` on the scale 0..maxValue. Values outside the scale clamp to its
// ends; a non-positive maxValue or a NaN value gives the bottom colour.
glm::u8vec3 heatmapColor(float value, float maxValue);

}  // namespace punctual
