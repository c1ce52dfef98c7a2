#include "scene/scene_path.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/box_layout.h"

namespace punctual {
namespace {

glm::vec3 sampled(const KeyframeTrack& track, double time) {
    const std::vector<float> v = sampleTrack(track, time);
    return glm::vec3(v[0], v[1], v[2]);
}

}  // namespace

KeyframeTrack linearTrack(std::vector<float> times, const std::vector<glm::vec3>& values) {
    KeyframeTrack track;
    track.interpolation = Interpolation::Linear;
    track.components = 3;
    track.times = std::move(times);
    for (const glm::vec3& v : values) track.values.insert(track.values.end(), {v.x, v.y, v.z});
    return track;
}

std::vector<uint32_t> movingLights(uint32_t lightCount, double share) {
    std::vector<uint32_t> lights;
    if (!(share > 0.0)) return lights;
    for (uint32_t k = 0;; ++k) {
        const double index = std::floor(double(k) / share + 1e-9);
        if (index >= double(lightCount)) break;
        lights.push_back(uint32_t(index));
    }
    return lights;
}

void addSwayingLights(ScenePath& path, uint32_t lightCount, double share) {
    const float length = float(path.seconds);
    const std::vector<float> times = {0.0f, 0.25f * length, 0.5f * length, 0.75f * length, length};
    for (const uint32_t light : movingLights(lightCount, share)) {
        path.lights.push_back({light, linearTrack(times, {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f},
                                                          {-1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}})});
    }
}

std::vector<uint32_t> sceneProps(const Scene& scene) {
    std::vector<uint32_t> props;
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        const Bounds& bounds = scene.objects[i].worldBounds;
        const glm::vec3 size = bounds.max - bounds.min;
        if (size.x <= kPropSide && size.y <= kPropSide && size.z <= kPropSide) props.push_back(i);
    }
    return props;
}

void addLiftedProps(ScenePath& path, const Scene& scene, double share) {
    const float length = float(path.seconds);
    const std::vector<float> times = {0.0f, 0.25f * length, 0.5f * length, 0.75f * length, length};
    const std::vector<uint32_t> props = sceneProps(scene);
    for (const uint32_t k : movingLights(uint32_t(props.size()), share)) {
        path.objects.push_back({props[k], linearTrack(times, {{0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f},
                                                              {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}})});
    }
}

void applyScenePath(Scene& scene, const ScenePath& path, double time) {
    // The offset is added to the placement's translation alone, so an offset of 0 (time 0) leaves
    // the model matrix, and so the still scene, bit for bit.
    for (const ObjectPath& moving : path.objects) {
        glm::mat4& model = scene.objects.at(moving.object).model;
        model[3] += glm::vec4(sampled(moving.offset, time), 0.0f);
    }
    if (!path.objects.empty()) scene.computeBounds();
    Camera& camera = scene.camera;
    camera.view = glm::lookAtRH(sampled(path.eye, time), sampled(path.target, time), glm::vec3(0.0f, 1.0f, 0.0f));
    camera.zfar = farthestViewDepth(scene.bounds, camera.view) + 1.0f;
    for (const LightPath& moving : path.lights) {
        Light& light = scene.lights.at(moving.light);
        light.position = light.position + sampled(moving.offset, time);
    }
}

}  // namespace punctual
