#include "lights/cascade_setup.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cascades.h"
#include "core/error.h"
#include "lights/shadow_resolution.h"
#include "lights/shadow_setup.h"

namespace punctual {

void validateCascadeSettings(const CascadeSettings& settings) {
    if (settings.count < 1 || settings.count > PUNCTUAL_MAX_CASCADES) {
        throw Error("--cascades", "must be from 1 to " + std::to_string(PUNCTUAL_MAX_CASCADES));
    }
    float previous = 0.0f;
    for (const float split : settings.splits) {
        if (!std::isfinite(split) || split <= previous || split >= 1.0f) {
            throw Error("--cascade-splits", "expected three rising fractions of the shadow distance, each above 0 and below 1");
        }
        previous = split;
    }
    if (settings.lambda >= 0.0f && !(settings.lambda <= 1.0f)) throw Error("--cascade-lambda", "must be from 0 to 1");
    if (!std::isfinite(settings.shadowDistance) || settings.shadowDistance < 0.0f || settings.shadowDistance > 1e6f) {
        throw Error("--shadow-distance", "must be a distance in metres above 0 and at most 1000000");
    }
    if (!(settings.cascadeFade > 0.0f && settings.cascadeFade <= 1.0f) ||
        !(settings.distanceFade > 0.0f && settings.distanceFade <= 1.0f)) {
        throw Error("cascades", "the cascade and distance fades must be above 0 and at most 1");
    }
}

std::array<float, PUNCTUAL_MAX_CASCADES> cascadeSplits(const CascadeSettings& settings, float nearPlane,
                                                       float shadowDistance) {
    std::array<float, PUNCTUAL_MAX_CASCADES> splits{};
    for (uint32_t i = 0; i < settings.count; ++i) {
        if (i + 1 == settings.count) {
            splits[i] = shadowDistance;
        } else if (settings.lambda >= 0.0f) {
            splits[i] = gpu::practicalSplit(nearPlane, shadowDistance, float(i + 1) / float(settings.count), settings.lambda);
        } else {
            splits[i] = settings.splits[i] * shadowDistance;
        }
    }
    return splits;
}

float farthestVisibleReceiver(const Scene& scene, uint32_t width, uint32_t height, const LazyTriangleBvh* geometry) {
    const uint32_t step = std::max({width / 160u, height / 90u, 1u});
    float farthest = 0.0f;
    forEachVisibleReceiver(scene, width, height, step, [&](uint32_t, uint32_t, const ReceiverSample& sample) {
        farthest = std::max(farthest, -(scene.camera.view * glm::vec4(sample.position, 1.0f)).z);
    }, geometry);
    return farthest;
}

float cascadeShadowDistance(const CascadeSettings& settings, const Scene& scene, uint32_t width, uint32_t height,
                            const LazyTriangleBvh* geometry) {
    if (settings.shadowDistance > 0.0f) return settings.shadowDistance;
    const float farthest = farthestVisibleReceiver(scene, width, height, geometry);
    // Up to the next quarter octave: 2^(ceil(4 log2 d) / 4).
    const float rounded = farthest > 0.0f ? std::exp2(std::ceil(4.0f * std::log2(farthest)) * 0.25f) : kMaxFittedShadowDistance;
    return std::clamp(rounded, 4.0f * scene.camera.znear, std::max(kMaxFittedShadowDistance, 4.0f * scene.camera.znear));
}

namespace {

// The index of the scene's first directional light (the one FrameLights packs as the sun).
uint32_t firstDirectionalLight(const Scene& scene) {
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
        if (scene.lights[i].type == LightType::Directional) return i;
    }
    return uint32_t(scene.lights.size());
}

// The extent of a world box along a unit axis.
glm::vec2 extentAlong(const Bounds& box, const glm::vec3& axis) {
    const glm::vec3 centre = box.center();
    const glm::vec3 half = box.size() * 0.5f;
    const float middle = glm::dot(centre, axis);
    const float reach = glm::dot(half, glm::abs(axis));
    return {middle - reach, middle + reach};
}

// The objects that can shadow a receiver inside cascade `index`'s sphere: those whose bounds meet
// the sphere's square across the light (padded by a tenth of the radius, more than snapping moves
// it) anywhere from the sphere's far side up towards the sun (what lies between the sun and the
// sphere is pancaked, never cut). The seed's culling bias then drops the casters that lie wholly
// inside `cullingFactor` of the previous cascade's sphere: that cascade already holds them.
std::vector<uint32_t> cascadeCasters(const Scene& scene, const CascadePlan& cascades, uint32_t index,
                                     float cullingFactor) {
    const glm::vec3 centre(cascades.spheres[index]);
    const float radius = cascades.spheres[index].w;
    const float pad = 0.1f * radius;
    const glm::vec2 across(glm::dot(centre, cascades.lightX), glm::dot(centre, cascades.lightY));
    const float farSide = glm::dot(centre, cascades.lightZ) - radius;
    std::vector<uint32_t> casters;
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        const Bounds& box = scene.objects[i].worldBounds;
        if (box.empty()) continue;
        const glm::vec2 x = extentAlong(box, cascades.lightX);
        const glm::vec2 y = extentAlong(box, cascades.lightY);
        const glm::vec2 z = extentAlong(box, cascades.lightZ);
        if (x.y < across.x - radius - pad || x.x > across.x + radius + pad) continue;
        if (y.y < across.y - radius - pad || y.x > across.y + radius + pad) continue;
        if (z.y < farSide) continue;
        if (index > 0 && cullingFactor > 0.0f) {
            const glm::vec4 previous = cascades.spheres[index - 1];
            if (glm::length(box.center() - glm::vec3(previous)) + box.radius() <= cullingFactor * previous.w) continue;
        }
        casters.push_back(i);
    }
    return casters;
}

}  // namespace

