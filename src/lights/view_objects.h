#pragma once
// Per-view object culling on the CPU: which objects a view can draw a fragment of. The camera's
// raster passes (depth prepass, forward, transparent) draw only those; drawing the rest would
// produce no fragment at all, so the image does not change, only the vertex work.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual {

// The objects whose world bounds meet the frustum of `viewProjection` (Vulkan clip space, depth
// in [0, w], reversed or not), ascending. Conservative: each box is first widened by a
// millionth of the scene's extent plus a ten-thousandth of its own, more than the rounding of the
// plane extraction and of the box test can move a plane, so an object that may cover a pixel is
// never dropped. One pass over the objects: O(objects), not triangles.
std::vector<uint32_t> objectsInView(const Scene& scene, const glm::mat4& viewProjection);

// The entries of `objects` (any order) that `inView` (ascending) holds, in the order of `objects`.
std::vector<uint32_t> keepInView(const std::vector<uint32_t>& objects, const std::vector<uint32_t>& inView);

// The triangles drawn when `objects` are: each object's mesh, once per object.
uint64_t trianglesOf(const Scene& scene, const std::vector<uint32_t>& objects);

}  // namespace punctual
