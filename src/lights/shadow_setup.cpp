#include "lights/shadow_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "lights/caster_distance.h"
#include "shadows.h"

namespace punctual {
namespace {

// Spots wider than this are shadowed with a frustum of this half-angle: a perspective frustum
// cannot reach 90 degrees (tan -> infinity) and texels stretch without bound on the way. The
// rim between 80 and 90 degrees then stays unshadowed (README, "Shadows").
constexpr float kMaxSpotShadowHalfAngle = 1.3962634f;  // 80 degrees

// True when the box may meet the frustum (each plane tested against the box corner furthest
// along its normal).
bool boxMeetsFrustum(const Frustum& frustum, const Bounds& box) {
    for (const glm::vec4& plane : frustum.planes) {
        const glm::vec3 n(plane);
        const glm::vec3 corner(n.x >= 0.0f ? box.max.x : box.min.x, n.y >= 0.0f ? box.max.y : box.min.y,
                               n.z >= 0.0f ? box.max.z : box.min.z);
        if (glm::dot(n, corner) + plane.w < 0.0f) return false;
    }
    return true;
}

// The smallest and largest depth along `axis` (from `position`) of the box's corners. The near
// and far planes are planes across the view's axis, so the depths along that axis, not the
// distances, decide what they would clip: a caster off the axis can be far from the light yet
// shallow along it (up to 1.56x at a cube-face corner, 5x at an 80-degree spot edge).
struct DepthSpan {
    float nearest = std::numeric_limits<float>::max();
    float farthest = -std::numeric_limits<float>::max();
    // The least depth at which any caster's surface can lie inside the view (see reachDepth):
    // the near plane may come up to it and clip nothing.
    float nearestReach = std::numeric_limits<float>::max();

    void extend(const DepthSpan& other) {
        nearest = std::min(nearest, other.nearest);
        farthest = std::max(farthest, other.farthest);
        nearestReach = std::min(nearestReach, other.nearestReach);
    }
};

// A lower bound of the depth of any surface point of a caster inside the view. Two bounds hold,
// so their larger one does:
// - its bounds' shallowest corner along the axis (depthSpanAlong);
// - its distance from the light, over sqrt(1 + 2 tan^2): inside a square frustum of half-angle
//   slope `tanHalf`, a point at depth z lies within z sqrt(1 + 2 tan^2) of the apex (its two side
//   offsets are at most z tan each). A floor under a point light straddles the light's plane, so
//   its corners give a depth <= 0, yet it is 2.5 m below the light: no part of it inside a side
//   face's frustum is shallower than 2.5 / sqrt(3) m.
float reachDepth(float shallowestCorner, float distance, float tanHalf) {
    return std::max(shallowestCorner, distance / std::sqrt(1.0f + 2.0f * tanHalf * tanHalf));
}

DepthSpan depthSpanAlong(const glm::vec3& position, const glm::vec3& axis, const Bounds& box) {
    DepthSpan span;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                          (corner & 4) ? box.max.z : box.min.z);
        const float depth = glm::dot(p - position, axis);
        span.nearest = std::min(span.nearest, depth);
        span.farthest = std::max(span.farthest, depth);
    }
    return span;
}

// Objects meeting the view of `viewProjection` (only its side planes count) between the light and
// the range along `axis`, and the depth span along the axis of their bounds (see
// depthSpanAlong). They are the view's casters and its receivers both. The matrix's near and far
// planes are replaced by the plane through the light across its axis and the plane at the range:
// a near plane at any fixed share of the range would miss the casters in front of it, and glTF
// allows any range (1e6 m would put a 1/1000 one at 1 km).
std::vector<uint32_t> findCasters(const Scene& scene, const glm::mat4& viewProjection, const glm::vec3& position,
                                  const glm::vec3& axis, float range, float tanHalf, DepthSpan& span) {
    Frustum frustum = extractFrustum(viewProjection);
    frustum.planes[4] = glm::vec4(axis, -glm::dot(axis, position));           // depth along the axis >= 0
    frustum.planes[5] = glm::vec4(-axis, glm::dot(axis, position) + range);   // depth along the axis <= range
    std::vector<uint32_t> casters;
    span = DepthSpan{};
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        if (!boxMeetsFrustum(frustum, scene.objects[i].worldBounds)) continue;
        casters.push_back(i);
        DepthSpan object = depthSpanAlong(position, axis, scene.objects[i].worldBounds);
        object.nearestReach = reachDepth(object.nearest, casterDistance(scene, i, position), tanHalf);
        span.extend(object);
    }
    return casters;
}

