#include "reference/shadow_validation.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <tbb/parallel_for.h>

#include "core/check.h"
#include "lights/cascade_setup.h"
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
// frustum, or the point face the position falls on (linear depth along the view's axis), at the
// resolution it reads there (shadowResolutionRead: the view's, or its virtual level's); 0 for a
// view without storage (always lit: no edge to be near).
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
    const float resolution = shadowResolutionRead(plan, viewIndex, depth, position);
    return resolution > 0.0f ? gpu::shadowTexelWorldSize(depth, view.tanSpan, resolution) : 0.0f;
}

}  // namespace

EdgeBand EdgeBand::ofScreenPixels(float pixels, const Camera& camera, uint32_t height) {
    EdgeBand band;
    band.screenPixels = pixels;
    band.cameraView = camera.view;
    band.pixelSpanAtUnitDepth = 2.0f * std::tan(camera.yfov * 0.5f) / float(height);
    return band;
}

namespace {

// What comparing one light needs: its factor at each pixel, the direction towards it from a point,
// Embree's visibility of it from a point, and the shadow map's texel size at a point (the default
// edge band's width).
struct ComparedLight {
    std::function<uint8_t(size_t pixel)> factor;
    std::function<glm::vec3(const glm::vec3& point)> toLight;  // unnormalised is fine
    std::function<bool(const glm::vec3& point, const glm::vec3& normal)> rayLit;
    std::function<float(const glm::vec3& point)> texelSize;
};

// Compares one light at every pixel (in parallel, deterministic): verdicts, the edge band, counts.
void compareLight(const ShadowFactorImage& factors, const ComparedLight& compared, const EdgeBand& band,
                  std::vector<PixelVerdict>& verdicts, std::vector<uint8_t>& inBandPixels, ShadowCounts& counts) {
    const size_t pixels = size_t(factors.width) * factors.height;
    verdicts.assign(pixels, PixelVerdict::NotCompared);
    inBandPixels.assign(pixels, 0);
    tbb::parallel_for(size_t(0), size_t(factors.height), [&](size_t y) {
        for (size_t x = 0; x < factors.width; ++x) {
            const size_t i = y * factors.width + x;
            const uint8_t factor = compared.factor(i);
            if (factor == PUNCTUAL_SHADOW_FACTOR_NOT_REACHED) continue;
            const glm::vec3 p = factors.positions[i];
            const glm::vec3 n = factors.normals[i];
            // A surface facing away from the light receives none of it (N.L <= 0 shades to
            // zero), whatever the shadow says: the light does not reach it.
            const glm::vec3 towards = compared.toLight(p);
            if (glm::dot(n, towards) <= 0.0f) continue;
            const bool rayLit = compared.rayLit(p, n);
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
                const glm::vec3 toLight = glm::normalize(towards);
                axisA = glm::cross(n, toLight);
                if (glm::dot(axisA, axisA) < 1e-8f) axisA = glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
                axisA = glm::normalize(axisA);
                axisB = glm::normalize(glm::cross(n, axisA));
                const float texel = compared.texelSize(p);
                reachA = texel;
                reachB = texel / std::max(glm::dot(n, toLight), 0.2f);
            }
            bool inBand = false;
            for (const glm::vec3 offset : {axisA * reachA, -axisA * reachA, axisB * reachB, -axisB * reachB}) {
                if (glm::dot(offset, offset) == 0.0f) continue;
                if (compared.rayLit(p + offset, n) != rayLit) {
                    inBand = true;
                    break;
                }
            }
            inBandPixels[i] = inBand ? 1 : 0;
            verdicts[i] = gpuLit == rayLit ? (rayLit ? PixelVerdict::AgreeLit : PixelVerdict::AgreeShadow)
                                           : (gpuLit ? PixelVerdict::FalseLit : PixelVerdict::FalseShadow);
        }
    });
    counts = ShadowCounts{};
    for (size_t i = 0; i < pixels; ++i) counts.count(verdicts[i], inBandPixels[i] != 0);
}

}  // namespace

