#pragma once
// Drawing into an ImageRgba8 on the CPU: filled rectangles and short ASCII labels. Text uses
// stb_easy_font (a tiny vector font made of axis-aligned quads), so no font file or texture is
// needed. Used by the heatmap legend; good enough for labels, not for typography.
#include <cstdint>
#include <string>

#include <glm/ext/vector_uint3_sized.hpp>

#include "core/image.h"

namespace punctual {

// stb_easy_font lays text out on a 12-unit line; glyph ink spans units 0..9 (with descenders).
// Everything below is in output pixels: font units times `scale`.
constexpr uint32_t kTextLineUnits = 12;

// Width in pixels of `text` drawn at `scale` (integer magnification of the font).
uint32_t textWidth(const std::string& text, uint32_t scale);
// Height in pixels of one line of text at `scale`, including the gap below it.
uint32_t textLineHeight(uint32_t scale);

// Fills [x, x + width) x [y, y + height) with an opaque colour; the parts outside the image are
// skipped, so callers may pass rectangles that hang over an edge.
void fillRect(ImageRgba8& image, int64_t x, int64_t y, int64_t width, int64_t height,
              glm::u8vec3 color);

// Draws `text` with its top-left corner at (x, y). Characters outside printable ASCII are drawn
// as '?'; text that runs past the image edge is clipped.
void drawText(ImageRgba8& image, int64_t x, int64_t y, const std::string& text, uint32_t scale,
              glm::u8vec3 color);

}  // namespace punctual