// The far plane from the objects in the view: the farthest depth any of them reaches along the
// axis, and never beyond the range (the light reaches nothing further). Every receiver the light
// reaches is in one of those objects, so lies in front of it; the forward shader clamps the
// reference depth at 1, so a receiver pushed a little beyond it by the bias compares as at the
// far plane. Fitting far to the geometry rather than to the range keeps the depth mapping, and
// its precision, the same whatever the range: a range of 1e6 m over a 20 m room maps depth
// exactly as a range of 20 m does.
float farPlaneFor(const DepthSpan& span, float range) {
    // 1% past the deepest corner: a caster there is never clipped by the rounding of its depth.
    return span.farthest > 0.0f ? std::min(span.farthest * 1.01f, range) : range;
}

// Near plane from the casters: 90% of the least depth any caster's surface reaches inside the view
// (DepthSpan::nearestReach), so no caster is clipped, however far the far plane is. It is not tied
// to the far plane: a wall 3 km away in a light's reach once pushed a near plane at far / 1000 to
// 3 m and clipped every caster nearer than that (issue 30).
//
// What that costs in precision, and why it is the right trade: a perspective depth d = A + B / z
// maps view depth z to d with dd/dz = n f / ((f - n) z^2) ~ n / z^2, so one step q of the depth
// format (2^-16 for D16; 2^-24 near 1 for D32's float, shadowDepthQuantum says 2^-20 to be safe)
// spans dz = q z^2 / n at depth z. The bias at a receiver is at least one texel's world size,
// 2 z tan / resolution (applyShadowBias), so the steps stay inside it up to z = 2 n tan / (q res):
// with n = 1 m, a 1024 map and D16, 128 m; with D32, 2 km. Receivers deeper than that lose
// precision (acne or leaks within dz of them), casters nearer than n would vanish entirely; the
// first is a graceful loss far from the light, the second was the bug. The far plane stays
// fitted to the deepest object in reach (farPlaneFor).
//
// Never beyond half the far plane (a degenerate range), never below far / 10^6 (a caster touching
// the light: a surface through its centre would otherwise ask for a zero near plane; the old far
// / 1000 floor remains for a caster whose surface passes through the light itself).
float nearPlaneFor(float nearestReach, float farPlane) {
    if (!(nearestReach > 0.0f)) return farPlane * 1e-3f;
    return std::clamp(nearestReach * 0.9f, farPlane * 1e-6f, farPlane * 0.5f);
}

glm::mat4 spotViewProjection(const glm::vec3& position, const glm::vec3& direction, float halfAngle, float nearPlane,
                             float farPlane) {
    const glm::vec3 up = std::abs(direction.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::mat4 view = glm::lookAtRH(position, position + direction, up);
    return glm::perspectiveRH_ZO(2.0f * halfAngle, 1.0f, nearPlane, farPlane) * view;
}

}  // namespace