void planCascades(ShadowPlan& plan, const Scene& scene, const FrameLights& lights, uint32_t width, uint32_t height,
                  const ShadowSettings& settings, const LazyTriangleBvh* geometry) {
    plan.cascades = CascadePlan{};
    if (!settings.enabled || lights.directionalCount == 0) return;
    const uint32_t sunIndex = firstDirectionalLight(scene);
    if (sunIndex >= scene.lights.size() || !scene.lights[sunIndex].castsShadow) return;

    CascadePlan& cascades = plan.cascades;
    cascades.sceneLight = sunIndex;
    cascades.strength = settings.strength * scene.lights[sunIndex].shadowStrength;
    // The sun's axes: z towards it, x and y across its light (any pair; fixed in the world, so that
    // texel snapping holds).
    cascades.lightZ = glm::normalize(glm::vec3(lights.sun.directionToLight));
    const glm::vec3 reference = std::abs(cascades.lightZ.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    cascades.lightX = glm::normalize(glm::cross(reference, cascades.lightZ));
    cascades.lightY = glm::cross(cascades.lightZ, cascades.lightX);

    const Camera& camera = scene.camera;
    const glm::mat4 cameraToWorld = glm::inverse(camera.view);
    const glm::vec3 eye(cameraToWorld[3]);
    const glm::vec3 forward = -glm::normalize(glm::vec3(cameraToWorld[2]));
    const float tanY = std::tan(camera.yfov * 0.5f);
    const float tanX = tanY * float(width) / float(height);
    const float spread = tanX * tanX + tanY * tanY;

    const CascadeSettings& cascadeSettings = settings.cascades;
    cascades.shadowDistance = cascadeShadowDistance(cascadeSettings, scene, width, height, geometry);
    cascades.distanceFitted = cascadeSettings.shadowDistance <= 0.0f;
    cascades.splits = cascadeSplits(cascadeSettings, camera.znear, cascades.shadowDistance);
    cascades.count = cascadeSettings.count;
    cascades.firstView = uint32_t(plan.views.size());
    float previous = camera.znear;
    for (uint32_t i = 0; i < cascades.count; ++i) {
        const glm::vec2 sphere = gpu::sliceBoundingSphere(previous, cascades.splits[i], spread);
        cascades.spheres[i] = glm::vec4(eye + forward * sphere.x, sphere.y);
        previous = cascades.splits[i];
    }
    for (uint32_t i = 0; i < cascades.count; ++i) {
        ShadowView view;
        view.isCascade = true;
        view.face = i;
        view.casters = cascadeCasters(scene, cascades, i, cascadeSettings.cullingFactor());
        view.tanSpan = 2.0f * cascades.spheres[i].w;  // orthographic: the same width at every depth
        view.nearPlane = 0.0f;
        view.farPlane = 2.0f * cascades.spheres[i].w;
        plan.views.push_back(std::move(view));
    }
}

void finishCascadeView(ShadowView& view, const CascadePlan& cascades, const ShadowSettings& settings) {
    const glm::vec4 sphere = cascades.spheres[view.face];
    const float radius = sphere.w;
    const float texel = gpu::cascadeTexelWorldSize(radius, float(std::max(view.resolution, 1u)));
    const glm::vec3 centre(sphere);
    glm::vec2 across(glm::dot(centre, cascades.lightX), glm::dot(centre, cascades.lightY));
    float height = glm::dot(centre, cascades.lightZ);
    if (settings.cascades.snapToTexels) {
        across = gpu::snapToTexels(across, texel);
        height = gpu::snapToTexels(glm::vec2(height), texel).x;
    }
    // clip.x = (p.X - cx) / r, clip.y = (p.Y - cy) / r: the sphere's square across the light onto
    // [-1, 1]; clip.z = (h + r - p.Z) / 2r: depth 0 at the sphere's side nearest the sun, 1 at the
    // far side; clip.w = 1 (orthographic). Column-major: m[column][row].
    glm::mat4 m(0.0f);
    for (int c = 0; c < 3; ++c) {
        m[c][0] = cascades.lightX[c] / radius;
        m[c][1] = cascades.lightY[c] / radius;
        m[c][2] = -cascades.lightZ[c] / (2.0f * radius);
    }
    m[3][0] = -across.x / radius;
    m[3][1] = -across.y / radius;
    m[3][2] = (height + radius) / (2.0f * radius);
    m[3][3] = 1.0f;
    view.gpu.viewProjection = m;
    view.tanSpan = 2.0f * radius;
    view.nearPlane = 0.0f;
    view.farPlane = 2.0f * radius;
}

float cascadeTexelSize(const ShadowPlan& plan, uint32_t index) {
    const ShadowView& view = plan.views[plan.cascades.firstView + index];
    return view.resolution > 0 ? gpu::cascadeTexelWorldSize(plan.cascades.spheres[index].w, float(view.resolution)) : 0.0f;
}

void selectCascadesBy(ShadowPlan& plan, const ShadowSettings& settings) {
    for (uint32_t i = 0; i < plan.cascades.count; ++i) {
        const ShadowView& view = plan.views[plan.cascades.firstView + i];
        const float reach = cascadeTexelSize(plan, i) * (settings.penumbraTexels(view.resolution) + 1.0f);
        const float radius = std::max(plan.cascades.spheres[i].w - reach, 0.0f);
        plan.cascades.selection[i] = glm::vec4(glm::vec3(plan.cascades.spheres[i]), radius * radius);
    }
}

uint32_t cascadeAt(const CascadePlan& cascades, const glm::vec3& position) {
    const auto& s = cascades.selection;
    return gpu::cascadeOf(position, s[0], s[1], s[2], s[3], cascades.count);
}

bool nearCascadeSplit(const ShadowPlan& plan, const glm::vec3& position) {
    const CascadePlan& cascades = plan.cascades;
    for (uint32_t i = 0; i + 1 < cascades.count; ++i) {
        const float texel = cascadeTexelSize(plan, i);
        const float distance = glm::length(position - glm::vec3(cascades.selection[i]));
        if (std::abs(distance - std::sqrt(cascades.selection[i].w)) <= texel) return true;
    }
    return false;
}

}  // namespace punctual
