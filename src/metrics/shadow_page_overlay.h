#pragma once
// Which virtual level the shadows at each pixel read (--shadow-pages FILE.png, and the validate
// report's pages.png with --shadow-res virtual), as the cascade overlay shows the sun's cascades.
//
// At each pixel (one primary ray through its centre, CPU), every shadowed light whose virtual map
// the receiver reads (virtualReadOnCpu: the forward shader's view, level and bias) gives a level;
// the pixel shows the finest of them (where its shadows cost the most texels). Pixels no light
// reads a page at keep the frame's own colour.
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "scene/scene.h"

namespace punctual {

// Per pixel, rows top to bottom: the finest level read, -1 where none.
std::vector<int8_t> shadowPageLevels(const Scene& scene, const FrameLights& lights, const ShadowPlan& plan,
                                     uint32_t width, uint32_t height, const ShadowSettings& settings);

// `frame` tinted by each pixel's level (red for the finest to blue for the coarsest), with a
// legend of the levels the frame reads and their resolutions.
ImageRgba8 shadowPageOverlay(const ImageRgba8& frame, const std::vector<int8_t>& levels);

}  // namespace punctual
