#pragma once
// The GPU's shadow factors read back per pixel. A plain CPU struct (no Vulkan) so that the Embree
// shadow validation and its tests build without the renderer.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace punctual {

// Per pixel, from the forward shader's validation variant (rows top to bottom): the surface it
// shaded and each shadowed light's shadow factor there.
struct ShadowFactorImage {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t slots = 0;                // shadowed lights: spots first, then points (ShadowPlan order)
    std::vector<glm::vec3> positions;  // world space
    std::vector<glm::vec3> normals;    // unit shading normal, facing the viewer
    std::vector<uint8_t> covered;      // 1 where geometry is
    std::vector<uint8_t> factors;      // [pixel * slots + slot]: factor x 254, 255 = light does not reach
    // The sun (when its shadow is cascaded): its factor as above, and the cascade read plus one
    // (0: none). Empty without cascades.
    std::vector<uint8_t> sunFactors;
    std::vector<uint8_t> sunCascades;
};

}  // namespace punctual