void ShadowCounts::count(PixelVerdict verdict, bool inBand) {
    if (verdict == PixelVerdict::NotCompared) return;
    ++compared;
    const bool isFalseShadow = verdict == PixelVerdict::FalseShadow;
    const bool isFalseLit = verdict == PixelVerdict::FalseLit;
    falseShadow += isFalseShadow;
    falseLit += isFalseLit;
    if (inBand) {
        ++edgeBand;
    } else {
        ++comparedOutsideBand;
        falseShadowOutsideBand += isFalseShadow;
        falseLitOutsideBand += isFalseLit;
    }
}

ShadowValidation validateShadows(const EmbreeScene& embree, const ShadowFactorImage& factors,
                                 const FrameLights& lights, const ShadowPlan& plan, const EdgeBand& band) {
    ShadowValidation result;
    result.width = factors.width;
    result.height = factors.height;

    // Each shadowed light, by the slot the GPU writes its factors to (gpu::shadowSlot).
    for (uint32_t viewIndex = 0; viewIndex < plan.views.size(); ++viewIndex) {
        const ShadowView& view = plan.views[viewIndex];
        if (view.isCascade || (view.isPoint && view.face != 0)) continue;
        LightShadowValidation light;
        light.slot = gpu::shadowSlot(viewIndex, plan.shadowedSpots);
        PUNCTUAL_CHECK(light.slot == result.lights.size(), "shadow slots out of plan order");
        light.packedLight = view.packedLight;
        light.sceneLight = lights.sceneLightIndex[view.packedLight];
        light.isPoint = view.isPoint;
        result.lights.push_back(std::move(light));
    }

    for (LightShadowValidation& validation : result.lights) {
        const gpu::GpuPunctualLight& light = lights.packed[validation.packedLight];
        const uint32_t firstView = uint32_t(light.angleOffsetShadow.y);
        const glm::vec3 lightPosition(light.positionInvRangeSq);
        ComparedLight compared;
        compared.factor = [&](size_t i) { return factors.factors[i * factors.slots + validation.slot]; };
        compared.toLight = [&](const glm::vec3& p) { return lightPosition - p; };
        compared.rayLit = [&](const glm::vec3& p, const glm::vec3& n) {
            return visibility(embree, p, n, light, plan.transparentShadows) > 0.5f;
        };
        compared.texelSize = [&](const glm::vec3& p) { return texelWorldSize(light, plan, firstView, p); };
        compareLight(factors, compared, band, validation.verdicts, validation.inBand, validation.counts);
        (validation.isPoint ? result.points : result.spots).add(validation.counts);
        result.overall.add(validation.counts);
    }

    if (plan.cascades.count > 0 && !factors.sunFactors.empty()) {
        SunShadowValidation& sun = result.sun.emplace();
        sun.sceneLight = plan.cascades.sceneLight;
        const gpu::GpuDirectionalLight& light = lights.sun;
        ComparedLight compared;
        compared.factor = [&](size_t i) { return factors.sunFactors[i]; };
        compared.toLight = [&](const glm::vec3&) { return glm::vec3(light.directionToLight); };
        compared.rayLit = [&](const glm::vec3& p, const glm::vec3& n) {
            return visibility(embree, p, n, light, plan.transparentShadows) > 0.5f;
        };
        compared.texelSize = [&](const glm::vec3& p) {
            const uint32_t cascade = cascadeAt(plan.cascades, p);
            return cascade < plan.cascades.count ? cascadeTexelSize(plan, cascade) : 0.0f;
        };
        compareLight(factors, compared, band, sun.verdicts, sun.inBand, sun.counts);
        // Per cascade, by the cascade the GPU read (dither may pick the next one), and the split
        // bands: pixels within one texel of the cascade's sphere (where the selection switches).
        sun.cascades.resize(plan.cascades.count);
        for (size_t i = 0; i < sun.verdicts.size(); ++i) {
            const uint8_t cascade = factors.sunCascades[i];
            if (cascade == 0 || cascade > plan.cascades.count) continue;
            const bool inBand = sun.inBand[i] != 0;
            sun.cascades[cascade - 1].count(sun.verdicts[i], inBand);
            if (nearCascadeSplit(plan, factors.positions[i])) sun.splitBand.count(sun.verdicts[i], inBand);
        }
        result.overall.add(sun.counts);
    }
    return result;
}

}  // namespace punctual::reference
