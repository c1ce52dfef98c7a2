#pragma once
// A small CPU ray caster over a Scene's world-space triangles, for the few hundred rays that
// placing generated lights needs (scene/light_reach.h). The Embree reference is the ray tracer
// for images; this stays in the scene library, which links neither Embree nor Vulkan.
//
// Results never depend on the tree's shape: occluded() is a yes/no over all triangles, and
// intersect() returns the smallest distance, ties going to the lowest triangle index.
#include <cstdint>
#include <memory>
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

    // Calls `visit(triangle index, distance)` for each triangle hit within (0, maxDistance],
    // pruning with the current maxDistance, which `visit` may lower; stops when it returns true.
    template <typename Visit>
    void traverse(const glm::vec3& origin, const glm::vec3& direction, float& maxDistance, Visit&& visit) const;
    bool hitTriangle(const Triangle& t, const glm::vec3& origin, const glm::vec3& direction, float maxDistance,
                     float& distance) const;

    // A triangle's centroid beside its index, sorted in place while building: every pass over a
    // node's range reads memory in order (through order_ it would jump across all triangles, which
    // at 10^7 triangles cost more than the arithmetic).
    struct Centroid {
        glm::vec3 position;
        uint32_t triangle = 0;
    };
    // Builds the node over centroids[first, first + count) and returns its index; `bounds` gets the
    // node's unpadded box (the union of its children's: each triangle is read once, at its leaf).
    uint32_t build(uint32_t first, uint32_t count, std::vector<Centroid>& centroids, glm::vec3 bounds[2]);

    std::vector<Triangle> triangles_;
    std::vector<uint32_t> order_;  // triangle indices, leaves' ranges
    std::vector<Node> nodes_;
};

// A scene's tree, built on first use and then kept: the frame's planners that cast rays into the
// same geometry (the cascades' fitted distance, the shadow maps' auto resolution) share one build,
// and a frame that needs neither builds none. Only the scene's objects and meshes shape the tree,
// so a copy of the scene with another camera may use it too.
class LazyTriangleBvh {
public:
    explicit LazyTriangleBvh(const Scene& scene) : scene_(scene) {}
    const TriangleBvh& get() const {
        if (!bvh_) bvh_ = std::make_unique<TriangleBvh>(scene_);
        return *bvh_;
    }

private:
    const Scene& scene_;
    mutable std::unique_ptr<TriangleBvh> bvh_;
};

}  // namespace punctual
