#include "reference/shadow_validation.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "reference/reference_renderer.h"
#include "shadows.h"

namespace punctual::reference {

void ShadowCounts::add(const ShadowCounts& other) {
    compared += other.compared;
    falseShadow += other.falseShadow;
    falseLit += other.falseLit;
    edgeBand += other.edgeBand;
    comparedOutsideBand += other.comparedOutsideBand;
    falseShadowOutsideBand += other.falseShadowOutsideBand;
    falseLitOutsideBand += other.falseLitOutsideBand;
}

double ShadowCounts::misclassified() const {
    return compared > 0 ? double(falseShadow + falseLit) / double(compared) : 0.0;
}

double ShadowCounts::misclassifiedOutsideBand() const {
    return comparedOutsideBand > 0 ? double(falseShadowOutsideBand + falseLitOutsideBand) / double(comparedOutsideBand)
                                   : 0.0;
}

namespace {

// The world size of one shadow-map texel at `position` for the light's view there: the spot's
// frustum, or the point face the position falls on (linear depth along the view's axis), at that
// view's own resolution; 0 for a view without storage (always lit: no edge to be near).
float texelWorldSize(const gpu::GpuPunctualLight& light, const ShadowPlan& plan, uint32_t firstView,
                     const glm::vec3& position) {
    const glm::vec3 lightPosition(light.positionInvRangeSq);
    float depth = 0.0f;
    uint32_t viewIndex = firstView;
    if (light.angleOffsetShadow.z > -1.0f) {
        depth = std::abs(glm::dot(lightPosition - position, glm::vec3(light.directionAngleScale)));
    } else {
        const glm::vec3 direction = position - lightPosition;
        const uint32_t face = gpu::cubeFaceOfDirection(direction);
        depth = std::abs(glm::dot(direction, gpu::cubeFaceAxis(face)));
        viewIndex += face;
    }
    const ShadowView& view = plan.views[viewIndex];
    return view.resolution > 0 ? gpu::shadowTexelWorldSize(depth, view.tanSpan, float(view.resolution)) : 0.0f;
}

}  // namespace

EdgeBand EdgeBand::ofScreenPixels(float pixels, const Camera& camera, uint32_t height) {
    EdgeBand band;
    band.screenPixels = pixels;
    band.cameraView = camera.view;
    band.pixelSpanAtUnitDepth = 2.0f * std::tan(camera.yfov * 0.5f) / float(height);
    return band;
}

ShadowValidation validateShadows(const EmbreeScene& embree, const ShadowFactorImage& factors,
                                 const FrameLights& lights, const ShadowPlan& plan, const EdgeBand& band) {
    ShadowValidation result;
    result.width = factors.width;
    result.height = factors.height;
    const size_t pixels = size_t(factors.width) * factors.height;

    // The slot of each shadowed light, in the order the GPU numbers them.
    for (uint32_t viewIndex = 0; viewIndex < plan.views.size(); ++viewIndex) {
        const ShadowView& view = plan.views[viewIndex];
        if (view.isPoint && view.face != 0) continue;
        LightShadowValidation light;
        light.slot = uint32_t(result.lights.size());
        light.packedLight = view.packedLight;
        light.sceneLight = lights.sceneLightIndex[view.packedLight];
        light.isPoint = view.isPoint;
        light.verdicts.assign(pixels, PixelVerdict::NotCompared);
        light.inBand.assign(pixels, 0);
        result.lights.push_back(std::move(light));
    }

    for (LightShadowValidation& validation : result.lights) {
        const gpu::GpuPunctualLight& light = lights.packed[validation.packedLight];
        const uint32_t firstView = uint32_t(light.angleOffsetShadow.y);
        const glm::vec3 lightPosition(light.positionInvRangeSq);
        tbb::parallel_for(size_t(0), size_t(factors.height), [&](size_t y) {
            for (size_t x = 0; x < factors.width; ++x) {
                const size_t i = y * factors.width + x;
                const uint8_t factor = factors.factors[i * factors.slots + validation.slot];
                if (factor == PUNCTUAL_SHADOW_FACTOR_NOT_REACHED) continue;
                const glm::vec3 p = factors.positions[i];
                const glm::vec3 n = factors.normals[i];
                // A surface facing away from the light receives none of it (N.L <= 0 shades to
                // zero), whatever the shadow says: the light does not reach it.
                if (glm::dot(n, lightPosition - p) <= 0.0f) continue;
                const bool rayLit = visibility(embree, p, n, light) > 0.5f;
                const bool gpuLit = factor >= 127;  // factor x 254 >= 0.5

                // Edge band: four probes in the surface's plane, each its own shadow ray. One texel
                // away, across and along the light's direction (stretched by 1 / cos theta along
                // it, as a texel's footprint is); or band.screenPixels pixels away, across and along
                // the view's slant (stretched by 1 / cos of the view angle along it).
                glm::vec3 axisA;
                glm::vec3 axisB;
                float reachA = 0.0f;
                float reachB = 0.0f;
                if (band.screenPixels > 0.0f) {
                    const glm::vec3 viewPoint(band.cameraView * glm::vec4(p, 1.0f));
                    const glm::vec3 eye(glm::inverse(band.cameraView)[3]);
                    const float width = band.screenPixels * gpu::screenPixelWorldSize(-viewPoint.z, band.pixelSpanAtUnitDepth);
                    const glm::vec3 toEye = glm::normalize(eye - p);
                    axisA = toEye - n * glm::dot(n, toEye);
                    if (glm::dot(axisA, axisA) < 1e-8f) axisA = glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
                    axisA = glm::normalize(axisA);
                    axisB = glm::normalize(glm::cross(n, axisA));
                    reachA = width / std::max(std::abs(glm::dot(n, toEye)), 0.2f);
                    reachB = width;
                } else {
                    const glm::vec3 toLight = glm::normalize(lightPosition - p);
                    axisA = glm::cross(n, toLight);
                    if (glm::dot(axisA, axisA) < 1e-8f) axisA = glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
                    axisA = glm::normalize(axisA);
                    axisB = glm::normalize(glm::cross(n, axisA));
                    const float texel = texelWorldSize(light, plan, firstView, p);
                    reachA = texel;
                    reachB = texel / std::max(glm::dot(n, toLight), 0.2f);
                }
                bool inBand = false;
                for (const glm::vec3 offset : {axisA * reachA, -axisA * reachA, axisB * reachB, -axisB * reachB}) {
                    if (glm::dot(offset, offset) == 0.0f) continue;
                    if ((visibility(embree, p + offset, n, light) > 0.5f) != rayLit) {
                        inBand = true;
                        break;
                    }
                }
                validation.inBand[i] = inBand ? 1 : 0;
                validation.verdicts[i] = gpuLit == rayLit ? (rayLit ? PixelVerdict::AgreeLit : PixelVerdict::AgreeShadow)
                                                          : (gpuLit ? PixelVerdict::FalseLit : PixelVerdict::FalseShadow);
            }
        });
        ShadowCounts& counts = validation.counts;
        for (size_t i = 0; i < pixels; ++i) {
            const PixelVerdict verdict = validation.verdicts[i];
            if (verdict == PixelVerdict::NotCompared) continue;
            ++counts.compared;
            const bool falseShadow = verdict == PixelVerdict::FalseShadow;
            const bool falseLit = verdict == PixelVerdict::FalseLit;
            counts.falseShadow += falseShadow;
            counts.falseLit += falseLit;
            if (validation.inBand[i]) {
                ++counts.edgeBand;
            } else {
                ++counts.comparedOutsideBand;
                counts.falseShadowOutsideBand += falseShadow;
                counts.falseLitOutsideBand += falseLit;
            }
        }
        (validation.isPoint ? result.points : result.spots).add(counts);
        result.overall.add(counts);
    }
    return result;
}

}  // namespace punctual::reference