float shadowResolutionRead(const ShadowPlan& plan, uint32_t viewIndex, float linearDepth, const glm::vec3& position) {
    const ShadowView& view = plan.views[viewIndex];
    const VirtualPageReads& reads = plan.virtualReads;
    if (!reads.enabled || view.isCascade || view.resolution == 0) return float(view.resolution);
    const float pixel = gpu::screenPixelWorldSize(glm::dot(position - reads.eye, reads.forward), reads.pixelSpan);
    const float needed = gpu::resolutionForOneTexelPerPixel(linearDepth, view.tanSpan, pixel) * reads.texelsPerPixel;
    // As the forward shader's virtualReadLevel (shadow_pages.glsl): the nearest level, or one finer
    // where hysteresis may hold it and the previous frame marked that level's page here.
    const uint32_t level = gpu::virtualShadowLevel(needed, PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_LEVELS);
    const uint32_t nearest = gpu::virtualShadowCoarsened(level, view.coarserLevels);
    const uint32_t previous = reads.previousFirstWord.empty() ? PUNCTUAL_NO_SHADOW_PAGE : reads.previousFirstWord[viewIndex];
    if (previous != PUNCTUAL_NO_SHADOW_PAGE && gpu::virtualShadowMayKeepFiner(needed, level, reads.keep)) {
        const glm::vec4 clip = view.gpu.viewProjection * glm::vec4(position, 1.0f);
        const uint32_t finer = gpu::virtualShadowCoarsened(level - 1, view.coarserLevels);
        if (clip.w > 0.0f && finer != nearest) {
            const glm::uvec2 page = gpu::virtualShadowPage(glm::vec2(clip) / clip.w * 0.5f + 0.5f, finer,
                                                           PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_PAGE);
            const uint32_t index =
                gpu::virtualShadowPageIndex(page, finer, PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_PAGE);
            if ((reads.previousMarks.at(previous + index / 32) >> (index % 32)) & 1u) {
                return float(PUNCTUAL_VIRTUAL_SHADOW_SIZE >> finer);
            }
        }
    }
    return float(PUNCTUAL_VIRTUAL_SHADOW_SIZE >> nearest);
}

float ShadowSettings::penumbraTexels(uint32_t viewResolution) const {
    const ShadowFilterInfo* info = findVariant(kShadowFilters, filter);
    if (!info) info = &kShadowFilters[0];
    return info->reachTexels(diskRadius * float(viewResolution));
}

float ShadowSettings::biasPenumbraTexels(uint32_t viewResolution, bool onAtlas) const {
    const ShadowFilterInfo* info = findVariant(kShadowFilters, filter);
    const bool footprintFilter = info && info->footprint() > 0;
    return receiverPlane && onAtlas && footprintFilter ? 0.0f : penumbraTexels(viewResolution);
}

float shadowDepthQuantum(ShadowFormat format) {
    return format == ShadowFormat::D16 ? 2.0f / 65535.0f : 1.0f / float(1u << 20);
}

const char* shadowFormatName(ShadowFormat format) { return format == ShadowFormat::D16 ? "d16" : "d32"; }

std::string shadowResolutionName(const ShadowSettings& settings) {
    for (const ShadowResolutionModeInfo& mode : kShadowResolutionModes) {
        if (mode.value == settings.resolution) return mode.name;
    }
    return std::to_string(settings.resolution);
}

uint32_t ShadowSettings::filterTaps() const {
    const ShadowFilterInfo* info = findVariant(kShadowFilters, filter);
    if (!info) info = &kShadowFilters[0];
    return info->taps(diskSamples);
}

void validateShadowSettings(const ShadowSettings& settings) {
    validateCascadeSettings(settings.cascades);
    if (!settings.autoResolution() &&
        (settings.resolution < 16 || settings.resolution > 8192 || (settings.resolution & (settings.resolution - 1)) != 0)) {
        throw Error("--shadow-res", "must be auto, virtual or a power of two from 16 to 8192, got " + std::to_string(settings.resolution));
    }
    if (settings.autoResolution() && settings.pointLayout == PointShadowLayout::Cube) {
        throw Error("--point-shadow-layout cube",
                    "a cube map's faces share one resolution: use it with a fixed --shadow-res N, or use slices");
    }
    if (!std::isfinite(settings.texelsPerPixel) || settings.texelsPerPixel < 0.25f || settings.texelsPerPixel > 16.0f) {
        throw Error("--shadow-texels-per-pixel", "must be from 0.25 to 16");
    }
    if (settings.budgetBytes < (1ull << 20) || settings.budgetBytes > (64ull << 30)) {
        throw Error("--shadow-budget", "must be from 1 to 65536 MiB");
    }
    if (settings.maxShadowedSpots > PUNCTUAL_MAX_SHADOWED_SPOT_LIGHTS ||
        settings.maxShadowedPoints > PUNCTUAL_MAX_SHADOWED_POINT_LIGHTS) {
        throw Error("--shadowed", "at most " + std::to_string(PUNCTUAL_MAX_SHADOWED_SPOT_LIGHTS) + " spots and " +
                                      std::to_string(PUNCTUAL_MAX_SHADOWED_POINT_LIGHTS) + " points can be shadowed");
    }
    if (settings.diskSamples < 1 || settings.diskSamples > 64) {
        throw Error("--shadow-samples", "must be from 1 to 64, got " + std::to_string(settings.diskSamples));
    }
    for (int i = 0; i < 4; ++i) {
        if (!std::isfinite(settings.bias[i]) || settings.bias[i] < 0.0f || settings.bias[i] > 100.0f) {
            throw Error("--shadow-bias", "each of the four biases must be from 0 to 100");
        }
    }
    if (!std::isfinite(settings.diskRadius) || settings.diskRadius < 0.0f || settings.diskRadius > 0.1f) {
        throw Error("--shadow-penumbra", "must be from 0 to 0.1 (shadow-map UV units)");
    }
    if (!std::isfinite(settings.spotNearFraction) || settings.spotNearFraction < 0.0f || settings.spotNearFraction >= 1.0f) {
        throw Error("shadows", "the spot near-plane fraction must be from 0 to below 1");
    }
    if (!std::isfinite(settings.strength) || settings.strength < 0.0f || settings.strength > 1.0f) {
        throw Error("--shadow-strength", "must be from 0 to 1");
    }
}

