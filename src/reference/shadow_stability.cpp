#include "reference/shadow_stability.h"

#include <cmath>

#include "core/check.h"
#include "shadows.h"

namespace punctual::reference {
namespace {

bool gpuLit(PixelVerdict v) { return v == PixelVerdict::AgreeLit || v == PixelVerdict::FalseLit; }
bool rayLit(PixelVerdict v) { return v == PixelVerdict::AgreeLit || v == PixelVerdict::FalseShadow; }

bool sameLight(const Light& a, const Light& b) {
    return a.type == b.type && a.position == b.position && a.direction == b.direction && a.range == b.range &&
           a.innerConeAngle == b.innerConeAngle && a.outerConeAngle == b.outerConeAngle && a.castsShadow == b.castsShadow;
}

// The pixel of `frame` that sees `p`, or -1 outside its view.
int64_t pixelOf(const StabilityFrame& frame, const glm::vec3& p) {
    const glm::vec4 clip = frame.viewProjection * glm::vec4(p, 1.0f);
    if (!(clip.w > 0.0f)) return -1;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    // Vulkan clip space, y down (Camera::projection): pixel (x, y) covers ndc x in
    // [2x / w - 1, 2(x + 1) / w - 1], y likewise with rows top to bottom.
    const float x = std::floor((ndc.x * 0.5f + 0.5f) * float(frame.width));
    const float y = std::floor((ndc.y * 0.5f + 0.5f) * float(frame.height));
    if (!(x >= 0.0f && y >= 0.0f && x < float(frame.width) && y < float(frame.height))) return -1;
    return int64_t(y) * frame.width + int64_t(x);
}

// Whether `frame`'s pixel j has the GPU state and the truth of every covered neighbour (3 x 3)
// that the light reaches: a point inside a region, not on the edge of a shadow or of an error,
// where the half-pixel offset of a reprojected sample could cross the edge with no change at all.
bool uniformAround(const StabilityFrame& frame, const std::vector<PixelVerdict>& verdicts, size_t j) {
    const int64_t x = int64_t(j % frame.width);
    const int64_t y = int64_t(j / frame.width);
    const PixelVerdict centre = verdicts[j];
    for (int64_t dy = -1; dy <= 1; ++dy) {
        for (int64_t dx = -1; dx <= 1; ++dx) {
            if (x + dx < 0 || y + dy < 0 || x + dx >= int64_t(frame.width) || y + dy >= int64_t(frame.height)) continue;
            const size_t k = size_t(y + dy) * frame.width + size_t(x + dx);
            if (!frame.covered[k] || verdicts[k] == PixelVerdict::NotCompared) continue;
            if (gpuLit(verdicts[k]) != gpuLit(centre) || rayLit(verdicts[k]) != rayLit(centre)) return false;
        }
    }
    return true;
}

}  // namespace

StabilityFrame stabilityFrame(const Scene& scene, const ShadowFactorImage& factors, const ShadowValidation& validation) {
    StabilityFrame frame;
    frame.width = factors.width;
    frame.height = factors.height;
    frame.view = scene.camera.view;
    frame.viewProjection = scene.camera.projection(float(factors.width) / float(factors.height)) * scene.camera.view;
    frame.pixelSpanAtUnitDepth = 2.0f * std::tan(scene.camera.yfov * 0.5f) / float(factors.height);
    frame.positions = factors.positions;
    frame.covered = factors.covered;
    for (const LightShadowValidation& light : validation.lights) frame.verdicts[light.sceneLight] = light.verdicts;
    if (validation.sun) frame.verdicts[validation.sun->sceneLight] = validation.sun->verdicts;
    frame.lights = scene.lights;
    return frame;
}

void recordMapResolutions(StabilityFrame& frame, const ShadowPlan& plan, const std::vector<uint32_t>& sceneLightIndex,
                          std::optional<uint32_t> sunLight) {
    frame.mapResolutions.clear();
    for (const ShadowView& view : plan.views) {
        if (view.isCascade && !sunLight) continue;
        const uint32_t light = view.isCascade ? *sunLight : sceneLightIndex.at(view.packedLight);
        frame.mapResolutions[light].push_back(view.resolution);
    }
}

ShadowFlips countShadowFlips(const StabilityFrame& previous, const StabilityFrame& current) {
    PUNCTUAL_CHECK(previous.width == current.width && previous.height == current.height, "frames of different sizes");
    // The lights present in both frames that did not move.
    struct Compared {
        const std::vector<PixelVerdict>* before;
        const std::vector<PixelVerdict>* now;
        bool resized;  // its maps' resolutions differ between the frames
    };
    std::vector<Compared> lights;
    for (const auto& [index, verdicts] : current.verdicts) {
        const auto before = previous.verdicts.find(index);
        if (before == previous.verdicts.end() || index >= current.lights.size() || index >= previous.lights.size()) continue;
        if (!sameLight(previous.lights[index], current.lights[index])) continue;
        const auto sizesBefore = previous.mapResolutions.find(index);
        const auto sizesNow = current.mapResolutions.find(index);
        const bool resized = sizesBefore != previous.mapResolutions.end() && sizesNow != current.mapResolutions.end() &&
                             sizesBefore->second != sizesNow->second;
        lights.push_back({&before->second, &verdicts, resized});
    }
    ShadowFlips flips;
    const size_t pixels = size_t(current.width) * current.height;
    for (size_t i = 0; i < pixels; ++i) {
        if (!current.covered[i]) continue;
        const glm::vec3 p = current.positions[i];
        const int64_t j = pixelOf(previous, p);
        if (j < 0 || !previous.covered[size_t(j)]) continue;
        // The same static point: within two pixels' world size at its depth (a reprojected pixel
        // centre lands up to a pixel's diagonal from the previous frame's centre).
        const float depth = -(current.view * glm::vec4(p, 1.0f)).z;
        const float tolerance = 2.0f * gpu::screenPixelWorldSize(depth, current.pixelSpanAtUnitDepth);
        if (!(glm::length(previous.positions[size_t(j)] - p) <= tolerance)) continue;
        for (const Compared& light : lights) {
            const PixelVerdict a = (*light.before)[size_t(j)];
            const PixelVerdict b = (*light.now)[i];
            if (a == PixelVerdict::NotCompared || b == PixelVerdict::NotCompared || rayLit(a) != rayLit(b)) continue;
            if (!uniformAround(previous, *light.before, size_t(j))) continue;
            ++flips.compared;
            const bool flipped = gpuLit(a) != gpuLit(b);
            flips.flips += flipped;
            flips.flipsWhereMapsResized += flipped && light.resized;
        }
    }
    return flips;
}

}  // namespace punctual::reference
