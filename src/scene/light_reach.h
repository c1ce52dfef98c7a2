#pragma once
// Whether a light can reach anything the camera sees: the test every generated light must pass
// (scene/light_generator.h), so that `--lights S,P` on a small closed model puts no light inside
// it, where it would light nothing visible.
//
// The view is sampled by a grid of primary rays from the scene's camera (its vertical field of
// view in both directions: the frame's aspect is not known here, and a landscape frame shows at
// least that square). Each ray that meets a surface gives a sample: the point, and the normal
// turned towards the camera, as the renderer turns it (faces are two-sided). A point or spot light
// reaches a sample when the sample is within its range (attenuation > 0), inside a spot's outer
// cone, on the side of the surface the camera sees (N.L > 0) and the segment between them crosses
// no triangle: then, shadows or not, the light adds to that pixel.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "scene/triangle_bvh.h"

namespace punctual {

class LightReach {
public:
    explicit LightReach(const Scene& scene, uint32_t gridSide = 24);

    // No sample: the scene has no triangles, or the camera sees none of them. Nothing to test.
    bool empty() const { return samples_.empty(); }
    size_t sampleCount() const { return samples_.size(); }
    // The samples' points (lifted off their surfaces), in the samples' order.
    std::vector<glm::vec3> samplePoints() const;

    // Whether a point or spot light reaches some sample (see above). Casts at most
    // kMaxShadowRays segments, spread over the view; directional lights are not tested (true).
    bool reaches(const Light& light) const;

    static constexpr uint32_t kMaxShadowRays = 64;

private:
    struct Sample {
        glm::vec3 point;   // lifted off its surface along the normal, the start of shadow rays
        glm::vec3 normal;  // unit, towards the camera
    };
    TriangleBvh bvh_;
    std::vector<Sample> samples_;  // in a fixed shuffled order, so the capped rays cover the view
};

}  // namespace punctual
