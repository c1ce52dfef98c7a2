#pragma once
// The forward shader's debug buffers, as bytes read back from the GPU, decoded on the CPU by the
// layouts gpu_types.h declares: the light statistics (WRITE_LIGHT_STATS) and the shadow factors
// (WRITE_SHADOW_FACTORS). CPU only, so their decoding is tested without a device
// (tests/unit/test_debug_buffers.cpp); the renderer reads the buffers and calls these.
#include <cstdint>
#include <vector>

#include "metrics/culling_stats.h"
#include "metrics/shadow_factor_image.h"

namespace punctual {

// The light statistics of a width x height frame whose method has `listCells` list cells of
// `gridWords` mask words each, from its buffer's bytes (at least lightStatsBytes of them).
LightStatsImage decodeLightStats(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height, uint32_t listCells,
                                 uint32_t gridWords);
uint64_t lightStatsBytes(uint32_t width, uint32_t height, uint32_t listCells, uint32_t gridWords);

// The shadow factors of a width x height frame with `slots` shadowed spot and point lights (and
// the sun's, in PUNCTUAL_SUN_SHADOW_SLOT, when `sun`), from its buffer's bytes (at least
// shadowFactorBytes(width, height)). Uncovered pixels read as not reached.
ShadowFactorImage decodeShadowFactors(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height,
                                      uint32_t slots, bool sun);
uint64_t shadowFactorBytes(uint32_t width, uint32_t height);

}  // namespace punctual
