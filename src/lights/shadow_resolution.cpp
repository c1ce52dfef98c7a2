#include "lights/shadow_resolution.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "cascades.h"
#include "lights/shadow_setup.h"
#include "scene/triangle_bvh.h"
#include "shadows.h"

namespace punctual {

void forEachVisibleReceiver(const Scene& scene, uint32_t width, uint32_t height, uint32_t step,
                            const std::function<void(uint32_t x, uint32_t y, const ReceiverSample& sample)>& visit,
                            const LazyTriangleBvh* geometry) {
    if (width == 0 || height == 0 || step == 0) return;
    std::optional<LazyTriangleBvh> own;
    if (geometry == nullptr) geometry = &own.emplace(scene);
    const TriangleBvh& bvh = geometry->get();
    if (bvh.empty()) return;
    const Camera& camera = scene.camera;
    const glm::mat4 cameraToWorld = glm::inverse(camera.view);
    const glm::vec3 eye(cameraToWorld[3]);
    const glm::vec3 forward = -glm::normalize(glm::vec3(cameraToWorld[2]));
    const float tanHalf = std::tan(camera.yfov * 0.5f);
    const float aspect = float(width) / float(height);
    const float pixelSpan = 2.0f * tanHalf / float(height);  // screenPixelWorldSize's unit-depth span
    for (uint32_t y = step / 2; y < height; y += step) {
        for (uint32_t x = step / 2; x < width; x += step) {
            // The ray through the pixel's centre, in view space (x right, y up, looking down -Z).
            const float ndcX = 2.0f * (float(x) + 0.5f) / float(width) - 1.0f;
            const float ndcY = 1.0f - 2.0f * (float(y) + 0.5f) / float(height);
            const glm::vec3 viewRay(ndcX * tanHalf * aspect, ndcY * tanHalf, -1.0f);
            const glm::vec3 direction = glm::normalize(glm::mat3(cameraToWorld) * viewRay);
            // What lies nearer than the near plane is clipped away: the ray starts there.
            const float start = camera.znear * glm::length(viewRay);
            const auto hit = bvh.intersect(eye + direction * start, direction,
                                           std::max(camera.zfar * glm::length(viewRay) - start, 0.0f));
            if (!hit) continue;
            const glm::vec3 point = eye + direction * (start + hit->distance);
            const float viewDepth = glm::dot(point - eye, forward);
            visit(x, y, {point, hit->normal, gpu::screenPixelWorldSize(viewDepth, pixelSpan)});
        }
    }
}

VisibleReceivers sampleVisibleReceivers(const Scene& scene, uint32_t width, uint32_t height,
                                        const LazyTriangleBvh* geometry) {
    VisibleReceivers receivers;
    if (width == 0 || height == 0) return receivers;
    receivers.step = std::max({1u, (width + kMaxSampleColumns - 1) / kMaxSampleColumns,
                               (height + kMaxSampleRows - 1) / kMaxSampleRows});
    forEachVisibleReceiver(scene, width, height, receivers.step,
                           [&](uint32_t, uint32_t, const ReceiverSample& sample) { receivers.samples.push_back(sample); },
                           geometry);
    return receivers;
}

float resolutionNeededAt(const ShadowPlan& plan, uint32_t viewIndex, const gpu::GpuPunctualLight& light,
                         const ReceiverSample& sample) {
    const ShadowView& view = plan.views[viewIndex];
    const glm::vec3 lightPosition(light.positionInvRangeSq);
    const glm::vec3 toReceiver = sample.position - lightPosition;
    const float distance = glm::length(toReceiver);
    const float range = light.radiantColor.w;
    if (!(distance < range) || !(distance > 0.0f)) return 0.0f;
    if (!(glm::dot(sample.normal, -toReceiver) > 0.0f)) return 0.0f;  // faces away: BRDF zero
    glm::vec3 axis;
    if (view.isPoint) {
        if (gpu::cubeFaceOfDirection(toReceiver) != view.face) return 0.0f;
        axis = gpu::cubeFaceAxis(view.face);
    } else {
        axis = glm::vec3(light.directionAngleScale);
        if (!(glm::dot(axis, toReceiver / distance) > light.angleOffsetShadow.z)) return 0.0f;  // outside the cone
        const glm::vec4 clip = view.gpu.viewProjection * glm::vec4(sample.position, 1.0f);
        if (!(clip.w > 0.0f) || std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w) return 0.0f;
    }
    const float linearDepth = glm::dot(toReceiver, axis);
    if (!(linearDepth > 0.0f)) return 0.0f;
    return gpu::resolutionForOneTexelPerPixel(linearDepth, view.tanSpan, sample.pixelWorldSize);
}

namespace {

// The sun's cascades: each sample that faces the sun falls in the first cascade whose sphere holds
// it (cascadeOf over the culling spheres), which must give it a texel no wider than its pixel. An
// orthographic cascade's texel is its width / resolution at every depth: the same formula as a
// view of that span at unit depth.
void cascadeDemand(const ShadowPlan& plan, const VisibleReceivers& receivers, std::vector<float>& demand) {
    const CascadePlan& cascades = plan.cascades;
    std::array<glm::vec4, PUNCTUAL_MAX_CASCADES> spheres{};
    for (uint32_t i = 0; i < cascades.count; ++i) {
        spheres[i] = glm::vec4(glm::vec3(cascades.spheres[i]), cascades.spheres[i].w * cascades.spheres[i].w);
    }
    for (const ReceiverSample& sample : receivers.samples) {
        if (!(glm::dot(sample.normal, cascades.lightZ) > 0.0f)) continue;  // faces away: BRDF zero
        const uint32_t cascade = gpu::cascadeOf(sample.position, spheres[0], spheres[1], spheres[2], spheres[3], cascades.count);
        if (cascade >= cascades.count) continue;
        const uint32_t v = cascades.firstView + cascade;
        demand[v] = std::max(demand[v], gpu::resolutionForOneTexelPerPixel(1.0f, plan.views[v].tanSpan, sample.pixelWorldSize));
    }
}

}  // namespace

std::vector<float> shadowViewDemand(const ShadowPlan& plan, const FrameLights& lights,
                                    const VisibleReceivers& receivers) {
    std::vector<float> demand(plan.views.size(), 0.0f);
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        const ShadowView& view = plan.views[v];
        if (view.isCascade) {
            if (view.face == 0) cascadeDemand(plan, receivers, demand);
            continue;
        }
        const gpu::GpuPunctualLight& light = lights.packed[view.packedLight];
        if (!view.isPoint) {
            for (const ReceiverSample& sample : receivers.samples) {
                demand[v] = std::max(demand[v], resolutionNeededAt(plan, v, light, sample));
            }
        } else if (view.face == 0) {
            // A point light's six faces follow each other from face 0: each sample falls on one of
            // them, so only that face is asked.
            const glm::vec3 lightPosition(light.positionInvRangeSq);
            for (const ReceiverSample& sample : receivers.samples) {
                const uint32_t face = v + gpu::cubeFaceOfDirection(sample.position - lightPosition);
                demand[face] = std::max(demand[face], resolutionNeededAt(plan, face, light, sample));
            }
        }
    }
    return demand;
}

uint32_t shadowTierFor(float demand, uint32_t minTier, uint32_t maxTier) {
    if (!(demand > 0.0f)) return 0;
    // Nearest power of two in log scale: 2^round(log2 demand). Compared through the geometric
    // midpoints 2^(k + 1/2) so that no log2 rounding decides a boundary.
    uint32_t tier = minTier;
    while (tier < maxTier && demand > float(tier) * 1.41421356f) tier *= 2;
    return tier;
}

uint32_t shadowTierWithHysteresis(float demand, uint32_t previousTier, float octaves, uint32_t minTier, uint32_t maxTier) {
    const uint32_t nearest = shadowTierFor(demand, minTier, maxTier);
    if (nearest == 0 || previousTier == 0 || !(octaves > 0.0f) || previousTier < minTier || previousTier > maxTier) {
        return nearest;
    }
    // Up at once (a view never gets coarser than its nearest tier: that would trade accuracy for
    // stability); down only once the demand falls below previous / 2^(1/2 + h).
    if (nearest >= previousTier) return nearest;
    return demand >= float(previousTier) / std::exp2(0.5f + octaves) ? previousTier : nearest;
}
}  // namespace punctual
