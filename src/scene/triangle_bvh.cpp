#include "scene/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace punctual {
namespace {

constexpr uint32_t kLeafSize = 4;

}  // namespace

TriangleBvh::TriangleBvh(const Scene& scene) {
    // Reserved once: a scene of 10^7 triangles would otherwise hold up to twice its triangles while
    // the array grows.
    size_t triangleCount = 0;
    for (const Object& object : scene.objects) triangleCount += scene.meshes.at(object.mesh).indexCount / 3;
    triangles_.reserve(triangleCount);
    for (const Object& object : scene.objects) {
        const Mesh& mesh = scene.meshes.at(object.mesh);
        for (uint32_t i = 0; i + 2 < mesh.indexCount; i += 3) {
            glm::vec3 corners[3];
            for (uint32_t k = 0; k < 3; ++k) {
                const uint32_t index = scene.indices.at(size_t(mesh.firstIndex) + i + k);
                const glm::vec3 local = scene.vertices.at(size_t(mesh.vertexOffset) + index).position;
                corners[k] = glm::vec3(object.model * glm::vec4(local, 1.0f));
            }
            triangles_.push_back({corners[0], corners[1] - corners[0], corners[2] - corners[0]});
        }
    }
    PUNCTUAL_CHECK(triangles_.size() < size_t(std::numeric_limits<uint32_t>::max()), "too many triangles");
    if (triangles_.empty()) return;
    std::vector<Centroid> centroids(triangles_.size());
    for (uint32_t i = 0; i < centroids.size(); ++i) {
        const Triangle& t = triangles_[i];
        centroids[i] = {t.v0 + (t.e1 + t.e2) * (1.0f / 3.0f), i};
    }
    nodes_.reserve(2 * triangles_.size() / kLeafSize + 1);
    glm::vec3 bounds[2];
    build(0, uint32_t(triangles_.size()), centroids, bounds);
    order_.resize(centroids.size());
    for (uint32_t i = 0; i < centroids.size(); ++i) order_[i] = centroids[i].triangle;
}

uint32_t TriangleBvh::build(uint32_t first, uint32_t count, std::vector<Centroid>& centroids, glm::vec3 bounds[2]) {
    const uint32_t index = uint32_t(nodes_.size());
    nodes_.emplace_back();
    glm::vec3 centroidLo(std::numeric_limits<float>::max());
    glm::vec3 centroidHi(-std::numeric_limits<float>::max());
    for (uint32_t i = first; i < first + count; ++i) {
        centroidLo = glm::min(centroidLo, centroids[i].position);
        centroidHi = glm::max(centroidHi, centroids[i].position);
    }
    const glm::vec3 extent = centroidHi - centroidLo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(-std::numeric_limits<float>::max());
    if (count <= kLeafSize || !(extent[axis] > 0.0f)) {
        for (uint32_t i = first; i < first + count; ++i) {
            const Triangle& t = triangles_[centroids[i].triangle];
            // The corners the intersection test uses (v0 + e may differ from the file's vertex in
            // the last bit, so the box is built from these).
            for (const glm::vec3& p : {t.v0, t.v0 + t.e1, t.v0 + t.e2}) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        }
        nodes_[index].first = first;
        nodes_[index].count = count;
    } else {
        // Median split; ties broken by triangle index, so the partition is the same everywhere.
        const uint32_t middle = first + count / 2;
        std::nth_element(centroids.begin() + first, centroids.begin() + middle, centroids.begin() + first + count,
                         [&](const Centroid& a, const Centroid& b) {
                             const float ca = a.position[axis];
                             const float cb = b.position[axis];
                             return ca < cb || (ca == cb && a.triangle < b.triangle);
                         });
        glm::vec3 left[2];
        glm::vec3 right[2];
        build(first, middle - first, centroids, left);
        const uint32_t rightChild = build(middle, first + count - middle, centroids, right);
        lo = glm::min(left[0], right[0]);
        hi = glm::max(left[1], right[1]);
        nodes_[index].first = rightChild;
        nodes_[index].count = 0;
    }
    // A relative pad keeps the box test conservative under its own rounding.
    const glm::vec3 pad = (hi - lo) * 1e-5f + glm::max(glm::abs(lo), glm::abs(hi)) * 1e-6f;
    nodes_[index].min = lo - pad;
    nodes_[index].max = hi + pad;
    bounds[0] = lo;
    bounds[1] = hi;
    return index;
}

