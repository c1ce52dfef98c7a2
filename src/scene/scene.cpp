#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace punctual {

Bounds Bounds::transformed(const glm::mat4& m) const {
    Bounds out;
    if (empty()) return out;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? max.x : min.x, (corner & 2) ? max.y : min.y,
                          (corner & 4) ? max.z : min.z);
        out.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
    }
    return out;
}

glm::vec3 Camera::position() const { return glm::vec3(glm::inverse(view)[3]); }

glm::mat4 Camera::projection(float aspect) const {
    // Reversed Z: GLM's 0..1 projection with the planes swapped maps the near plane to depth 1 and
    // the far plane to 0, depth = n (f - D) / (D (f - n)) at view distance D, close to n / D
    // wherever D << f. A float depth buffer resolves n / D to the same relative precision (2^-24)
    // at every distance and for any n > 0. The usual mapping, 1 - n / D, crowds every distance
    // into the few floats just below 1: with n = 1e-6 m all of them beyond ~17 m round to 1.0,
    // the clear value.
    glm::mat4 p = glm::perspectiveRH_ZO(yfov, aspect, zfar, znear);
    p[1][1] *= -1.0f;  // Vulkan's framebuffer y points down; flip so the image is upright.
    return p;
}

void Scene::computeBounds() {
    bounds = Bounds{};
    for (Object& object : objects) {
        object.worldBounds = meshes.at(object.mesh).localBounds.transformed(object.model);
        bounds.extend(object.worldBounds);
    }
}

float derivedRange(float intensityCandela, const glm::vec3& color) {
    const float peak = intensityCandela * std::max({color.r, color.g, color.b, 0.0f});
    return std::max(std::sqrt(peak / kInfiniteRangeCutoffLux), 1e-3f);
}

Camera fitCameraToBounds(const Bounds& bounds, float yfov) {
    Camera camera;
    camera.name = "fitted";
    camera.yfov = yfov;
    const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    const float radius = bounds.empty() ? 1.0f : std::max(bounds.radius(), 1e-3f);
    // Distance at which a sphere of `radius` fits the vertical field of view.
    const float distance = radius / std::sin(yfov * 0.5f);
    const glm::vec3 viewDirection = glm::normalize(glm::vec3(-0.45f, -0.5f, -1.0f));
    const glm::vec3 eye = center - viewDirection * distance;
    camera.view = glm::lookAtRH(eye, center, glm::vec3(0.0f, 1.0f, 0.0f));
    camera.znear = std::max(distance - radius, distance * 0.01f) * 0.5f;
    camera.zfar = (distance + radius) * 1.05f;
    return camera;
}

namespace {
bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string describe(const Light& light, size_t index) {
    std::ostringstream s;
    s << "light " << index;
    if (!light.name.empty()) s << " (\"" << light.name << "\")";
    return s.str();
}
}  // namespace

void checkCameraPrecision(const Camera& camera, uint32_t height, const std::string& source) {
    // A pixel spans about 2 tan(yfov / 2) / height radians at the centre of the frame.
    const double pixelAngle = 2.0 * std::tan(double(camera.yfov) * 0.5) / double(std::max(height, 1u));
    if (pixelAngle >= kMinPixelAngle) return;
    const double smallest = 2.0 * std::atan(kMinPixelAngle * double(std::max(height, 1u)) * 0.5);
    std::ostringstream message;
    message << "camera" << (camera.name.empty() ? "" : " '" + camera.name + "'") << ": yfov " << camera.yfov
            << " rad is too narrow for float precision at " << height << " rows (a pixel would span " << pixelAngle
            << " rad, less than 2^-16); use a yfov of at least " << smallest << " rad";
    throw Error(source, message.str());
}

void validateLights(const std::vector<Light>& lights, const std::string& source) {
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& light = lights[i];
        const std::string who = describe(light, i);
        if (!std::isfinite(light.intensity) || light.intensity < 0.0f)
            throw Error(source, who + " has an invalid intensity (must be finite and >= 0)");
        if (!finite3(light.color) || light.color.r < 0.0f || light.color.g < 0.0f || light.color.b < 0.0f)
            throw Error(source, who + " has an invalid colour (must be finite and >= 0)");
        // A point light shines the same way in every direction, so only spots and the sun have one
        // to lose to a singular (e.g. zero-scale) node transform.
        if (light.type != LightType::Point && (!finite3(light.direction) || glm::length(light.direction) < 0.5f))
            throw Error(source, who + " has a degenerate direction (its node transform is singular or not finite)");
        if (light.type == LightType::Directional) continue;
        if (!finite3(light.position)) throw Error(source, who + " has a position that is not finite");
        if (light.rangeDerived && !(std::isfinite(light.range) && light.range > 0.0f)) {
            std::ostringstream intensity;
            intensity << light.intensity << " cd, too large to derive a cut-off radius from (sqrt(intensity / "
                      << kInfiniteRangeCutoffLux << " lux) overflows a float)";
            throw Error(source, who + " has no range and an intensity of " + intensity.str() + "; give the light a range");
        }
        if (!std::isfinite(light.range) || light.range <= 0.0f)
            throw Error(source, who + " has an invalid range (must be finite and > 0)");
        if (light.type == LightType::Spot) {
            const float halfPi = 1.57079633f;
            if (!std::isfinite(light.innerConeAngle) || !std::isfinite(light.outerConeAngle) ||
                light.innerConeAngle < 0.0f || light.outerConeAngle > halfPi ||
                light.innerConeAngle >= light.outerConeAngle)
                throw Error(source, who + " has invalid cone angles (need 0 <= innerConeAngle < outerConeAngle <= pi/2)");
        }
    }
}

}  // namespace punctual
