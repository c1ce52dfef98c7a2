#include "scene/light_reach.h"

#include <algorithm>
#include <cmath>

#include "scene/light_generator.h"

namespace punctual {
namespace {

// cos and sin for angles in [0, pi] by their Taylor series (Horner, in double): only + and x,
// so the same on every platform, where std::cos may differ between libms in the last bit and
// flip a borderline decision (and with it every generated light after it). Error < 1e-8.
double portableCos(double x) {
    const double x2 = x * x;
    double term = 1.0;  // 1 - x^2/(1*2) (1 - x^2/(3*4) (1 - ...)), to x^18
    for (int n = 18; n >= 2; n -= 2) term = 1.0 - x2 / double(n * (n - 1)) * term;
    return term;
}

double portableSin(double x) {
    const double x2 = x * x;
    double term = 1.0;  // x (1 - x^2/(2*3) (1 - x^2/(4*5) (1 - ...))), to x^19
    for (int n = 19; n >= 3; n -= 2) term = 1.0 - x2 / double(n * (n - 1)) * term;
    return x * term;
}

}  // namespace

LightReach::LightReach(const Scene& scene, uint32_t gridSide) : bvh_(scene) {
    if (bvh_.empty() || scene.bounds.empty() || gridSide == 0) return;
    // Shadow rays start this far off the surface: a relative epsilon, as the reference's
    // (1e-4 x the scene's bounding radius), so a surface never shadows itself.
    const float lift = std::max(scene.bounds.radius(), 1e-6f) * 1e-4f;
    const Camera& camera = scene.camera;
    const glm::mat4 cameraToWorld = glm::inverse(camera.view);
    const glm::vec3 eye = glm::vec3(cameraToWorld[3]);
    const double halfFov = double(camera.yfov) * 0.5;
    const float tanHalf = float(portableSin(halfFov) / portableCos(halfFov));
    for (uint32_t row = 0; row < gridSide; ++row) {
        for (uint32_t column = 0; column < gridSide; ++column) {
            const float x = (2.0f * (float(column) + 0.5f) / float(gridSide) - 1.0f) * tanHalf;
            const float y = (1.0f - 2.0f * (float(row) + 0.5f) / float(gridSide)) * tanHalf;
            const glm::vec3 direction = glm::normalize(glm::mat3(cameraToWorld) * glm::vec3(x, y, -1.0f));
            // Surfaces nearer than the near plane are clipped away: start the ray there.
            const glm::vec3 origin = eye + direction * camera.znear;
            const auto hit = bvh_.intersect(origin, direction, std::max(camera.zfar - camera.znear, 0.0f));
            if (!hit) continue;
            const glm::vec3 point = origin + direction * hit->distance;
            samples_.push_back({point + hit->normal * lift, hit->normal});
        }
    }
    // A fixed shuffle (Fisher-Yates on our portable random source), so the first
    // kMaxShadowRays candidates of reaches() are spread over the whole view.
    PortableRandom random(0x5eed);
    for (size_t i = samples_.size(); i > 1; --i) {
        const size_t j = std::min(size_t(random.uniform() * float(i)), i - 1);
        std::swap(samples_[i - 1], samples_[j]);
    }
}

std::vector<glm::vec3> LightReach::samplePoints() const {
    std::vector<glm::vec3> points;
    points.reserve(samples_.size());
    for (const Sample& sample : samples_) points.push_back(sample.point);
    return points;
}

bool LightReach::reaches(const Light& light) const {
    if (light.type == LightType::Directional) return true;
    const float cosOuter = float(portableCos(double(light.outerConeAngle)));
    uint32_t rays = 0;
    for (const Sample& sample : samples_) {
        const glm::vec3 toLight = light.position - sample.point;
        const float distance = glm::length(toLight);
        if (!(distance < light.range) || !(distance > 0.0f)) continue;
        if (!(glm::dot(sample.normal, toLight) > 0.0f)) continue;
        if (light.type == LightType::Spot && !(glm::dot(light.direction, -toLight / distance) > cosOuter)) continue;
        if (!bvh_.occluded(sample.point, light.position)) return true;
        if (++rays >= kMaxShadowRays) return false;
    }
    return false;
}

}  // namespace punctual
