#include "scene_test_support.h"

#include <cstring>
#include <vector>

namespace punctual::testing {
namespace {

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

template <typename T>
bool sameBytes(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

}  // namespace

std::string firstSceneDifference(const Scene& a, const Scene& b) {
    if (a.source != b.source) return "source";
    if (!sameBytes(a.vertices, b.vertices)) return "vertices";
    if (!sameBytes(a.indices, b.indices)) return "indices";
    if (a.meshes.size() != b.meshes.size()) return "mesh count";
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        const Mesh& x = a.meshes[i];
        const Mesh& y = b.meshes[i];
        if (x.firstIndex != y.firstIndex || x.indexCount != y.indexCount || x.vertexOffset != y.vertexOffset ||
            x.vertexCount != y.vertexCount || x.material != y.material)
            return "mesh " + std::to_string(i);
    }
    if (a.objects.size() != b.objects.size()) return "object count";
    for (size_t i = 0; i < a.objects.size(); ++i) {
        if (a.objects[i].mesh != b.objects[i].mesh || !sameBytes(a.objects[i].model, b.objects[i].model))
            return "object " + std::to_string(i) + " (" + a.objects[i].name + ")";
    }
    if (a.materials.size() != b.materials.size()) return "material count";
    for (size_t i = 0; i < a.materials.size(); ++i) {
        const Material& x = a.materials[i];
        const Material& y = b.materials[i];
        if (!sameBytes(x.baseColorFactor, y.baseColorFactor) || !sameBytes(x.metallic, y.metallic) ||
            !sameBytes(x.roughness, y.roughness))
            return "material " + std::to_string(i);
    }
    const Camera& p = a.camera;
    const Camera& q = b.camera;
    if (!sameBytes(p.view, q.view) || !sameBytes(p.yfov, q.yfov) || !sameBytes(p.znear, q.znear) ||
        !sameBytes(p.zfar, q.zfar))
        return "camera";
    if (a.lights.size() != b.lights.size()) return "light count";
    for (size_t i = 0; i < a.lights.size(); ++i) {
        const Light& x = a.lights[i];
        const Light& y = b.lights[i];
        if (x.type != y.type || !sameBytes(x.position, y.position) || !sameBytes(x.direction, y.direction) ||
            !sameBytes(x.color, y.color) || !sameBytes(x.intensity, y.intensity) || !sameBytes(x.range, y.range) ||
            !sameBytes(x.innerConeAngle, y.innerConeAngle) || !sameBytes(x.outerConeAngle, y.outerConeAngle) ||
            x.castsShadow != y.castsShadow)
            return "light " + std::to_string(i) + " (" + x.name + ")";
    }
    return "";
}

float distanceToObjectBox(const Scene& scene, const Object& object, const glm::vec3& point) {
    const Bounds& box = scene.meshes[object.mesh].localBounds;
    const glm::vec3 local = glm::vec3(glm::inverse(object.model) * glm::vec4(point, 1.0f));
    return glm::distance(local, glm::clamp(local, box.min, box.max));
}

}  // namespace punctual::testing
