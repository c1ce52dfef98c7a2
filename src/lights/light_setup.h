#pragma once
// CPU light setup for one frame: cull the scene's spot and point lights to the view frustum, keep
// at most the capacity's spots and points (the most important ones; --max-lights, 64 + 32 by
// default), and pack them into the GPU layout of shaders/shared/gpu_types.h. Also picks the one
// directional light (the sun).
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gpu_types.h"
#include "scene/scene.h"

namespace punctual {

// How many spot and point lights a frame keeps (--max-lights S,P): the design notes' 64 + 32 by
// default, at most PUNCTUAL_MAX_LIGHT_CAPACITY of each kind.
struct LightCapacity {
    uint32_t spots = PUNCTUAL_DEFAULT_MAX_SPOT_LIGHTS;
    uint32_t points = PUNCTUAL_DEFAULT_MAX_POINT_LIGHTS;
};

struct FrameLights {
    std::vector<gpu::GpuPunctualLight> packed;  // spots first (spotCount), then points (pointCount); no padding to the caps
    std::vector<uint32_t> sceneLightIndex;      // packed[i] came from scene.lights[sceneLightIndex[i]]
    uint32_t spotCount = 0;
    uint32_t pointCount = 0;
    gpu::GpuDirectionalLight sun{};             // directionToLight.w = 0 when the scene has none
    uint32_t directionalCount = 0;              // 0 or 1: the first directional light of the scene
    uint32_t culledByFrustum = 0;               // spot/point lights whose bounding sphere is outside the view
    uint32_t droppedByCap = 0;                  // visible lights over the capacity, plus directional lights after the first
};

// A sphere bounding everything a light can illuminate (attenuation > 0).
struct BoundingSphere {
    glm::vec3 center{0.0f};
    float radius = 0.0f;
};

// Point: (position, range). Spot: the smallest sphere around its cone of slant length `range`
// (gpu::spotBoundingSphere in shaders/shared/culling.h, with the derivation); it also contains
// the cone's spherical cap. Not meaningful for directional lights.
BoundingSphere lightBoundingSphere(const Light& light);

// The six planes of a view frustum, each (n, d) with unit n pointing inside: a point p is inside
// when dot(n, p) + d >= 0 for all six.
struct Frustum {
    std::array<glm::vec4, 6> planes{};  // left, right, bottom, top, near, far

    // Conservative: false only when the sphere is entirely behind one plane. (Spheres near a
    // frustum corner can be kept although outside; that only costs a little culling efficiency.)
    bool intersectsSphere(const glm::vec3& center, float radius) const;
};

// Gribb-Hartmann plane extraction from a Vulkan-style clip transform (projection * view with
// depth in [0, w]; a y flip in the projection is harmless, it only swaps top and bottom).
Frustum extractFrustum(const glm::mat4& viewProjection);

// How much a light matters to this frame; used to choose which lights survive the caps.
// importance = peak intensity (intensity x max colour channel)
//            x fraction of the sphere of directions it emits into (1 for points, (1 - cos outer)/2 for spots)
//            x (R / max(distance from the camera to its bounding sphere's centre, R))^2
// where R is the bounding sphere's radius (the range for points). The last factor approximates the
// solid angle the light's volume covers on screen, saturating at 1 when the camera is inside it.
float lightImportance(const Light& light, const glm::vec3& cameraPosition);

// Packing into the shared GPU layout (see GpuPunctualLight / GpuDirectionalLight).
gpu::GpuPunctualLight packPunctualLight(const Light& light);
gpu::GpuDirectionalLight packDirectionalLight(const Light& light);

// The whole setup: frustum cull, rank and cap per type, keep the survivors in scene order (so that
// a light added far away never reorders the others and the shading sum stays the same), pack.
FrameLights setupFrameLights(const Scene& scene, const glm::mat4& view, const glm::mat4& projection,
                             const LightCapacity& capacity = {});

}  // namespace punctual
