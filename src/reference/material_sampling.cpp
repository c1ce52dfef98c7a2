#include "reference/material_sampling.h"

#include "materials.h"
#include "reference/texture_sampler.h"

namespace punctual::reference {
namespace {

struct TransformRows {
    glm::vec4 u;
    glm::vec4 v;
};

TransformRows rowsOf(const TextureRef& ref) {
    const TextureTransform& t = ref.transform;
    return {glm::vec4(gpu::textureTransformRowU(t.offset, t.rotation, t.scale), float(ref.texCoord)),
            glm::vec4(gpu::textureTransformRowV(t.offset, t.rotation, t.scale), 0.0f)};
}


}  // namespace

glm::vec4 sampleMaterialTexture(const Scene& scene, const TextureRef& ref, const SurfaceUv& at) {
    if (!ref.present() || size_t(ref.image) >= scene.textures.size()) return glm::vec4(1.0f);
    const Texture& texture = scene.textures[size_t(ref.image)];
    const TransformRows rows = rowsOf(ref);
    const uint32_t set = ref.texCoord > 0 ? 1 : 0;
    const glm::vec2 uv = gpu::materialUv(rows.u, rows.v, at.uv[0], at.uv[1]);
    const float lod = textureLod(texture, gpu::materialUvDerivative(rows.u, rows.v, at.dx[set]),
                                 gpu::materialUvDerivative(rows.u, rows.v, at.dy[set]));
    return sampleTexture(texture, ref.sampler, uv, lod);
}

float baseColorAlpha(const Scene& scene, const Material& material, glm::vec2 uv0, glm::vec2 uv1) {
    SurfaceUv at;
    at.uv[0] = uv0;
    at.uv[1] = uv1;
    return material.baseColorFactor.a * sampleMaterialTexture(scene, material.baseColorTexture, at).a;
}

}  // namespace punctual::reference
