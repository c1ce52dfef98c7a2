// A material texture read at the pixel's level of detail, for forward.frag and alpha_mask.frag.
// GLSL only (it samples and differentiates); include after materials.h, in a shader with the
// inputs inUv and inUv1 (mesh.vert's interface).
//
// The level comes from the fine derivatives of the texture's coordinate set, through its
// transform's linear part (materialUvDerivative) and isotropicLod (materials.h): the formula
// the CPU reference uses. It is passed to textureLod clamped at 0: Vulkan takes lambda <= 0 as
// magnification of level 0, so the clamp changes no result on any device. Both choices are
// there for lavapipe (Mesa 22.3): with texture() on the transformed coordinates it sampled a
// wrong mip level (the 1x1 one) at some pixels of 2x2 quads straddling a triangle edge, grey
// dots along a magnified quad's diagonal (ReferenceImage.MatchesGpuOnATexturedGltfQuadUnderTheSun);
// textureGrad and a negative textureLod did the same, while each pixel's own coordinates and the
// derivatives of the untransformed set were smooth there.
vec4 sampleMaterialTexture(sampler2D tex, vec4 rowU, vec4 rowV) {
    bool second = rowU.w > 0.5;
    vec2 dx = materialUvDerivative(rowU, rowV, second ? dFdxFine(inUv1) : dFdxFine(inUv));
    vec2 dy = materialUvDerivative(rowU, rowV, second ? dFdyFine(inUv1) : dFdyFine(inUv));
    float lod = isotropicLod(dx, dy, vec2(textureSize(tex, 0)));
    return textureLod(tex, materialUv(rowU, rowV, inUv, inUv1), max(lod, 0.0));
}
