#pragma once
// What a shadow view's depth is made of, as one number (--shadow-cache on, issue 34): two frames
// whose view has the same signature draw the same depth into it, texel for texel, so the second
// may keep the first's (render/shadow_cache.h).
//
// A view's depth is a function of its matrix, its side and its casters: which objects, in which
// order (the depth test keeps the nearest, but a masked caster's alpha test and equal depths make
// order matter no less than membership), and what each is: its model matrix, its mesh's vertices
// and indices, and its material's alpha test. The pipelines and the depth format are the
// sequence's settings, the same every frame. Textures are not in it: glTF animates nodes and
// weights, never an image, so a texture that alpha-tests a caster is the same every frame.
//
// 64-bit FNV-1a over 8-byte words (as vk/object_cache.h keys shaders): two different views
// would have to collide in 64 bits for a cached view to be kept wrongly; the GPU test compares
// whole sequences cached and uncached, bit for bit.
#include <cstdint>
#include <vector>

#include "lights/shadow_setup.h"
#include "scene/scene.h"

namespace punctual {

// Per object of `scene`: its caster fingerprint where some view of `plan` draws it, else 0 (the
// others are not read, and at 10^7 triangles hashing every mesh each frame would cost seconds).
std::vector<uint64_t> casterFingerprints(const Scene& scene, const ShadowPlan& plan);

// The view's signature: its matrix, its side and its casters' fingerprints in draw order.
uint64_t shadowViewSignature(const ShadowView& view, const std::vector<uint64_t>& fingerprints);
// The same over `casters` (some of the view's, in its order) in place of all of them: what the
// view's depth of those casters alone is made of (the static casters' kept depth of mixed
// caching, render/shadow_cache.h).
uint64_t shadowViewSignature(const ShadowView& view, const std::vector<uint32_t>& casters,
                             const std::vector<uint64_t>& fingerprints);

// A virtual page's signature (--shadow-res virtual): its view's matrix, its level and place, and the
// casters that meet it (shadowPageCasters, in the view's order): what the page's depth is made of.
uint64_t shadowPageSignature(const ShadowView& view, uint32_t level, uint32_t column, uint32_t row,
                             const std::vector<uint32_t>& casters, const std::vector<uint64_t>& fingerprints);

}  // namespace punctual
