#pragma once
// A small CPU ray caster over a Scene's world-space triangles, for the few hundred rays that
// placing generated lights needs (scene/light_reach.h). The Embree reference is the ray tracer
// for images; this stays in the scene library, which links neither Embree nor Vulkan.
//
// Results never depend on the tree's shape: occluded() is a yes/no over all triangles, and
// intersect() returns the smallest distance, ties going to the lowest triangle index.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual {

class TriangleBvh {
public:
    explicit TriangleBvh(const Scene& scene);

    bool empty() const { return triangles_.empty(); }
    size_t triangleCount() const { return triangles_.size(); }

    struct Hit {
        float distance = 0.0f;  // along the unit direction
        glm::vec3 normal{0.0f};  // unit geometric normal, facing the ray's origin
    };
    // The nearest triangle along `direction` (unit) within (0, maxDistance].
    std::optional<Hit> intersect(const glm::vec3& origin, const glm::vec3& direction, float maxDistance) const;
    // Whether any triangle crosses the open segment from `from` to `to`.
    bool occluded(const glm::vec3& from, const glm::vec3& to) const;

private:
    struct Triangle {
        glm::vec3 v0, e1, e2;  // a vertex and the two edges from it
    };
    struct Node {
        glm::vec3 min, max;
        uint32_t first = 0;  // leaf: first index into order_; inner: the right child (left is next)
        uint32_t count = 0;  // triangles in a leaf; 0 for an inner node
    };

    uint32_t build(uint32_t first, uint32_t count, std::vector<glm::vec3>& centroids);
    // Calls `visit(triangle index, distance)` for each triangle hit within (0, maxDistance],
    // pruning with the current maxDistance, which `visit` may lower; stops when it returns true.
    template <typename Visit>
    void traverse(const glm::vec3& origin, const glm::vec3& direction, float& maxDistance, Visit&& visit) const;
    bool hitTriangle(const Triangle& t, const glm::vec3& origin, const glm::vec3& direction, float maxDistance,
                     float& distance) const;

    std::vector<Triangle> triangles_;
    std::vector<uint32_t> order_;  // triangle indices, leaves' ranges
    std::vector<Node> nodes_;
};

}  // namespace punctual
