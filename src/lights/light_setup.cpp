#include "lights/light_setup.h"

#include <algorithm>
#include <cmath>

#include "culling.h"
#include "shading.h"

namespace punctual {

namespace {

constexpr float kHalfPi = 1.57079633f;

// The unit shine direction. A degenerate one (validateLights rejects it) falls back to -Z rather
// than producing NaN, which would poison even a point light's angular factor (NaN * 0 = NaN).
glm::vec3 unitDirection(const Light& light) {
    const float length = glm::length(light.direction);
    return length > 1e-6f && std::isfinite(length) ? light.direction / length : glm::vec3(0.0f, 0.0f, -1.0f);
}

float clampedOuterAngle(const Light& light) { return std::clamp(light.outerConeAngle, 0.0f, kHalfPi); }

float peakIntensity(const Light& light) {
    return light.intensity * std::max({light.color.r, light.color.g, light.color.b, 0.0f});
}

}  // namespace

// Points: the range sphere. Spots: the smallest sphere around the cone and its cap, derived at
// gpu::spotBoundingSphere (culling.h), the one formula the GPU's tile culling also uses.
BoundingSphere lightBoundingSphere(const Light& light) {
    if (light.type != LightType::Spot) return {light.position, light.range};
    const glm::vec4 sphere =
        gpu::spotBoundingSphere(light.position, unitDirection(light), light.range, std::cos(clampedOuterAngle(light)));
    return {glm::vec3(sphere), sphere.w};
}

bool Frustum::intersectsSphere(const glm::vec3& center, float radius) const {
    for (const glm::vec4& plane : planes)
        if (glm::dot(glm::vec3(plane), center) + plane.w < -radius) return false;
    return true;
}

// Gribb & Hartmann, "Fast Extraction of Viewing Frustum Planes from the World-View-Projection
// Matrix" (2001). A world point p maps to clip c = M p, so c_i = row_i(M) . (p, 1). Vulkan's clip
// volume is -w <= x <= w, -w <= y <= w, 0 <= z <= w, giving the planes
//   left  row3 + row0 >= 0     right row3 - row0 >= 0
//   bottom row3 + row1 >= 0    top   row3 - row1 >= 0   (a y flip in M just swaps these two)
//   near  row2 >= 0            far   row3 - row2 >= 0   (OpenGL's near would be row3 + row2)
// With the camera's reversed depth (1 at near, 0 at far) the same two rows bound it, with their
// roles swapped: row2 >= 0 is its far plane, row3 - row2 >= 0 its near one.
// Each is normalised by the length of its xyz so dot(n, p) + d is a distance in world units.
Frustum extractFrustum(const glm::mat4& viewProjection) {
    auto row = [&](int i) {
        return glm::vec4(viewProjection[0][i], viewProjection[1][i], viewProjection[2][i], viewProjection[3][i]);
    };
    const glm::vec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
    Frustum frustum;
    frustum.planes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2};
    for (glm::vec4& plane : frustum.planes) {
        const float length = glm::length(glm::vec3(plane));
        plane /= std::max(length, 1e-20f);
    }
    return frustum;
}

float lightImportance(const Light& light, const glm::vec3& cameraPosition) {
    // Directions emitted into, as a fraction of the full sphere: a cone of half-angle theta
    // subtends 2 pi (1 - cos theta) of the 4 pi steradians.
    const float emittedFraction =
        light.type == LightType::Spot ? (1.0f - std::cos(clampedOuterAngle(light))) * 0.5f : 1.0f;
    const BoundingSphere sphere = lightBoundingSphere(light);
    const float distance = glm::length(sphere.center - cameraPosition);
    // A sphere of radius R at distance d subtends a solid angle of about pi (R/d)^2: screen
    // coverage up to a constant. Clamp d to R so a camera inside the sphere gets the maximum, 1.
    const float coverage = sphere.radius / std::max(distance, std::max(sphere.radius, 1e-6f));
    const float importance = peakIntensity(light) * emittedFraction * coverage * coverage;
    return std::isfinite(importance) ? std::max(importance, 0.0f) : 0.0f;
}

