#pragma once
// The CPU reference image, ray traced with Embree: the ruler the GPU image (and later its
// shadows) is measured against.
//
// What it shares with the GPU path, on purpose: the scene, the camera's view and projection
// matrices, the frame's light list (setupFrameLights: the same culling and caps) and the shading
// math itself (shaders/shared/shading.h, compiled here as C++). What it does NOT share: how
// surfaces are found (one Embree ray per pixel centre instead of rasterisation), how attributes
// are interpolated (Embree's barycentrics) and how textures are filtered (texture_sampler.h). So
// an agreement between the two images checks the GPU's geometry, interpolation and sampling
// against an independent implementation, and the shading formulas cannot drift apart.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "gpu_types.h"
#include "lights/light_setup.h"
#include "reference/embree_scene.h"
#include "reference/material_sampling.h"
#include "scene/scene.h"

namespace punctual::reference {

struct ReferenceSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    float exposure = 1.0f;      // linear multiplier before tone mapping, as the GPU's
    bool shadows = true;        // false: every light is unoccluded (what the GPU draws today)
    // How alphaMode BLEND surfaces shadow (--transparent-shadows), as the GPU's caster passes.
    TransparentShadows transparentShadows = TransparentShadows::Clip;
    LightCapacity maxLights;    // --max-lights: the same lights as the GPU's frame
    bool showProgress = false;  // one updating line on stderr (the command sets it for terminals)
};

struct ReferenceStats {
    uint64_t primaryRays = 0;
    uint64_t shadowRays = 0;
    double seconds = 0.0;  // wall clock of the ray tracing and shading (not the BVH build)
    double buildSeconds = 0.0;  // Embree scene build
    uint64_t rays() const { return primaryRays + shadowRays; }
    double raysPerSecond() const { return seconds > 0.0 ? double(rays()) / seconds : 0.0; }
};

// What the primary ray through one pixel centre found. The later shadow validation needs these
// per pixel (which surface, where, facing which way), so they are public.
struct SurfaceHit {
    bool hit = false;
    uint32_t object = 0;    // index into Scene::objects (== Embree geomID)
    uint32_t triangle = 0;  // triangle within the object's mesh (== Embree primID)
    float distance = 0.0f;  // along the ray, from the near plane
    glm::vec3 position{0.0f};         // world space
    glm::vec3 normal{0.0f};           // unit shading normal, turned to the viewer like the GPU's
    glm::vec3 geometricNormal{0.0f};  // unit normal of the triangle plane, on the viewer's side
    glm::vec2 uv{0.0f};     // TEXCOORD_0
    // Both coordinate sets with their change across one pixel right and one down (the pixel
    // footprint the GPU's implicit level of detail comes from), found by intersecting the
    // neighbouring pixels' rays with the hit triangle's plane; the derivatives only where the
    // material has a texture.
    SurfaceUv texCoords;
    bool backFace = false;  // the viewer sees the side opposite the mesh's front (CCW) face
};

// Visibility of a light from a surface point, by one shadow ray: 1 (nothing between) or 0.
// `normal` is the unit geometric normal on the side the point is seen from (SurfaceHit::
// geometricNormal); the ray leaves from the point lifted along it (see the .cpp for the
// tnear/tfar rule). The light's attenuation is not looked at: this is geometry only.
// Transparent (alphaMode BLEND) surfaces block it as `transparentShadows` says.
float visibility(const EmbreeScene& scene, glm::vec3 point, glm::vec3 normal, const gpu::GpuPunctualLight& light,
                 TransparentShadows transparentShadows = TransparentShadows::Clip);
// A directional light: the ray goes to infinity along directionToLight.
float visibility(const EmbreeScene& scene, glm::vec3 point, glm::vec3 normal, const gpu::GpuDirectionalLight& sun,
                 TransparentShadows transparentShadows = TransparentShadows::Clip);

// The GPU's tone mapping (tonemap.comp): exposure, ACES, sRGB encoding, then packUnorm4x8's
// quantisation round(clamp(c, 0, 1) * 255); alpha 255.
std::array<uint8_t, 4> toneMapToRgba8(glm::vec3 radiance, float exposure);

