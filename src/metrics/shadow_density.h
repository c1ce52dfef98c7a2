#pragma once
// Shadow texels per screen pixel at every pixel (--shadow-density FILE.png), where the frame's
// shadowed lights reach: how well each pixel's shadows are resolved, 1 being the target of
// --shadow-res auto (lights/shadow_resolution.h).
//
// At each pixel (one primary ray through its centre, CPU), for each shadowed light that reaches
// the surface there (in range, in the cone, facing it: the tests of resolutionNeededAt), the view
// the shader reads gives density = its resolution / the resolution one texel per pixel needs
// there, i.e. how many of its texels span one pixel. The pixel shows the smallest density over
// those lights (its coarsest shadow). A light whose view has no map (no caster: always lit) has
// no shadow edge to resolve and is left out; so is a pixel no shadowed light reaches.
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "scene/scene.h"

namespace punctual {

struct ShadowDensityImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> density;  // per pixel, rows top to bottom; 0 where no shadowed light reaches
};

ShadowDensityImage computeShadowDensity(const Scene& scene, const FrameLights& lights, const ShadowPlan& plan,
                                        uint32_t width, uint32_t height);

// The density as a colour map on a log2 scale from 1/8 to 8 (1 in the middle), with a legend like
// the heat map's; pixels no shadowed light reaches are drawn as background.
ImageRgba8 renderShadowDensity(const ShadowDensityImage& image, const std::string& title);

}  // namespace punctual
