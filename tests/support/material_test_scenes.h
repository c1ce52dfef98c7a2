#pragma once
// Building blocks for the material and transparency tests' scenes (with study::addQuad): matte
// materials, checkerboard textures and a camera. CPU only, like everything in tests/support.
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual::testing {

// A dielectric of the given colour, roughness 0.8, single-sided and opaque.
Material matte(const std::string& name, glm::vec3 color);

// `side` x `side` texels in checks of `check` texels: opaque white where (x / check + y / check)
// is even, else `odd` (RGBA); with its mip chain.
Texture checkerTexture(uint32_t side, uint32_t check, glm::u8vec4 odd);

// The scene's camera at `eye` looking at `target` (y up), near 0.1 m, far 60 m.
void lookAt(Scene& scene, glm::vec3 eye, glm::vec3 target, float yfov = 1.0f);

}  // namespace punctual::testing