glm::mat4 cubeFaceViewProjection(const glm::vec3& position, uint32_t face, float nearPlane, float farPlane,
                                 float scale) {
    const glm::vec3 u = gpu::cubeFaceU(face) / scale;
    const glm::vec3 v = gpu::cubeFaceV(face) / scale;
    const glm::vec3 axis = gpu::cubeFaceAxis(face);
    // depth = A + B / ma with A = f / (f - n), B = -f n / (f - n): clip.z = A ma + B, clip.w = ma.
    const float a = farPlane / (farPlane - nearPlane);
    const float b = -farPlane * nearPlane / (farPlane - nearPlane);
    glm::mat4 m(0.0f);  // column-major: m[column][row]
    for (int c = 0; c < 3; ++c) {
        m[c][0] = u[c];
        m[c][1] = v[c];
        m[c][2] = a * axis[c];
        m[c][3] = axis[c];
    }
    m[3][0] = -glm::dot(u, position);
    m[3][1] = -glm::dot(v, position);
    m[3][2] = -a * glm::dot(axis, position) + b;
    m[3][3] = -glm::dot(axis, position);
    return m;
}

namespace {

// Spot `index`'s view (packed light `index`), appended to the plan.
void planSpotView(const Scene& scene, FrameLights& lights, uint32_t index, const ShadowSettings& settings,
                  ShadowPlan& plan) {
    const Light& source = scene.lights[lights.sceneLightIndex[index]];
    gpu::GpuPunctualLight& light = lights.packed[index];
    const glm::vec3 position(light.positionInvRangeSq);
    const glm::vec3 direction(light.directionAngleScale);
    const float range = light.radiantColor.w;
    const float halfAngle = std::min(std::acos(std::clamp(light.angleOffsetShadow.z, -1.0f, 1.0f)), kMaxSpotShadowHalfAngle);
    // Casters are found between the light's plane and the range (see findCasters), then the
    // near and far planes move in to just short of the shallowest one and just past the
    // deepest object along the axis.
    DepthSpan span;
    ShadowView view;
    // The side planes do not depend on the near and far planes given here (see findCasters).
    view.casters = findCasters(scene, spotViewProjection(position, direction, halfAngle, 1.0f, 2.0f), position,
                               direction, range, std::tan(halfAngle), span);
    // The failure study's fixed near plane (a share of the range) keeps the range as far.
    const bool fixedNear = settings.spotNearFraction > 0.0f;
    view.farPlane = fixedNear ? range : farPlaneFor(span, range);
    view.nearPlane = fixedNear ? range * settings.spotNearFraction : nearPlaneFor(span.nearestReach, view.farPlane);
    view.gpu.viewProjection = spotViewProjection(position, direction, halfAngle, view.nearPlane, view.farPlane);
    view.tanSpan = 2.0f * std::tan(halfAngle);
    view.packedLight = index;
    plan.shadowedSpots++;
    light.angleOffsetShadow.y = float(plan.views.size());
    light.angleOffsetShadow.w = settings.strength * source.shadowStrength;
    plan.views.push_back(std::move(view));
}

// Point `index`'s six faces (packed light `index`), appended to the plan.
void planPointViews(const Scene& scene, FrameLights& lights, uint32_t index, const ShadowSettings& settings,
                    ShadowPlan& plan) {
    const Light& source = scene.lights[lights.sceneLightIndex[index]];
    gpu::GpuPunctualLight& light = lights.packed[index];
    const glm::vec3 position(light.positionInvRangeSq);
    const float range = light.radiantColor.w;
    const uint32_t cube = plan.shadowedPoints++;
    light.angleOffsetShadow.y = float(plan.views.size());
    light.angleOffsetShadow.w = settings.strength * source.shadowStrength;
    // One near and one far plane for the whole light: the cube layout's hardware filters across
    // face edges (seamless cube sampling), so every face must map depth the same way, and the
    // slices keep the same planes so that the two layouts differ only in their storage.
    std::vector<ShadowView> faces(6);
    DepthSpan cubeSpan;
    for (uint32_t face = 0; face < 6; ++face) {
        DepthSpan span;
        // Slices: a guard band of up to twice the face (at the smallest tier and the widest
        // filter the widening stays below 1.6) bounds every face's frustum, whatever its
        // resolution turns out to be.
        const float widest = settings.pointLayout == PointShadowLayout::Slices ? 2.0f : 1.0f;
        faces[face].casters = findCasters(scene, cubeFaceViewProjection(position, face, 1.0f, 2.0f, widest), position,
                                          gpu::cubeFaceAxis(face), range, widest, span);
        cubeSpan.extend(span);
    }
    const float farPlane = farPlaneFor(cubeSpan, range);
    const float nearPlane = nearPlaneFor(cubeSpan.nearestReach, farPlane);
    for (uint32_t face = 0; face < 6; ++face) {
        ShadowView& view = faces[face];
        view.farPlane = farPlane;
        view.nearPlane = nearPlane;
        view.tanSpan = 2.0f;  // widened by the slices' guard band once the resolution is known
        view.gpu.viewProjection = cubeFaceViewProjection(position, face, nearPlane, farPlane);
        view.cubeLayer = cube * 6 + face;
        view.packedLight = index;
        view.face = face;
        view.isPoint = true;
        plan.views.push_back(std::move(view));
    }
}

}  // namespace

