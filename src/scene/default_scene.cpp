#include "scene/default_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu_types.h"
#include "scene/box_faces.h"
#include "scene/box_layout.h"
#include "scene/scene_path.h"
#include "scene/light_generator.h"

namespace punctual {

namespace {

// ---- geometry --------------------------------------------------------------------------------

enum MaterialId : uint32_t { kFloor, kConcrete, kRedPaint, kSteel, kBrass, kBluePlastic, kGreenRubber };

void addMaterials(Scene& scene) {
    // Order matches MaterialId. Albedos stay below ~0.8 as real materials do.
    scene.materials = {
        plainMaterial("floor", {0.50f, 0.50f, 0.48f}, 0.0f, 0.85f),
        plainMaterial("concrete", {0.72f, 0.70f, 0.66f}, 0.0f, 0.70f),
        plainMaterial("red paint", {0.70f, 0.18f, 0.14f}, 0.0f, 0.50f),
        plainMaterial("brushed steel", {0.82f, 0.83f, 0.85f}, 1.0f, 0.35f),
        plainMaterial("brass", {0.95f, 0.75f, 0.40f}, 1.0f, 0.25f),
        plainMaterial("blue plastic", {0.10f, 0.25f, 0.65f}, 0.0f, 0.30f),
        plainMaterial("green rubber", {0.20f, 0.45f, 0.22f}, 0.0f, 0.95f),
    };
}

// The hall: floor 40 m x 30 m (top at y = 0), a 5 m back wall, partial side walls, three interior
// walls (the near one hides a strip of floor behind it from the camera: a depth discontinuity), a
// colonnade of eight 6 m pillars and crates of assorted sizes, some rotated or stacked.
std::vector<BoxSpec> hallLayout() {
    using default_scene::kFloorHalfDepth;
    using default_scene::kFloorHalfWidth;
    std::vector<BoxSpec> boxes = {
        {"floor", {-kFloorHalfWidth, -0.2f, -kFloorHalfDepth}, {kFloorHalfWidth, 0.0f, kFloorHalfDepth}, kFloor},
        {"back wall", {-20.4f, 0.0f, -15.4f}, {20.4f, 5.0f, -15.0f}, kConcrete},
        {"left wall", {-20.4f, 0.0f, -15.0f}, {-20.0f, 3.5f, 5.0f}, kConcrete},
        {"right wall", {20.0f, 0.0f, -15.0f}, {20.4f, 3.5f, -3.0f}, kConcrete},
        {"near wall", {-13.0f, 0.0f, 3.8f}, {-3.0f, 2.5f, 4.2f}, kRedPaint},
        {"middle wall", {5.0f, 0.0f, -6.2f}, {15.0f, 3.0f, -5.8f}, kConcrete},
        {"partition", {-0.2f, 0.0f, -13.0f}, {0.2f, 2.2f, -7.0f}, kRedPaint},
    };
    const glm::vec3 pillarSize(0.8f, 6.0f, 0.8f);
    const std::array<glm::vec2, 8> pillars = {{{-15, -10}, {-5, -10}, {5, -10}, {15, -10},
                                               {-15, 0}, {-5, 0}, {5, 0}, {15, 0}}};
    for (size_t i = 0; i < pillars.size(); ++i)
        boxes.push_back(standing("pillar", pillars[i].x, pillars[i].y, pillarSize, i % 3 == 2 ? kSteel : kConcrete));
    const std::vector<BoxSpec> crates = {
        standing("crate", -16.0f, 10.0f, {2.0f, 1.0f, 2.0f}, kBluePlastic),
        standing("crate", -8.0f, 9.0f, {1.2f, 1.2f, 1.2f}, kBrass, {11.0f, 4.0f}),            // turned 20 deg
        standing("stacked crate", -8.0f, 9.0f, {0.7f, 0.7f, 0.7f}, kGreenRubber, {4.0f, 5.0f}, 1.2f),  // 51 deg, on top
        standing("platform", 2.0f, 11.0f, {3.0f, 0.6f, 1.5f}, kSteel),
        standing("tower", 9.0f, 10.0f, {1.5f, 2.0f, 1.5f}, kConcrete),
        standing("crate", 14.0f, 7.0f, {2.5f, 1.2f, 2.5f}, kGreenRubber, {7.0f, 4.0f}),      // 30 deg
        standing("cube", -1.0f, 2.5f, {1.0f, 1.0f, 1.0f}, kRedPaint),
        standing("block", 7.0f, -2.0f, {2.0f, 2.5f, 1.0f}, kBluePlastic, {15.0f, 4.0f}),    // 15 deg
        standing("big block", -14.0f, -5.0f, {3.0f, 1.5f, 3.0f}, kConcrete),
        standing("crate", -2.5f, -4.0f, {1.5f, 1.0f, 1.5f}, kBrass),
        standing("tall crate", 12.0f, -12.0f, {2.0f, 3.0f, 2.0f}, kSteel),
        standing("post", 17.5f, 3.0f, {1.0f, 4.0f, 1.0f}, kRedPaint),
        standing("bar", -6.0f, -5.0f, {1.6f, 0.8f, 0.8f}, kSteel, {1.0f, 1.0f}),             // 45 deg
        standing("slab", 3.0f, 5.0f, {1.2f, 0.5f, 2.5f}, kGreenRubber, {2.0f, -1.0f}),       // -27 deg
    };
    boxes.insert(boxes.end(), crates.begin(), crates.end());
    return boxes;
}

void addGeometry(Scene& scene) { addBoxes(scene, hallLayout()); }

// ---- camera ----------------------------------------------------------------------------------

// Eye 9 m up, 3.5 m behind the near edge of the floor, looking at a floor point 12.4 m ahead: a
// pitch of atan(9 / 12.4) = 36 degrees down. With a 60 degree vertical field of view the lowest
// ray (66 degrees down) meets the floor at z = 14.5, just inside its near edge, and the far edge
// and back wall fill the upper part of a 16:9 frame: the floor is ~64% of the frame (after
// occlusion), walls and boxes most of the rest, background ~6% (the top corners).
// (Built with lookAt from points, no trigonometry, so it is the same everywhere.)
void addCamera(Scene& scene) {
    Camera& camera = scene.camera;
    camera.name = "default";
    const glm::vec3 eye(0.0f, 9.0f, 18.5f);
    const glm::vec3 target(0.0f, 0.0f, 6.1f);
    camera.view = glm::lookAtRH(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
    camera.yfov = 1.04719755f;  // 60 degrees
    camera.znear = 0.1f;
    // Far plane just beyond the farthest corner of the bounds along the view axis.
    const float farthest = farthestViewDepth(scene.bounds, camera.view);
    camera.zfar = farthest + 1.0f;
    scene.cameraFromFile = true;
}

// ---- lights ----------------------------------------------------------------------------------

// Places lights above visible floor points. All placement tests use the camera's 16:9
// projection, so every light is inside the default view (with a margin) and lights floor that
// the camera sees.
class LightPlacer {
public:
    explicit LightPlacer(const Scene& scene)
        : view_(scene.camera.view),
          zfar_(scene.camera.zfar),
          random_(0x70756E637475A1ull) {  // "punctu" + a version byte: any fixed value works
        for (size_t i = 1; i < scene.objects.size(); ++i) solids_.push_back(scene.objects[i].worldBounds);
    }

    PortableRandom& random() { return random_; }

    // A floor point (y = 0) well inside the view, spread out by best-candidate sampling
    // (Mitchell 1991): of 8 random candidates take the one farthest from the targets chosen so far,
    // which covers the floor far more evenly than plain random points.
    glm::vec3 nextTarget() {
        glm::vec3 best(0.0f);
        float bestDistance = -1.0f;
        for (int candidate = 0; candidate < 8; ++candidate) {
            const glm::vec3 p = randomVisibleFloorPoint();
            float nearest = 1e30f;
            for (const glm::vec3& t : targets_) nearest = std::min(nearest, glm::distance(p, t));
            if (nearest > bestDistance) {
                bestDistance = nearest;
                best = p;
            }
        }
        targets_.push_back(best);
        return best;
    }

    // True when `p` is inside the 16:9 view with a margin and outside every solid by `clearance`.
    bool acceptablePosition(const glm::vec3& p, float clearance) const {
        if (!insideView(p, 0.9f)) return false;
        for (const Bounds& solid : solids_) {
            if (glm::all(glm::greaterThan(p, solid.min - clearance)) && glm::all(glm::lessThan(p, solid.max + clearance)))
                return false;
        }
        return true;
    }

    void forgetLastTarget() { targets_.pop_back(); }

private:
    // Inside |x|, |y| <= margin in normalised device coordinates, at least 1 m in front of the eye
    // and before the far plane. The perspective is applied by hand with 1/tan(30 deg) = sqrt(3)
    // (Camera::projection calls tan(), which maths libraries may round differently; a last-bit
    // difference must not be able to move a light).
    bool insideView(const glm::vec3& p, float margin) const {
        const glm::vec3 v = glm::vec3(view_ * glm::vec4(p, 1.0f));
        const float depth = -v.z;
        const float focal = std::sqrt(3.0f);  // cot(yfov / 2) for the 60 degree field of view
        return depth > 1.0f && depth < zfar_ && std::abs(focal / default_scene::kDesignAspect * v.x) <= margin * depth &&
               std::abs(focal * v.y) <= margin * depth;
    }

    glm::vec3 randomVisibleFloorPoint() {
        for (int attempt = 0; attempt < 10000; ++attempt) {
            const glm::vec3 p(random_.uniform(-19.0f, 19.0f), 0.0f, random_.uniform(-14.5f, 14.5f));
            if (insideView(p, 0.85f)) return p;
        }
        throw std::logic_error("default scene: no visible floor point found");  // the layout is broken
    }

    glm::mat4 view_;
    float zfar_;
    PortableRandom random_;
    std::vector<Bounds> solids_;
    std::vector<glm::vec3> targets_;
};

// (1 - (d/r)^4)^2: the distance window of shading.h, to aim an intensity at a wanted illuminance.
float distanceWindow(float distance, float range) {
    const float ratio = (distance * distance) / (range * range);
    const float window = 1.0f - ratio * ratio;
    return window * window;
}

constexpr float kDegree = 0.0174532925f;

// 64 spots hung 3-6.5 m above floor targets, aimed at them with the tilt that implies (up to
// atan(0.35 sqrt 2) = 26 degrees from vertical), outer cones 25-50 degrees, ranges 1.5-2.2 x the distance to their target, and
// intensities that give 0.6-1.6 lux on the axis at the target.
void addSpotLights(Scene& scene, LightPlacer& placer, int count) {
    PortableRandom& random = placer.random();
    for (int i = 0; i < count; ++i) {
        for (int attempt = 0;; ++attempt) {
            if (attempt == 1000) throw std::logic_error("default scene: cannot place spot lights");
            const glm::vec3 target = placer.nextTarget();
            const float height = random.uniform(3.0f, 6.5f);
            // Aim at the target from a point offset horizontally by (tilt x height).
            const glm::vec3 shine(random.uniform(-0.35f, 0.35f), -1.0f, random.uniform(-0.35f, 0.35f));
            const glm::vec3 position = target - shine * height;
            if (!placer.acceptablePosition(position, 0.3f)) {
                placer.forgetLastTarget();
                continue;
            }
            Light light;
            light.name = "spot " + std::to_string(i);
            light.type = LightType::Spot;
            light.position = position;
            light.direction = glm::normalize(shine);
            light.color = randomLightColor(random);
            light.outerConeAngle = random.uniform(25.0f, 50.0f) * kDegree;
            light.innerConeAngle = light.outerConeAngle * random.uniform(0.5f, 0.9f);
            const float distance = glm::length(shine) * height;
            light.range = distance * random.uniform(1.5f, 2.2f);
            const float axisLux = random.uniform(0.6f, 1.6f);
            light.intensity = axisLux * distance * distance / distanceWindow(distance, light.range);
            light.castsShadow = true;
            scene.lights.push_back(light);
            break;
        }
    }
}

// 32 points 1-3.5 m above floor targets, ranges 6-9 m, 1-2.5 lux on the floor right below.
void addPointLights(Scene& scene, LightPlacer& placer, int count) {
    PortableRandom& random = placer.random();
    for (int i = 0; i < count; ++i) {
        for (int attempt = 0;; ++attempt) {
            if (attempt == 1000) throw std::logic_error("default scene: cannot place point lights");
            const glm::vec3 target = placer.nextTarget();
            const float height = random.uniform(1.0f, 3.5f);
            const glm::vec3 position = target + glm::vec3(0.0f, height, 0.0f);
            if (!placer.acceptablePosition(position, 0.3f)) {
                placer.forgetLastTarget();
                continue;
            }
            Light light;
            light.name = "point " + std::to_string(i);
            light.type = LightType::Point;
            light.position = position;
            light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
            light.color = randomLightColor(random);
            light.range = random.uniform(6.0f, 9.0f);
            const float belowLux = random.uniform(1.0f, 2.5f);
            light.intensity = belowLux * height * height / distanceWindow(height, light.range);
            light.castsShadow = true;
            scene.lights.push_back(light);
            break;
        }
    }
}

}  // namespace

uint32_t appendBoxMesh(Scene& scene, const std::string& name, const glm::vec3& size, uint32_t material) {
    // The faces and their corners: scene/box_faces.h.

    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    mesh.firstIndex = static_cast<uint32_t>(scene.indices.size());
    mesh.vertexOffset = static_cast<uint32_t>(scene.vertices.size());
    const glm::vec3 half = size * 0.5f;
    for (const BoxFace& face : kBoxFaces) {
        const uint32_t base = static_cast<uint32_t>(scene.vertices.size()) - mesh.vertexOffset;
        for (const glm::vec2& corner : kBoxFaceCorners) {
            Vertex vertex;
            vertex.position = (face.n + face.u * corner.x + face.v * corner.y) * half;
            vertex.normal = face.n;
            vertex.uv = glm::vec2((corner.x + 1.0f) * 0.5f, 1.0f - (corner.y + 1.0f) * 0.5f);
            scene.vertices.push_back(vertex);
            mesh.localBounds.extend(vertex.position);
        }
        for (const uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) scene.indices.push_back(base + i);
    }
    mesh.indexCount = static_cast<uint32_t>(scene.indices.size()) - mesh.firstIndex;
    mesh.vertexCount = static_cast<uint32_t>(scene.vertices.size()) - mesh.vertexOffset;
    scene.meshes.push_back(mesh);
    return static_cast<uint32_t>(scene.meshes.size() - 1);
}

// ---- the walk (issue 34) ---------------------------------------------------------------------

// From the still view, down and to the left over the near crates, along the aisle between the
// left colonnade (x = -15) and the middle one (x = -5) at 3.5-4.5 m, above every box there (the
// near wall is 2.5 m high), turning towards the partition and the back wall. Keyframes every 3 s.
// Every sixth lamp (16 of 96: spots and points alike; --moving-lights F another share) sways 1 m
// to +x and back and 1 m to -x and back (addSwayingLights).
ScenePath hallWalk(const Scene& scene, const PathMotion& motion) {
    using default_scene::kWalkSeconds;
    ScenePath path;
    const std::vector<float> times = {0.0f, 3.0f, 6.0f, 9.0f, kWalkSeconds};
    path.eye = linearTrack(times, {{0.0f, 9.0f, 18.5f}, {-6.0f, 6.0f, 14.0f}, {-10.0f, 4.5f, 8.0f},
                                   {-10.0f, 4.0f, 0.0f}, {-8.0f, 3.5f, -6.0f}});
    path.target = linearTrack(times, {{0.0f, 0.0f, 6.1f}, {-9.0f, 0.5f, 2.0f}, {-10.0f, 1.0f, -10.0f},
                                      {-4.0f, 1.0f, -12.0f}, {6.0f, 1.0f, -12.0f}});
    path.seconds = double(kWalkSeconds);
    addSwayingLights(path, uint32_t(scene.lights.size()), motion.lights.value_or(default_scene::kMovingLightShare));
    addLiftedProps(path, scene, motion.casters);
    return path;
}

void poseDefaultScene(Scene& scene, double time, const PathMotion& motion) {
    applyScenePath(scene, hallWalk(scene, motion), time);
}

Scene makeDefaultScene() {
    Scene scene;
    scene.source = default_scene::kSource;
    addMaterials(scene);
    addGeometry(scene);
    scene.computeBounds();
    addCamera(scene);
    LightPlacer placer(scene);
    addSpotLights(scene, placer, PUNCTUAL_DEFAULT_MAX_SPOT_LIGHTS);
    addPointLights(scene, placer, PUNCTUAL_DEFAULT_MAX_POINT_LIGHTS);
    return scene;
}

}  // namespace punctual
