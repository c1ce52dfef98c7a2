#include "scene/box_layout.h"

#include <algorithm>

#include "scene/default_scene.h"
#include "shading.h"

namespace punctual {

BoxSpec standing(const char* name, float x, float z, glm::vec3 size, uint32_t material, glm::vec2 facing,
                 float baseY) {
    const glm::vec3 half(size.x * 0.5f, 0.0f, size.z * 0.5f);
    return {name, glm::vec3(x, baseY, z) - half, glm::vec3(x, baseY + size.y, z) + half, material, facing};
}

Material plainMaterial(const char* name, glm::vec3 color, float metallic, float roughness) {
    Material m;
    m.name = name;
    m.baseColorFactor = glm::vec4(color, 1.0f);
    m.metallic = metallic;
    m.roughness = roughness;
    return m;
}

void addBoxes(Scene& scene, const std::vector<BoxSpec>& boxes) {
    for (const BoxSpec& box : boxes) {
        const glm::vec3 center = (box.min + box.max) * 0.5f;
        Object object;
        object.name = box.name;
        object.mesh = appendBoxMesh(scene, box.name, box.max - box.min, box.material);
        // Columns: local +X -> (c, 0, s), +Y -> +Y, +Z -> cross(+X, +Y) = (-s, 0, c); then the centre.
        const glm::vec2 xAxis = glm::normalize(box.facing);
        object.model = glm::mat4(glm::vec4(xAxis.x, 0.0f, xAxis.y, 0.0f), glm::vec4(0.0f, 1.0f, 0.0f, 0.0f),
                                 glm::vec4(-xAxis.y, 0.0f, xAxis.x, 0.0f), glm::vec4(center, 1.0f));
        scene.objects.push_back(object);
    }
}

float farthestViewDepth(const Bounds& bounds, const glm::mat4& view) {
    float farthest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                          (corner & 4) ? bounds.max.z : bounds.min.z);
        farthest = std::max(farthest, -(view * glm::vec4(p, 1.0f)).z);
    }
    return farthest;
}

float intensityForIlluminance(float lux, float distance, float range) {
    return lux / gpu::distanceAttenuation(distance * distance, 1.0f / (range * range));
}

}  // namespace punctual