ShadowPlan planShadows(const Scene& scene, FrameLights& lights, const glm::vec3& cameraPosition,
                       const ShadowSettings& settings) {
    ShadowPlan plan;
    plan.transparentShadows = settings.transparent;
    for (gpu::GpuPunctualLight& light : lights.packed) {
        light.angleOffsetShadow.y = -1.0f;
        light.angleOffsetShadow.w = 0.0f;
    }
    if (!settings.enabled) return plan;

    // Rank the shadow casters of each type; the most important keep their shadows.
    auto rankedCasters = [&](uint32_t first, uint32_t count, uint32_t cap) {
        std::vector<uint32_t> order;
        for (uint32_t i = first; i < first + count; ++i) {
            if (scene.lights[lights.sceneLightIndex[i]].castsShadow) order.push_back(i);
        }
        std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
            return lightImportance(scene.lights[lights.sceneLightIndex[a]], cameraPosition) >
                   lightImportance(scene.lights[lights.sceneLightIndex[b]], cameraPosition);
        });
        if (order.size() > cap) {
            plan.droppedByCap += uint32_t(order.size() - cap);
            order.resize(cap);
        }
        std::sort(order.begin(), order.end());  // packed order: stable slot assignment
        return order;
    };
    const std::vector<uint32_t> spots = rankedCasters(
        0, lights.spotCount, std::min<uint32_t>(settings.maxShadowedSpots, PUNCTUAL_MAX_SHADOWED_SPOT_LIGHTS));
    const std::vector<uint32_t> points = rankedCasters(
        lights.spotCount, lights.pointCount, std::min<uint32_t>(settings.maxShadowedPoints, PUNCTUAL_MAX_SHADOWED_POINT_LIGHTS));

    for (uint32_t index : spots) planSpotView(scene, lights, index, settings, plan);
    for (uint32_t index : points) planPointViews(scene, lights, index, settings, plan);
    return plan;
}

}  // namespace punctual