bool TriangleBvh::hitTriangle(const Triangle& t, const glm::vec3& origin, const glm::vec3& direction,
                              float maxDistance, float& distance) const {
    // Möller-Trumbore.
    const glm::vec3 p = glm::cross(direction, t.e2);
    const float det = glm::dot(t.e1, p);
    if (!(std::abs(det) > 0.0f)) return false;  // parallel, or a degenerate triangle
    const float inverse = 1.0f / det;
    const glm::vec3 s = origin - t.v0;
    const float u = glm::dot(s, p) * inverse;
    if (!(u >= 0.0f && u <= 1.0f)) return false;
    const glm::vec3 q = glm::cross(s, t.e1);
    const float v = glm::dot(direction, q) * inverse;
    if (!(v >= 0.0f && u + v <= 1.0f)) return false;
    const float d = glm::dot(t.e2, q) * inverse;
    if (!(d > 0.0f && d <= maxDistance)) return false;
    distance = d;
    return true;
}

template <typename Visit>
void TriangleBvh::traverse(const glm::vec3& origin, const glm::vec3& direction, float& maxDistance,
                           Visit&& visit) const {
    if (nodes_.empty()) return;
    const glm::vec3 inverse = 1.0f / direction;  // +-inf for axis-parallel rays: the slabs still work
    uint32_t stack[64];
    uint32_t depth = 0;
    stack[depth++] = 0;
    while (depth > 0) {
        const Node& node = nodes_[stack[--depth]];
        float tNear = 0.0f;
        float tFar = maxDistance;
        for (int axis = 0; axis < 3; ++axis) {
            const float t1 = (node.min[axis] - origin[axis]) * inverse[axis];
            const float t2 = (node.max[axis] - origin[axis]) * inverse[axis];
            // A NaN (0 x inf, the origin on a slab plane of a parallel ray) drops out of max/min
            // when it is their second argument: the axis is then not used to reject, which is
            // conservative.
            tNear = std::max(tNear, std::min(t1, t2));
            tFar = std::min(tFar, std::max(t1, t2));
        }
        if (tNear > tFar) continue;
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                float distance = 0.0f;
                if (hitTriangle(triangles_[order_[i]], origin, direction, maxDistance, distance) &&
                    visit(order_[i], distance))
                    return;
            }
            continue;
        }
        // A median-split tree is at most ~log2(n) deep, far below 64 for any 32-bit count.
        PUNCTUAL_CHECK(depth + 2 <= 64, "bounding volume hierarchy deeper than its stack");
        stack[depth++] = node.first;
        stack[depth++] = uint32_t(&node - nodes_.data()) + 1;
    }
}

std::optional<TriangleBvh::Hit> TriangleBvh::intersect(const glm::vec3& origin, const glm::vec3& direction,
                                                       float maxDistance) const {
    float nearest = maxDistance;
    uint32_t hitIndex = std::numeric_limits<uint32_t>::max();
    traverse(origin, direction, nearest, [&](uint32_t triangle, float distance) {
        if (distance < nearest || (distance == nearest && triangle < hitIndex)) {
            nearest = distance;
            hitIndex = triangle;
        }
        return false;
    });
    if (hitIndex == std::numeric_limits<uint32_t>::max()) return std::nullopt;
    const Triangle& t = triangles_[hitIndex];
    glm::vec3 normal = glm::normalize(glm::cross(t.e1, t.e2));
    if (glm::dot(normal, direction) > 0.0f) normal = -normal;
    return Hit{nearest, normal};
}

bool TriangleBvh::occluded(const glm::vec3& from, const glm::vec3& to) const {
    const glm::vec3 offset = to - from;
    const float length = glm::length(offset);
    if (!(length > 0.0f)) return false;
    const glm::vec3 direction = offset / length;
    // Strictly before `to`: a triangle exactly at the end point does not block it.
    float maxDistance = length * (1.0f - 1e-6f);
    bool blocked = false;
    traverse(from, direction, maxDistance, [&](uint32_t, float) {
        blocked = true;
        return true;
    });
    return blocked;
}

}  // namespace punctual
