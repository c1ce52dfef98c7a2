#version 450
// glTF alphaMode MASK for the depth-only passes: the depth prepass and every shadow caster pass
// (spot, point, cascades) drop the fragments whose alpha is below the material's cutoff, with the
// test the forward pass makes (materials.h). Only masked objects (and, in the shadow passes,
// clipped or dithered transparent ones) are drawn with it, so opaque depth passes keep their
// fragment-shader-free pipelines and the early depth test.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "materials.h"
#include "cascades.h"

// The depth prepass also culls the back faces of single-sided masked materials here (its opaque
// pipelines cull them in the rasteriser); shadow casters are two-sided (README, "Materials").
layout(constant_id = 0) const bool CULL_SINGLE_SIDED_BACK_FACES = false;
// Shadow casters of alphaMode BLEND materials (--transparent-shadows): clip at the cutoff the
// material carries (0.5 for BLEND), or, when dithering, keep a texel where alpha beats the seed's
// interleaved gradient noise (section 5.3: clip(alpha - dither)), so coverage follows alpha.
layout(constant_id = 1) const bool DITHER_TRANSPARENT = false;

layout(std430, set = 0, binding = PUNCTUAL_BINDING_OBJECTS) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_MATERIALS) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(set = 1, binding = 0) uniform sampler2D baseColorTexture;

// mesh.vert's interface, which shadow_masked.vert repeats: one fragment shader for both.
layout(location = 0) in vec3 inWorldPosition;  // unread
layout(location = 1) in vec3 inWorldNormal;    // unread
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec2 inUv1;
layout(location = 4) flat in uint inObject;

#include "texture_sampling.glsl"

void main() {
    GpuObject object = objects[inObject];
    GpuMaterial material = materials[object.material.x];
    if (CULL_SINGLE_SIDED_BACK_FACES && materialIsSingleSided(material) &&
        gl_FrontFacing == (object.material.y != 0u)) {
        discard;
    }
    float alpha = material.baseColorFactor.a *
                  sampleMaterialTexture(baseColorTexture, material.baseColorUv[0], material.baseColorUv[1]).a;
    bool dithered = DITHER_TRANSPARENT && (material.flags & PUNCTUAL_MATERIAL_ALPHA_BLEND) != 0u;
    float cutoff = dithered ? interleavedGradientNoise(gl_FragCoord.xy) : material.emission.w;
    if (!alphaMaskKeeps(alpha, cutoff)) discard;
}