class ReferenceRenderer {
public:
    // Builds the Embree scene and the frame's lights. `scene` must outlive the renderer. Throws
    // punctual::Error for bad settings (naming the option), bad scenes and Embree errors.
    ReferenceRenderer(const Scene& scene, const ReferenceSettings& settings);
    ~ReferenceRenderer();
    ReferenceRenderer(const ReferenceRenderer&) = delete;
    ReferenceRenderer& operator=(const ReferenceRenderer&) = delete;

    // The primary ray through the centre of pixel (x, y), rows top to bottom: the nearest opaque
    // or masked surface (transparent ones are passed, as the GPU's depth prepass leaves them out).
    SurfaceHit traceSurface(uint32_t x, uint32_t y) const;
    // Linear radiance (before exposure) leaving `hit` towards the camera: the sun, then every
    // packed spot and point light in the GPU's order, each times its visibility when shadows are
    // on. Adds the shadow rays it casts to `shadowRays` when given. Background: black.
    glm::vec3 shade(const SurfaceHit& hit, uint64_t* shadowRays = nullptr) const;
    // The pixel's radiance: shade(hit), then every transparent surface in front of it blended over
    // it, farthest first, by its base colour's alpha (the GPU's transparent pass, per surface hit
    // where the GPU sorts per object).
    glm::vec3 shadePixel(uint32_t x, uint32_t y, const SurfaceHit& hit, uint64_t* shadowRays = nullptr) const;

    // The whole image, parallel over rows (TBB). Deterministic: every pixel is computed on its
    // own, so scheduling cannot change a bit. `surfaces`, when given, receives every pixel's hit.
    ImageRgba8 render(ReferenceStats* stats = nullptr, std::vector<SurfaceHit>* surfaces = nullptr) const;

    const EmbreeScene& embree() const { return *embree_; }
    const FrameLights& lights() const { return lights_; }
    const glm::mat4& view() const { return view_; }
    const glm::mat4& projection() const { return projection_; }
    const ReferenceSettings& settings() const { return settings_; }
    double buildSeconds() const { return buildSeconds_; }

private:
    struct ObjectShading {
        glm::mat4 model{1.0f};
        glm::mat3 normalMatrix{1.0f};  // inverse transpose of the model matrix, as the GPU's
        bool mirrored = false;         // negative determinant: the world winding is reversed
    };

    struct PixelRay {
        glm::vec3 origin;     // on the near plane
        glm::vec3 direction;  // unit
        float length;         // to the far plane
    };
    // The ray through the point (x, y) of the image, in pixels from its top-left corner.
    PixelRay pixelRay(double x, double y) const;
    // The SurfaceHit of an intersection query for pixel (x, y).
    SurfaceHit surfaceOf(const RTCRayHit& query, uint32_t x, uint32_t y) const;
    // Fills hit.texCoords' derivatives from the rays through the centres right of and below
    // pixel (x, y).
    void addUvFootprint(SurfaceHit& hit, uint32_t x, uint32_t y, const glm::vec3 corners[3],
                        const glm::vec2 uv0[3], const glm::vec2 uv1[3]) const;
    glm::vec4 baseColor(const SurfaceHit& hit) const;

    const Scene& scene_;
    ReferenceSettings settings_;
    std::unique_ptr<EmbreeScene> embree_;
    std::vector<ObjectShading> objects_;
    glm::mat4 view_{1.0f};
    glm::mat4 projection_{1.0f};
    glm::dmat4 inverseViewProjection_{1.0};
    glm::vec3 cameraPosition_{0.0f};
    FrameLights lights_;
    double buildSeconds_ = 0.0;
    bool hasTransparency_ = false;  // some mesh's material is alphaMode BLEND
};

// Convenience: build, render, report.
ImageRgba8 renderReference(const Scene& scene, const ReferenceSettings& settings, ReferenceStats* stats = nullptr);

}  // namespace punctual::reference
