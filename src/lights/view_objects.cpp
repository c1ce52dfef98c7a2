#include "lights/view_objects.h"

#include <algorithm>

#include "lights/light_setup.h"

namespace punctual {

std::vector<uint32_t> objectsInView(const Scene& scene, const glm::mat4& viewProjection) {
    const Frustum frustum = extractFrustum(viewProjection);
    const float scenePad = scene.bounds.empty() ? 0.0f : 1e-6f * glm::length(scene.bounds.size());
    std::vector<uint32_t> visible;
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        const Bounds& box = scene.objects[i].worldBounds;
        if (box.empty()) continue;
        const glm::vec3 pad(scenePad + 1e-4f * glm::length(box.size()));
        const glm::vec3 lo = box.min - pad;
        const glm::vec3 hi = box.max + pad;
        // Outside when the box's corner furthest along a plane's inward normal is behind it.
        bool inside = true;
        for (const glm::vec4& plane : frustum.planes) {
            const glm::vec3 n(plane);
            const glm::vec3 corner(n.x >= 0.0f ? hi.x : lo.x, n.y >= 0.0f ? hi.y : lo.y, n.z >= 0.0f ? hi.z : lo.z);
            if (glm::dot(n, corner) + plane.w < 0.0f) {
                inside = false;
                break;
            }
        }
        if (inside) visible.push_back(i);
    }
    return visible;
}

std::vector<uint32_t> keepInView(const std::vector<uint32_t>& objects, const std::vector<uint32_t>& inView) {
    std::vector<uint32_t> kept;
    kept.reserve(objects.size());
    for (const uint32_t object : objects) {
        if (std::binary_search(inView.begin(), inView.end(), object)) kept.push_back(object);
    }
    return kept;
}

uint64_t trianglesOf(const Scene& scene, const std::vector<uint32_t>& objects) {
    uint64_t triangles = 0;
    for (const uint32_t object : objects) triangles += scene.meshes[scene.objects[object].mesh].indexCount / 3;
    return triangles;
}

}  // namespace punctual
