// Compile-time checks that the C++ view of the shared GPU structs (shaders/shared/gpu_types.h)
// has exactly the std430/std140 layout GLSL gives them.
#include <cstddef>

#include "culling.h"
#include "gpu_types.h"

namespace punctual::gpu {

static_assert(sizeof(GpuPunctualLight) == 64);
static_assert(offsetof(GpuPunctualLight, radiantColor) == 16);
static_assert(offsetof(GpuPunctualLight, directionAngleScale) == 32);
static_assert(offsetof(GpuPunctualLight, angleOffsetShadow) == 48);

static_assert(sizeof(GpuDirectionalLight) == 32);
static_assert(offsetof(GpuDirectionalLight, illuminance) == 16);

static_assert(offsetof(GpuFrame, projection) == 64);
static_assert(offsetof(GpuFrame, viewProjection) == 128);
static_assert(offsetof(GpuFrame, inverseViewProjection) == 192);
static_assert(offsetof(GpuFrame, cameraPosition) == 256);
static_assert(offsetof(GpuFrame, viewport) == 272);
static_assert(offsetof(GpuFrame, spotCount) == 288);
static_assert(offsetof(GpuFrame, pointCount) == 292);
static_assert(offsetof(GpuFrame, directionalCount) == 296);
static_assert(offsetof(GpuFrame, transparentSpans) == 300);
static_assert(offsetof(GpuFrame, exposure) == 304);
static_assert(offsetof(GpuFrame, sun) == 320);
static_assert(offsetof(GpuFrame, lightGrid) == 352);
static_assert(offsetof(GpuFrame, depthToView) == 368);
static_assert(offsetof(GpuFrame, ndcToView) == 384);
static_assert(offsetof(GpuFrame, shadowBias) == 400);
static_assert(offsetof(GpuFrame, shadowAtlasSize) == 416);
static_assert(offsetof(GpuFrame, diskRadius) == 424);
static_assert(offsetof(GpuFrame, shadowDepthQuantum) == 428);
static_assert(offsetof(GpuFrame, shadowCounts) == 432);
static_assert(offsetof(GpuFrame, sunShadow) == 448);
static_assert(offsetof(GpuFrame, sunShadowFade) == 464);
static_assert(offsetof(GpuFrame, cascadeSpheres) == 480);
static_assert(offsetof(GpuFrame, shadowPageNeed) == 480 + 16 * PUNCTUAL_MAX_CASCADES);
static_assert(offsetof(GpuFrame, shadowPagePool) == 496 + 16 * PUNCTUAL_MAX_CASCADES);
static_assert(offsetof(GpuFrame, shadowPageSlots) == 512 + 16 * PUNCTUAL_MAX_CASCADES);
static_assert(sizeof(GpuFrame) == 528 + 16 * PUNCTUAL_MAX_CASCADES);

static_assert(sizeof(GpuVirtualShadowView) == 16 + 16 * PUNCTUAL_VIRTUAL_SHADOW_LEVELS);
static_assert(offsetof(GpuVirtualShadowView, levels) == 16);
static_assert(virtualShadowLevels(PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_PAGE) ==
              PUNCTUAL_VIRTUAL_SHADOW_LEVELS);

static_assert(sizeof(GpuShadowView) == 112);
static_assert(offsetof(GpuShadowView, params) == 64);
static_assert(offsetof(GpuShadowView, atlasRect) == 80);
static_assert(offsetof(GpuShadowView, texel) == 96);

// The slices' lights follow the header as a uint array: at its size, a multiple of 4.
static_assert(sizeof(GpuDepthRange) == 16 + 4 * PUNCTUAL_MAX_CLUSTER_SLICES);
static_assert(offsetof(GpuDepthRange, sliceStartDepth) == 16);
// The bins' masks follow the header as a uint array.
static_assert(sizeof(GpuZBins) == 4 * PUNCTUAL_ZBIN_COUNT + 4 * PUNCTUAL_ZBIN_COUNT);
static_assert(offsetof(GpuZBins, binRange) == 4 * PUNCTUAL_ZBIN_COUNT);
// A z-bin's range holds 16-bit indices of the depth-sorted lights.
static_assert(2 * PUNCTUAL_MAX_LIGHT_CAPACITY <= 0x10000);

// CullLight (culling.h) is read from a std430 buffer: each vec3 + float pair packs into 16 bytes.
static_assert(sizeof(CullLight) == 48);
static_assert(offsetof(CullLight, axis) == 16);
static_assert(offsetof(CullLight, cosOuter) == 28);
static_assert(offsetof(CullLight, sphereCenter) == 32);
static_assert(offsetof(CullLight, sphereRadius) == 44);

static_assert(sizeof(GpuObject) == 144);
static_assert(offsetof(GpuObject, normalMatrix) == 64);
static_assert(offsetof(GpuObject, material) == 128);

static_assert(sizeof(GpuMaterial) == 128);
static_assert(offsetof(GpuMaterial, emission) == 16);
static_assert(offsetof(GpuMaterial, baseColorUv) == 32);
static_assert(offsetof(GpuMaterial, emissiveUv) == 64);
static_assert(offsetof(GpuMaterial, metallicRoughness) == 96);
static_assert(offsetof(GpuMaterial, baseColorTexture) == 104);
static_assert(offsetof(GpuMaterial, flags) == 108);
static_assert(offsetof(GpuMaterial, emissiveTexture) == 112);

// The light statistics buffer: the list block's words fit a pixel's, the covered bit leaves room
// for every light a frame can hold, and the work word for every shadowed light's lookups.
static_assert(PUNCTUAL_LIGHT_STATS_LIST_TESTED < PUNCTUAL_LIGHT_STATS_PIXEL_WORDS);
static_assert(PUNCTUAL_LIGHT_STATS_LIST < PUNCTUAL_LIGHT_STATS_BLOCKS);
static_assert(2 * PUNCTUAL_MAX_LIGHT_CAPACITY < PUNCTUAL_LIGHT_STATS_COVERED);
static_assert(PUNCTUAL_MAX_SHADOWED_SPOT_LIGHTS + PUNCTUAL_MAX_SHADOWED_POINT_LIGHTS + 2 < (1u << PUNCTUAL_STATS_LOOKUP_BITS));

}  // namespace punctual::gpu
