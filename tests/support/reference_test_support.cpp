#include "reference_test_support.h"

#include <glm/glm.hpp>

namespace punctual::testing {

Material greyMaterial() {
    Material material;
    material.name = "grey";
    material.baseColorFactor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
    material.metallic = 0.0f;
    material.roughness = 0.5f;
    return material;
}

reference::ReferenceSettings unshadowed(uint32_t width, uint32_t height, float exposure) {
    reference::ReferenceSettings settings;
    settings.width = width;
    settings.height = height;
    settings.exposure = exposure;
    settings.shadows = false;  // the GPU frames it is compared with are rendered with shadows off
    return settings;
}

}  // namespace punctual::testing