gpu::GpuPunctualLight packPunctualLight(const Light& light) {
    gpu::GpuPunctualLight packed{};
    const float rangeSquared = light.range * light.range;
    packed.positionInvRangeSq = glm::vec4(light.position, 1.0f / std::max(rangeSquared, 1e-4f));
    packed.radiantColor = glm::vec4(light.color * light.intensity, light.range);
    if (light.type == LightType::Spot) {
        // Angular attenuation saturate(cos(angle) * k + offset)^2 is 1 at the inner cone and 0 at the
        // outer: k = 1 / (cos inner - cos outer), offset = -cos outer * k.
        const float cosOuter = std::cos(clampedOuterAngle(light));
        const float cosInner = std::cos(std::clamp(light.innerConeAngle, 0.0f, kHalfPi));
        const float k = gpu::spotAngleScale(cosInner, cosOuter);
        packed.directionAngleScale = glm::vec4(unitDirection(light), k);
        packed.angleOffsetShadow = glm::vec4(-cosOuter * k, -1.0f, cosOuter, 0.0f);
    } else {
        // Scale 0, offset 1: the angular factor is saturate(1)^2 = 1 exactly.
        packed.directionAngleScale = glm::vec4(unitDirection(light), 0.0f);
        packed.angleOffsetShadow = glm::vec4(1.0f, -1.0f, -1.0f, 0.0f);  // cos outer -1: all directions
    }
    return packed;
}

gpu::GpuDirectionalLight packDirectionalLight(const Light& light) {
    gpu::GpuDirectionalLight sun{};
    sun.directionToLight = glm::vec4(-unitDirection(light), 1.0f);
    sun.illuminance = glm::vec4(light.color * light.intensity, 0.0f);
    return sun;
}

FrameLights setupFrameLights(const Scene& scene, const glm::mat4& view, const glm::mat4& projection,
                             const LightCapacity& capacity) {
    FrameLights frame;
    const Frustum frustum = extractFrustum(projection * view);
    const glm::vec3 cameraPosition = glm::vec3(glm::inverse(view)[3]);

    struct Candidate {
        uint32_t sceneIndex;
        float importance;
    };
    std::vector<Candidate> spots, points;

    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        if (light.type == LightType::Directional) {
            if (frame.directionalCount == 0) {
                frame.sun = packDirectionalLight(light);
                frame.directionalCount = 1;
            } else {
                ++frame.droppedByCap;  // one sun per frame
            }
            continue;
        }
        const BoundingSphere sphere = lightBoundingSphere(light);
        if (!frustum.intersectsSphere(sphere.center, sphere.radius)) {
            ++frame.culledByFrustum;
            continue;
        }
        (light.type == LightType::Spot ? spots : points).push_back({i, lightImportance(light, cameraPosition)});
    }

    // Keep the `cap` most important candidates, ties going to the lower scene index, then restore
    // scene order: the packed order decides the order in which the shader sums lights, and scene
    // order keeps that sum (and so the image, bit for bit) unchanged when an unrelated light
    // enters or leaves the frame.
    auto keepMostImportant = [&](std::vector<Candidate>& candidates, size_t cap) {
        if (candidates.size() <= cap) return;
        std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
            if (a.importance != b.importance) return a.importance > b.importance;
            return a.sceneIndex < b.sceneIndex;
        });
        frame.droppedByCap += static_cast<uint32_t>(candidates.size() - cap);
        candidates.resize(cap);
        std::sort(candidates.begin(), candidates.end(),
                  [](const Candidate& a, const Candidate& b) { return a.sceneIndex < b.sceneIndex; });
    };
    keepMostImportant(spots, capacity.spots);
    keepMostImportant(points, capacity.points);

    frame.spotCount = static_cast<uint32_t>(spots.size());
    frame.pointCount = static_cast<uint32_t>(points.size());
    frame.packed.reserve(spots.size() + points.size());
    frame.sceneLightIndex.reserve(spots.size() + points.size());
    for (const std::vector<Candidate>* list : {&spots, &points}) {
        for (const Candidate& candidate : *list) {
            frame.packed.push_back(packPunctualLight(scene.lights[candidate.sceneIndex]));
            frame.sceneLightIndex.push_back(candidate.sceneIndex);
        }
    }
    return frame;
}

}  // namespace punctual
