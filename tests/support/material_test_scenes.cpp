#include "material_test_scenes.h"

#include <glm/gtc/matrix_transform.hpp>

#include "scene/texture_mips.h"

namespace punctual::testing {

Material matte(const std::string& name, glm::vec3 color) {
    Material material;
    material.name = name;
    material.baseColorFactor = glm::vec4(color, 1.0f);
    material.metallic = 0.0f;
    material.roughness = 0.8f;
    return material;
}

Texture checkerTexture(uint32_t side, uint32_t check, glm::u8vec4 odd) {
    Texture texture;
    texture.name = "checker";
    texture.width = side;
    texture.height = side;
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) {
            const bool even = (x / check + y / check) % 2 == 0;
            const glm::u8vec4 c = even ? glm::u8vec4(255) : odd;
            texture.rgba.insert(texture.rgba.end(), {c.r, c.g, c.b, c.a});
        }
    generateMipmaps(texture);
    return texture;
}

void lookAt(Scene& scene, glm::vec3 eye, glm::vec3 target, float yfov) {
    scene.camera.view = glm::lookAtRH(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.yfov = yfov;
    scene.camera.znear = 0.1f;
    scene.camera.zfar = 60.0f;
    scene.cameraFromFile = true;
}

}  // namespace punctual::testing
