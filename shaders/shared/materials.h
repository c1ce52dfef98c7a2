// Material inputs shared by the GPU passes and the CPU reference: texture coordinates through
// KHR_texture_transform, glTF's alpha mask test, and emission. Everything a material reads before
// the lights are summed (shading.h) lives here, once.
#ifndef PUNCTUAL_MATERIALS_H
#define PUNCTUAL_MATERIALS_H

#include "glsl_cpp.h"
#include "gpu_types.h"

PUNCTUAL_NAMESPACE_BEGIN

// KHR_texture_transform builds uv' = T * R * S * uv from
//   T = [1 0 ox; 0 1 oy; 0 0 1],  R = [c s 0; -s c 0; 0 0 1],  S = [sx 0 0; 0 sy 0; 0 0 1]
// (rows; c = cos(rotation), s = sin(rotation); the extension's R turns UV space, whose v axis
// points down the image, so a positive rotation looks counter-clockwise on the image). Multiplied
// out, the two rows that matter are
//   u' =  c sx u + s sy v + ox
//   v' = -s sx u + c sy v + oy.
PUNCTUAL_FN vec3 textureTransformRowU(vec2 offset, float rotation, vec2 scale) {
    return vec3(cos(rotation) * scale.x, sin(rotation) * scale.y, offset.x);
}
PUNCTUAL_FN vec3 textureTransformRowV(vec2 offset, float rotation, vec2 scale) {
    return vec3(-sin(rotation) * scale.x, cos(rotation) * scale.y, offset.y);
}

// A texture's coordinates: the set its row U's w names (0: TEXCOORD_0, 1: TEXCOORD_1), through
// its transform rows (GpuMaterial::baseColorUv, emissiveUv). The identity transform is exact:
// 1 * u + 0 * v + 0 == u in floating point.
PUNCTUAL_FN vec2 materialUv(vec4 rowU, vec4 rowV, vec2 uv0, vec2 uv1) {
    vec2 uv = rowU.w > 0.5f ? uv1 : uv0;
    return vec2(rowU.x * uv.x + rowU.y * uv.y + rowU.z, rowV.x * uv.x + rowV.y * uv.y + rowV.z);
}

// The level of detail Vulkan's isotropic rule gives a texture of `size` texels whose coordinates
// change by `dx` and `dy` across one pixel (spec "Scale Factor Operation", rho = max of the two
// footprint lengths, lambda = log2(rho)): the GPU passes it to textureLod (texture_sampling.glsl)
// and the reference samples with it (reference/texture_sampler.h). -inf for a zero footprint.
PUNCTUAL_FN float isotropicLod(vec2 dx, vec2 dy, vec2 size) {
    return log2(max(length(dx * size), length(dy * size)));
}

// How a texture's coordinates change across one pixel, from the change `d` of the set it reads:
// the transform's linear part (the offset does not move with the pixel). Differentiating the
// set's own coordinates and transforming the result, rather than differentiating the transformed
// coordinates, keeps a 0 x (something not finite) in a helper lane out of the result.
PUNCTUAL_FN vec2 materialUvDerivative(vec4 rowU, vec4 rowV, vec2 d) {
    return vec2(rowU.x * d.x + rowU.y * d.y, rowV.x * d.x + rowV.y * d.y);
}

// glTF alphaMode MASK: "rendered fully opaque if alpha >= alphaCutoff, fully transparent
// otherwise". alpha = baseColorFactor.a x the base-colour texture's alpha.
PUNCTUAL_FN bool alphaMaskKeeps(float alpha, float cutoff) { return alpha >= cutoff; }

PUNCTUAL_FN bool materialIsMasked(GpuMaterial material) { return (material.flags & PUNCTUAL_MATERIAL_ALPHA_MASK) != 0u; }
PUNCTUAL_FN bool materialIsSingleSided(GpuMaterial material) {
    return (material.flags & PUNCTUAL_MATERIAL_SINGLE_SIDED) != 0u;
}

PUNCTUAL_NAMESPACE_END

#endif
