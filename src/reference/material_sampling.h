#pragma once
// A material's textures on the CPU, as forward.frag and alpha_mask.frag read them: the texture
// coordinate set, KHR_texture_transform (shaders/shared/materials.h) and the level of detail
// from the pixel's footprint (texture_sampler.h).
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual::reference {

// Both texture coordinate sets at a surface point, with their derivatives across one pixel in
// x and in y (zero where unknown, which samples level 0).
struct SurfaceUv {
    glm::vec2 uv[2]{glm::vec2(0.0f), glm::vec2(0.0f)};
    glm::vec2 dx[2]{glm::vec2(0.0f), glm::vec2(0.0f)};
    glm::vec2 dy[2]{glm::vec2(0.0f), glm::vec2(0.0f)};
};

// The texture `ref` names, sampled at the point (linear RGBA); vec4(1) when there is none.
glm::vec4 sampleMaterialTexture(const Scene& scene, const TextureRef& ref, const SurfaceUv& at);

// The base colour's alpha (factor x texture) at level 0: the alpha mask test of rays without a
// footprint (shadow rays, and the primary ray's filter; README "Materials" on the difference).
float baseColorAlpha(const Scene& scene, const Material& material, glm::vec2 uv0, glm::vec2 uv1);

}  // namespace punctual::reference
