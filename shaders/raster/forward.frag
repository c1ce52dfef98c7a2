#version 450
// Forward shading: GGX metallic-roughness with the shared attenuation formulas (shading.h).
// Brute force: every spot, then every point light, in packed order. Later light-list sources
// (per-object, tiled, clustered) walk a subset in the same ascending order.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "shading.h"

layout(constant_id = PUNCTUAL_SPEC_TEXTURE_COUNT) const int TEXTURE_COUNT = 1;

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHTS) readonly buffer LightBlock { GpuPunctualLight lights[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_OBJECTS) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_MATERIALS) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(set = 0, binding = PUNCTUAL_BINDING_TEXTURES) uniform sampler2D baseColorTextures[TEXTURE_COUNT];
layout(push_constant) uniform DrawConstants { uint objectIndex; } draw;

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec4 outRadiance;

void main() {
    GpuObject object = objects[draw.objectIndex];
    GpuMaterial material = materials[object.material.x];
    vec4 baseColor = material.baseColorFactor;
    if (material.baseColorTexture >= 0) {
        baseColor *= texture(baseColorTextures[material.baseColorTexture], inUv);
    }

    // Faces are drawn two-sided; the normal is turned towards the viewer on back faces.
    // object.material.y marks mirrored transforms (negative determinant), whose winding flips.
    vec3 normal = normalize(inWorldNormal);
    bool frontFacing = gl_FrontFacing != (object.material.y != 0u);
    if (!frontFacing) normal = -normal;

    vec3 viewDir = normalize(frame.cameraPosition.xyz - inWorldPosition);
    Surface surface = makeSurface(inWorldPosition, normal, viewDir, baseColor.rgb,
                                  material.metallicRoughness.x, material.metallicRoughness.y);

    vec3 radiance = shadeDirectionalLight(surface, frame.sun);
    uint lightCount = frame.lightCounts.x + frame.lightCounts.y;
    for (uint i = 0u; i < lightCount; ++i) {
        radiance += shadePunctualLight(surface, lights[i], 1.0);
    }
    outRadiance = vec4(radiance, 1.0);
}
