#include "lights/per_object_lights.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "culling.h"
#include "shading.h"

namespace punctual {

namespace {

// Float-rounding slack of the reach test, relative to the scale of the numbers involved. The
// shader decides "lit" with float arithmetic (a few ulps, ~1e-7 relative), so an exact test could
// reject a light that the shader, rounding the other way, lets through by a hair. 1e-5 is 100x
// that, and costs nothing measurable in culling.
constexpr float kRelativeSlack = 1e-5f;
// The same slack on the cosine of the spot's outer angle: the cone is widened to
// cos(angle) >= cosOuter - kConeCosineSlack before testing.
constexpr float kConeCosineSlack = 1e-5f;
// The ranking's distance clamp: 1 cm, the same as distanceAttenuation's denominator clamp.
constexpr float kMinRankingDistanceSquared = 1e-4f;
// The angular factor given to a spot whose cone reaches the box although neither the box's
// closest point nor its centre is inside the cone.
constexpr float kGrazingSpotFactor = 0.05f;

// The geometry of a packed light, recovered from its fields (gpu_types.h):
//   position         = positionInvRangeSq.xyz
//   range            = 1 / sqrt(positionInvRangeSq.w). This is the range the shader really uses:
//                      distanceAttenuation is > 0 exactly when d^2 * invRangeSq < 1, i.e. d < range.
//                      (It equals radiantColor.w unless that is below the 1 cm packing clamp.)
//   spot or point    : directionAngleScale.w = k > 0 for spots, k = 0 for points.
//   cos outer angle  : packing stores k and offset = -cosOuter * k, so cosOuter = -offset / k.
//                      spotAttenuation = saturate(cos(angle) * k + offset)^2 is > 0 exactly when
//                      cos(angle) * k > -offset, i.e. cos(angle) > cosOuter (k > 0).
struct LightGeometry {
    glm::vec3 position{0.0f};
    float invRangeSquared = 0.0f;
    float range = 0.0f;
    bool isSpot = false;
    glm::vec3 axis{0.0f, 0.0f, -1.0f};  // unit direction the spot shines
    float angleScale = 0.0f;            // k
    float angleOffset = 1.0f;           // -cosOuter * k
    float cosOuter = -1.0f;             // as packed, clamped to [-1, 1]
};

LightGeometry unpack(const gpu::GpuPunctualLight& light) {
    LightGeometry geometry;
    geometry.position = glm::vec3(light.positionInvRangeSq);
    geometry.invRangeSquared = light.positionInvRangeSq.w;
    geometry.range = geometry.invRangeSquared > 0.0f ? 1.0f / std::sqrt(geometry.invRangeSquared)
                                                     : std::numeric_limits<float>::infinity();
    geometry.axis = glm::vec3(light.directionAngleScale);
    geometry.angleScale = light.directionAngleScale.w;
    geometry.angleOffset = light.angleOffsetShadow.x;
    geometry.isSpot = geometry.angleScale > 0.0f;
    if (geometry.isSpot) geometry.cosOuter = std::clamp(-geometry.angleOffset / geometry.angleScale, -1.0f, 1.0f);
    return geometry;
}

float squaredDistanceToBox(const glm::vec3& point, const Bounds& box) {
    const glm::vec3 offset = point - glm::clamp(point, box.min, box.max);  // closest point of the box
    return glm::dot(offset, offset);
}

// Bounding sphere of the spherical sector of apex P, unit axis D, half-angle theta (given by its
// cosine, theta <= 90 deg) and radius r: gpu::spotBoundingSphere (culling.h, with the
// derivation), the sphere lightBoundingSphere and the tile culling use.
BoundingSphere sectorBoundingSphere(const glm::vec3& apex, const glm::vec3& axis, float radius, float cosTheta) {
    const glm::vec4 sphere = gpu::spotBoundingSphere(apex, axis, radius, cosTheta);
    return {glm::vec3(sphere), sphere.w};
}

// True when the box lies entirely on the positive side of the plane through `apex` with unit
// normal `normal`, farther than `slack`: min over the box of dot(normal, x - apex) > slack. The
// minimum of a linear function over a box is at its centre minus |normal| . half size.
bool boxBeyondPlane(const Bounds& box, const glm::vec3& apex, const glm::vec3& normal, float slack) {
    const glm::vec3 halfSize = (box.max - box.min) * 0.5f;
    const float nearest = glm::dot(normal, box.center() - apex) - glm::dot(glm::abs(normal), halfSize);
    return nearest > slack;
}

// Planes through the apex that have the whole cone on their negative side, tested as separating
// planes. (A convex cone and a convex box that do not meet are always separated by such a plane
// through the apex, so trying good candidates is the natural test; any candidate is valid.)
//
// Tangent plane. With theta the (widened) half-angle <= 90 deg and u a unit vector perpendicular
// to the axis D, the plane containing the cone's generator D cos(theta) + u sin(theta) has outward
// normal n = u cos(theta) - D sin(theta). For a unit direction w at angle phi <= theta from D,
// w = D cos(phi) + v sin(phi) with v unit and perpendicular to D, so
//   dot(n, w) = cos(theta) dot(u, v) sin(phi) - sin(theta) cos(phi)
//            <= cos(theta) sin(phi) - sin(theta) cos(phi) = sin(phi - theta) <= 0:
// the cone is behind the plane. We take u towards the box (its centre, then its closest point),
// the plane that leans away from the box the most.
// Back plane: n = -D, the tangent plane for theta = 90 deg; it rejects boxes behind the light.
//
// A spot of 90 deg widened by the slack has theta' > 90 deg and is no longer convex; then we test
// the 90 deg planes and widen the slack instead: a lit point w (|w| < range) at phi <= theta' has
// dot(n, w) <= range sin(theta' - 90 deg) = range * (-cos(theta')).
bool coneMissesBox(const LightGeometry& light, const Bounds& box, float slack) {
    const float coneCos = light.cosOuter - kConeCosineSlack;  // widened
    const float planeCos = std::max(coneCos, 0.0f);
    const float planeSin = std::sqrt(1.0f - planeCos * planeCos);
    const float planeSlack = slack + (coneCos < 0.0f ? light.range * -coneCos : 0.0f);

    if (boxBeyondPlane(box, light.position, -light.axis, planeSlack)) return true;
    for (const glm::vec3& towards : {box.center(), glm::clamp(light.position, box.min, box.max)}) {
        const glm::vec3 offset = towards - light.position;
        const glm::vec3 perpendicular = offset - light.axis * glm::dot(offset, light.axis);
        const float length = glm::length(perpendicular);
        if (!(length > 1e-6f * glm::length(offset))) continue;  // on the axis: no tangent plane leans away
        const glm::vec3 normal = (perpendicular / length) * planeCos - light.axis * planeSin;
        if (boxBeyondPlane(box, light.position, normal, planeSlack)) return true;
    }
    return false;
}

bool mayReach(const LightGeometry& light, const Bounds& box) {
    if (box.empty()) return false;
    if (!std::isfinite(light.range)) return true;  // not produced by packPunctualLight: never cull
    // Absolute slack: rounding errors scale with the coordinates as well as with the range.
    const float slack = kRelativeSlack * (light.range + glm::length(light.position) + glm::length(box.min) +
                                          glm::length(box.max));

    // 1. The range sphere, exact: the closest point of the box to the light is clamp(P, min, max).
    const float reach = light.range + slack;
    if (squaredDistanceToBox(light.position, box) > reach * reach) return false;
    if (!light.isSpot) return true;

    // 2. The bounding sphere of the (widened) cone, when it is still a convex cone.
    const float coneCos = light.cosOuter - kConeCosineSlack;
    if (coneCos >= 0.0f) {
        const BoundingSphere sphere = sectorBoundingSphere(light.position, light.axis, light.range, coneCos);
        const float sphereReach = sphere.radius + slack;
        if (squaredDistanceToBox(sphere.center, box) > sphereReach * sphereReach) return false;
    }

    // 3. The cone itself.
    return !coneMissesBox(light, box, slack);
}

// The ranking formula of estimatedContribution (see per_object_lights.h), for a light that reaches.
float rankingContribution(const LightGeometry& light, const gpu::GpuPunctualLight& packed, const Bounds& box) {
    const float peakIntensity = std::max({packed.radiantColor.r, packed.radiantColor.g, packed.radiantColor.b, 0.0f});
    const glm::vec3 closest = glm::clamp(light.position, box.min, box.max);
    const glm::vec3 toClosest = closest - light.position;
    const float distanceSquared = std::max(glm::dot(toClosest, toClosest), kMinRankingDistanceSquared);
    float contribution = peakIntensity * gpu::distanceAttenuation(distanceSquared, light.invRangeSquared);

    if (light.isSpot) {
        // The shader's angular attenuation towards a box point; a point at the light itself (the
        // light inside the box) has no direction and counts as fully lit.
        auto angularTowards = [&](const glm::vec3& point) {
            const glm::vec3 toLight = light.position - point;
            const float length = glm::length(toLight);
            if (!(length > 1e-6f)) return 1.0f;
            return gpu::spotAttenuation(light.axis, toLight / length, light.angleScale, light.angleOffset);
        };
        float angular = std::max(angularTowards(closest), angularTowards(box.center()));
        if (!(angular > 0.0f)) angular = kGrazingSpotFactor;  // reaches (tested by the caller) but grazes
        contribution *= angular;
    }
    return std::isnan(contribution) ? 0.0f : contribution;
}

}  // namespace

BoundingSphere packedLightBoundingSphere(const gpu::GpuPunctualLight& light) {
    const LightGeometry geometry = unpack(light);
    if (!geometry.isSpot) return {geometry.position, geometry.range};
    return sectorBoundingSphere(geometry.position, geometry.axis, geometry.range, std::max(geometry.cosOuter, 0.0f));
}

bool lightMayReachBox(const gpu::GpuPunctualLight& light, const Bounds& box) { return mayReach(unpack(light), box); }

float estimatedContribution(const gpu::GpuPunctualLight& light, const Bounds& box) {
    const LightGeometry geometry = unpack(light);
    return mayReach(geometry, box) ? rankingContribution(geometry, light, box) : 0.0f;
}

PerObjectLightLists buildPerObjectLightLists(const Scene& scene, const FrameLights& frameLights) {
    constexpr uint32_t kCap = PUNCTUAL_MAX_LIGHTS_PER_OBJECT;
    const size_t objectCount = scene.objects.size();
    PerObjectLightLists lists;
    lists.lights.assign(objectCount * kCap, kUnusedLightSlot);
    lists.counts.assign(objectCount, 0u);

    std::vector<LightGeometry> geometries;
    geometries.reserve(frameLights.packed.size());
    for (const gpu::GpuPunctualLight& light : frameLights.packed) geometries.push_back(unpack(light));

    struct RankedLight {
        uint32_t packedIndex;
        float contribution;
    };
    // Strongest first, ties to the lower packed index: a strict total order (contributions are
    // never NaN), so the result does not depend on the sort algorithm.
    const auto strongerFirst = [](const RankedLight& a, const RankedLight& b) {
        if (a.contribution != b.contribution) return a.contribution > b.contribution;
        return a.packedIndex < b.packedIndex;
    };
    const auto ascendingIndex = [](const RankedLight& a, const RankedLight& b) { return a.packedIndex < b.packedIndex; };

    std::vector<RankedLight> candidates;
    candidates.reserve(geometries.size());
    for (size_t object = 0; object < objectCount; ++object) {
        const Bounds& box = scene.objects[object].worldBounds;
        candidates.clear();
        for (uint32_t i = 0; i < geometries.size(); ++i) {
            if (mayReach(geometries[i], box))
                candidates.push_back({i, rankingContribution(geometries[i], frameLights.packed[i], box)});
        }
        const uint32_t candidateCount = static_cast<uint32_t>(candidates.size());
        lists.maxCandidates = std::max(lists.maxCandidates, candidateCount);
        if (candidateCount > kCap) {
            ++lists.objectsOverCap;
            std::partial_sort(candidates.begin(), candidates.begin() + kCap, candidates.end(), strongerFirst);
            candidates.resize(kCap);
            std::sort(candidates.begin(), candidates.end(), ascendingIndex);
        }
        // Candidates were gathered in ascending index order, so an uncapped list is already sorted.
        lists.counts[object] = static_cast<uint32_t>(candidates.size());
        for (size_t k = 0; k < candidates.size(); ++k) lists.lights[object * kCap + k] = candidates[k].packedIndex;
    }
    return lists;
}

}  // namespace punctual
