#include "lights/caster_distance.h"

#include <algorithm>
#include <limits>

namespace punctual {

glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 ab = b - a;
    const glm::vec3 ac = c - a;
    const glm::vec3 ap = p - a;
    const float d1 = glm::dot(ab, ap);
    const float d2 = glm::dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return a;  // vertex region A
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp);
    const float d4 = glm::dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return b;  // vertex region B
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));  // edge AB
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp);
    const float d6 = glm::dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return c;  // vertex region C
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));  // edge AC
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));  // edge BC
    // Inside the face: barycentric (u, v, w) = (va, vb, vc) / (va + vb + vc).
    const float denominator = va + vb + vc;
    if (!(denominator > 0.0f)) return a;  // degenerate (zero-area) triangle: its vertices were tested
    return a + ab * (vb / denominator) + ac * (vc / denominator);
}

float casterDistance(const Scene& scene, uint32_t object, const glm::vec3& point) {
    const Object& caster = scene.objects[object];
    const Bounds& box = caster.worldBounds;
    const glm::vec3 outside = glm::max(glm::max(box.min - point, point - box.max), glm::vec3(0.0f));
    const float boxDistance = glm::length(outside);
    if (boxDistance > 0.0f) return boxDistance;
    // Inside the bounds (a room modelled as one mesh around its lights): the triangles decide.
    const Mesh& mesh = scene.meshes[caster.mesh];
    float nearestSquared = std::numeric_limits<float>::max();
    const auto world = [&](uint32_t index) {
        return glm::vec3(caster.model * glm::vec4(scene.vertices[mesh.vertexOffset + index].position, 1.0f));
    };
    for (uint32_t i = 0; i + 2 < mesh.indexCount; i += 3) {
        const uint32_t* triangle = &scene.indices[mesh.firstIndex + i];
        const glm::vec3 a = world(triangle[0]);
        const glm::vec3 b = world(triangle[1]);
        const glm::vec3 c = world(triangle[2]);
        const glm::vec3 offset = closestPointOnTriangle(point, a, b, c) - point;
        nearestSquared = std::min(nearestSquared, glm::dot(offset, offset));
    }
    return mesh.indexCount >= 3 ? std::sqrt(nearestSquared) : boxDistance;
}

}  // namespace punctual
