#pragma once
// The Embree 3 side of the CPU reference: one device and one scene holding the same triangles
// the GPU draws, in world space. It is built from punctual::Scene alone (never from anything the
// GPU path computes), so the reference stays an independent ruler.
//
// Mapping: object i of the Scene is Embree geometry i (attached by ID), one
// RTC_GEOMETRY_TYPE_TRIANGLE each with its vertices transformed by Object::model, so a hit's
// geomID is the object index and its primID the triangle within the object's mesh.
//
// Materials, as the GPU's passes treat them, through filter functions that read the ray's
// RayContext:
//  - alphaMode MASK: hits where the base colour's alpha is below the cutoff are dropped, for every
//    ray (the GPU's depth prepass and every shadow caster pass test alpha);
//  - single-sided (not doubleSided): hits on back faces are dropped for camera rays only (the GPU
//    culls back faces in the prepass; shadow casters are two-sided);
//  - alphaMode BLEND: primary rays pass through (they find the opaque surface, as the prepass
//    does), transparent-layer rays see only these, and shadow rays treat them as the ray's
//    TransparentShadows mode says (on: solid; clip and dither: alpha >= 0.5; off: never).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "lights/transparent_shadows.h"
#include "scene/scene.h"

namespace punctual::reference {

// What a ray is for, read by the filter functions. Embree's extended-context pattern: the
// RTCIntersectContext comes first, so the filters cast args->context back to the RayContext.
enum class RayKind : uint8_t { Primary, TransparentLayers, Shadow };
struct RayContext {
    RTCIntersectContext embree;
    RayKind kind = RayKind::Primary;
    TransparentShadows transparentShadows = TransparentShadows::Clip;  // shadow rays
};
RayContext makeRayContext(RayKind kind, TransparentShadows transparentShadows = TransparentShadows::Clip);

class EmbreeScene {
public:
    // Throws punctual::Error("embree", ...) when Embree reports an error (device creation,
    // geometry setup, commit). `scene` must outlive this (the filter functions read it).
    explicit EmbreeScene(const Scene& scene);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    RTCScene handle() const { return scene_.get(); }
    RTCDevice device() const { return device_.get(); }

    // The offset that lifts a shadow ray's origin at `point` off its surface: 1e-4 x the point's
    // largest coordinate, and at least 1e-4 x 1% of the scene's bounding radius (a relative
    // epsilon; an absolute one would be too small for a city and too large for a teapot). Float
    // rounding of a point is ~1e-7 x its largest coordinate, so three orders of magnitude of
    // margin remain. It is taken at the point rather than from the scene's radius, because the
    // lift moves shadow edges: by epsilon / tan(elevation) on a floor, and a radius-wide epsilon
    // (3 cm in a 300 m street) moved the sun's edges by a shadow texel.
    float rayEpsilonAt(const glm::vec3& point) const {
        const glm::vec3 a = glm::abs(point);
        return 1e-4f * std::max(std::max(a.x, std::max(a.y, a.z)), rayEpsilonFloor_);
    }
    uint32_t geometryCount() const { return geometryCount_; }  // objects with triangles

    // Embree's geometric normal Ng is (v1 - v0) x (v2 - v0) of the world-space triangle: it points
    // to the side from which the vertices are seen counter-clockwise (glTF's and our GPU
    // pipeline's front face). Verified by the test ReferenceEmbree.GeometricNormalIsCounterClockwiseFront.
    static glm::vec3 geometricNormal(const RTCHit& hit) { return {hit.Ng_x, hit.Ng_y, hit.Ng_z}; }

    // Throws punctual::Error("embree", <what>: <message>) if the device recorded an error since
    // the last check (the error callback's message, or rtcGetDeviceError's code).
    void throwIfError(const std::string& what) const;

private:
    struct ErrorLog;  // filled by the device's error callback; stable address for the user pointer
    struct DeviceRelease { void operator()(RTCDevice device) const { rtcReleaseDevice(device); } };
    struct SceneRelease { void operator()(RTCScene scene) const { rtcReleaseScene(scene); } };

    void addObject(const Scene& scene, uint32_t objectIndex);

public:
    // What an object's filter functions read (geometryUserPtr); public for the callbacks only.
    struct SurfaceFilter {
        const Scene* scene = nullptr;
        uint32_t object = 0;
        bool masked = false;       // alphaMode MASK
        bool blended = false;      // alphaMode BLEND
        bool singleSided = false;  // not doubleSided: primary rays pass its back faces
        bool mirrored = false;     // the transform reverses the winding
    };

private:
    std::vector<SurfaceFilter> filters_;  // one per object, reserved up front: stable addresses
    std::unique_ptr<ErrorLog> errors_;
    // Declared after errors_ and before scene_: the scene is released first, then the device,
    // then the log the device's callback may still write to while releasing.
    std::unique_ptr<RTCDeviceTy, DeviceRelease> device_;
    std::unique_ptr<RTCSceneTy, SceneRelease> scene_;
    float rayEpsilonFloor_ = 1.0f;  // 1% of the scene's bounding radius
    uint32_t geometryCount_ = 0;
};

}  // namespace punctual::reference
