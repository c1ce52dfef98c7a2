#version 450
// Forward shading: GGX metallic-roughness with the shared attenuation formulas (shading.h).
// The light list is chosen by specialization constant, one shader for every method:
//   brute       every spot, then every point light, in packed order;
//   per-object  the object's (at most 8) lights, ascending;
//   tiled       the set bits of the pixel's tile masks, ascending;
//   tiled-2.5d  the same, the masks also pruned by the tile's depth cells (light_culling.comp);
//   zbin        the set bits of the tile's masks AND its z-bin's, ascending;
//   zbin-2d     the same, the tile's masks two-dimensional (built without depth);
//   clustered   the set bits of the pixel's cluster masks, ascending.
// All walk lights in the same ascending order and a light beyond its range adds exactly 0, so
// tiled and clustered images are bit-identical to brute force. The methods reach this shader as
// their table rows' parameters (src/render/light_list_method.h): the list's source (LIGHT_SOURCE:
// every light, the object's list, the grid cell's masks, or those AND the z-bin's) and the grid's
// slices; the culling kernels get their flags. A shadow filter is its kernel and size
// (shadow_kernels.h). Every variant value (light source, shadow kernel, point-shadow layout,
// cascade blend) has its explicit case; a value without one (a C++ table entry whose shader case
// is missing) shades magenta wherever it is used (every pixel for a light source, every shadow
// lookup for a kernel or layout) instead of passing for another variant.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
// Set by the default case of every variant switch: the pipeline's specialization value has no
// case here. Constant false for every known value, so it costs nothing. (Declared before the
// includes: shadow_kernels.h's GLSL part sets it.)
bool unknownVariant = false;

#include "gpu_types.h"
#include "shading.h"
#include "culling.h"
#include "shadows.h"
#include "shadow_kernels.h"
#include "cascades.h"
#include "materials.h"

// Depth test before shading: only the visible fragment of each pixel runs (EQUAL against the
// prepass). Without it, the statistics variant's buffer writes would make drivers test depth late
// and let hidden fragments write statistics too.
layout(early_fragment_tests) in;

layout(constant_id = PUNCTUAL_SPEC_LIGHT_SOURCE) const uint LIGHT_SOURCE = PUNCTUAL_LIGHT_SOURCE_ALL;
layout(constant_id = PUNCTUAL_SPEC_TILE_SIZE) const uint TILE_SIZE = 16u;
layout(constant_id = PUNCTUAL_SPEC_SLICE_COUNT) const uint SLICE_COUNT = 1u;
layout(constant_id = PUNCTUAL_SPEC_GRID_WORDS) const uint GRID_WORDS = 3u;  // words a light-grid cell
// How a cell holds its lights (culling.h): GRID_WORDS mask words, or a header word and an index list.
layout(constant_id = PUNCTUAL_SPEC_LIGHT_LIST_FORM) const uint LIGHT_LIST_FORM = PUNCTUAL_LIGHT_LIST_MASKS;
// Debug variant for statistics and heat maps: also counts, per pixel, the lights that really
// reach it and the brute-force radiance, into lightStats. Never used for timing.
layout(constant_id = PUNCTUAL_SPEC_WRITE_LIGHT_STATS) const bool WRITE_LIGHT_STATS = false;
layout(constant_id = PUNCTUAL_SPEC_SHADOWS) const bool SHADOWS = false;
layout(constant_id = PUNCTUAL_SPEC_SHADOW_KERNEL) const uint SHADOW_KERNEL = PUNCTUAL_SHADOW_KERNEL_TENT;
layout(constant_id = PUNCTUAL_SPEC_SHADOW_FILTER_SIZE) const uint SHADOW_FILTER_SIZE = 5u;
layout(constant_id = PUNCTUAL_SPEC_SHADOW_SAMPLES) const uint SHADOW_SAMPLES = 16u;
layout(constant_id = PUNCTUAL_SPEC_POINT_SHADOW_LAYOUT) const uint POINT_SHADOW_LAYOUT = PUNCTUAL_POINT_SHADOW_CUBE;
// Validation variant: also writes this pixel's surface and every shadowed light's shadow factor
// into shadowDebug, for comparison with ray-traced visibility. Never used for timing.
layout(constant_id = PUNCTUAL_SPEC_WRITE_SHADOW_FACTORS) const bool WRITE_SHADOW_FACTORS = false;
layout(constant_id = PUNCTUAL_SPEC_SHADOW_RECEIVER_PLANE) const bool SHADOW_RECEIVER_PLANE = true;
layout(constant_id = PUNCTUAL_SPEC_CASCADE_BLEND) const uint CASCADE_BLEND = PUNCTUAL_CASCADE_BLEND_HARD;
// The transparent pass: alphaMode BLEND surfaces, written with their base colour's alpha for the
// pipeline's "over" blending; the opaque pass writes alpha 1.
layout(constant_id = PUNCTUAL_SPEC_TRANSPARENT) const bool TRANSPARENT = false;
// Spot and point shadows from each view's square of the atlas, or from virtual pages; or the
// marking pass, which shades nothing and marks the pages its lookups will read (shadow_pages.glsl).
layout(constant_id = PUNCTUAL_SPEC_SHADOW_PAGES) const uint SHADOW_PAGES = PUNCTUAL_SHADOW_PAGES_OFF;

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHTS) readonly buffer LightBlock { GpuPunctualLight lights[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_OBJECTS) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_MATERIALS) readonly buffer MaterialBlock { GpuMaterial materials[]; };
// The draw's base-colour and emissive textures (a white texel where its material has none), in
// set 1, bound per material. One set per material instead of an array indexed per draw: lavapipe
// (Mesa 22.3) moves dynamically indexed samplers into out-of-line functions whose code LLVM 15
// fails to compile for array textures, the shadow maps.
layout(set = 1, binding = 0) uniform sampler2D baseColorTexture;
layout(set = 1, binding = 1) uniform sampler2D emissiveTexture;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHT_GRID) readonly buffer GridBlock { uint lightGrid[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_DEPTH_RANGE) readonly buffer DepthRangeBlock { GpuDepthRange depthRange; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_OBJECT_LIGHTS) readonly buffer ObjectLightBlock { uint objectLights[]; };
// After the bins' ranges, each bin's mask (GRID_WORDS words a bin) or, with index lists, each
// light's 16-bit rank in depth order (lights/z_bins.h).
layout(std430, set = 0, binding = PUNCTUAL_BINDING_ZBINS) readonly buffer ZBinBlock { GpuZBins zBins; uint zBinWords[]; };
// Index lists: the words the culling kernels used, then the cells' lists (culling.h).
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHT_INDICES) readonly buffer LightIndexBlock {
    uint lightIndexWordsUsed;
    uint lightIndexWords[];
};
// Four words per pixel for the opaque surface, then four per pixel for its transparent fragments
// (gpu_types.h): several of those may land on one pixel, so they add up atomically.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHT_STATS) buffer LightStatsBlock { uint lightStatWords[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_VIEWS) readonly buffer ShadowViewBlock { GpuShadowView shadowViews[]; };
layout(set = 0, binding = PUNCTUAL_BINDING_SHADOW_ATLAS_DEPTH) uniform sampler2D shadowAtlasDepth;
layout(set = 0, binding = PUNCTUAL_BINDING_POINT_SHADOWS) uniform samplerCubeArrayShadow pointShadows;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_DEBUG) writeonly buffer ShadowDebugBlock { uint shadowDebug[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_PAGE_VIEWS) readonly buffer PageViewBlock { GpuVirtualShadowView virtualViews[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_PAGE_TABLE) readonly buffer PageTableBlock { uint pageTable[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_PAGE_MARKS) buffer PageMarkBlock { uint pageMarks[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_PREVIOUS_PAGE_MARKS) readonly buffer PreviousPageMarkBlock {
    uint previousPageMarks[];
};
layout(push_constant) uniform DrawConstants { uint objectIndex; } draw;

// Validation variant: the bytes of this pixel's shadow factors, all "not reached" to start.
uint shadowFactorWords[PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS];

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec2 inUv1;
layout(location = 4) flat in uint inObject;  // unread here (draw.objectIndex is): mesh.vert's full interface

layout(location = 0) out vec4 outRadiance;

const vec3 kUnknownVariantRadiance = vec3(1.0e4, 0.0, 1.0e4);  // saturates to magenta

// The light-grid cell of this pixel (tiled and clustered): cell = tile index x SLICE_COUNT +
// the pixel's depth slice (culling.h: the culling kernel's search, so both pick the same slice).
// Tiled grids are the one-slice case: SLICE_COUNT = 1, every depth in slice 0.
uint pixelGridCell() {
    uvec2 tile = uvec2(gl_FragCoord.xy) / TILE_SIZE;
    uint slice;
    PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(slice, gl_FragCoord.z, depthRange.sliceStartDepth, SLICE_COUNT);
    return (tile.y * frame.lightGrid.y + tile.x) * SLICE_COUNT + slice;
}

// Statistics variant: the list this pixel's method gives it is a function of one key, its list
// cell: the whole screen (brute), the object (per-object), the tile (tiled, tiled-2.5d), the
// cluster (clustered), or the tile and z-bin (zbin, zbin-2d). Exact lists per such cell (each the
// lights reaching any of its pixels) are the best any culler of that granularity can do: the
// statistics compare each method with them (metrics/culling_stats.h, floor efficiency).
uint pixelListCell() {
    // (Not a switch on LIGHT_SOURCE: that is the shading switch's, which must list every source.)
    if (LIGHT_SOURCE == PUNCTUAL_LIGHT_SOURCE_OBJECT) return draw.objectIndex;
    if (LIGHT_SOURCE == PUNCTUAL_LIGHT_SOURCE_GRID) return pixelGridCell();
    if (LIGHT_SOURCE == PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS) {
        uint bin;
        PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(bin, gl_FragCoord.z, zBins.binStartDepth, PUNCTUAL_ZBIN_COUNT);
        return pixelGridCell() * PUNCTUAL_ZBIN_COUNT + bin;
    }
    return 0u;  // brute force: one list for the screen
}

// Statistics variant: the shadow-map lookups and texture taps this pixel has taken so far
// (gpu_types.h, packPixelWork); the sampling functions count each filtered read they make.
uint shadowLookups = 0u;
uint shadowTaps = 0u;
void countShadowLookup(uint taps) {
    if (WRITE_LIGHT_STATS) {
        shadowLookups += 1u;
        shadowTaps += taps;
    }
}

#include "shadow_pages.glsl"
#include "shadow_sampling.glsl"
#include "texture_sampling.glsl"

// Validation variant: the cascade the sun's shadow read at this pixel, plus one (0: none).
uint sunCascadeWord = 0u;

// Writes `shadow` into this pixel's factor byte `slot` (validation variant).
void recordShadowFactor(uint slot, float shadow) {
    uint shift = (slot & 3u) * 8u;
    uint quantised = uint(round(clamp(shadow, 0.0, 1.0) * 254.0));
    shadowFactorWords[slot >> 2u] = (shadowFactorWords[slot >> 2u] & ~(0xFFu << shift)) | (quantised << shift);
}

// One light's contribution, with its shadow where it casts one and reaches this point. The lookup
// is skipped where the light has no shadow and wherever the shadow cannot change the result:
// where the attenuation is zero, and where the surface faces away from the light (facesLight, the
// test shadeBrdf makes on the same normal and direction, so its result is 0 whatever the shadow
// and the image stays bit-identical). The validation variant then leaves the light's factor
// "not reached", as validation skips such pixels too.
vec3 shadeLight(Surface surface, GpuPunctualLight light) {
    LightSample arrival = sampleLight(light, surface.position);
    float shadow = 1.0;
    if (SHADOWS && arrival.attenuation > 0.0 && light.angleOffsetShadow.y >= 0.0 &&
        facesLight(surface, arrival.toLight)) {
        if (SHADOW_PAGES == PUNCTUAL_SHADOW_PAGES_MARK) {
            markShadowPages(light, arrival.toLight, surface.position, surface.normal);
            return vec3(0.0);
        }
        shadow = shadowVisibility(light, arrival.toLight, surface.position, surface.normal);
        if (WRITE_SHADOW_FACTORS) {
            recordShadowFactor(shadowSlot(uint(light.angleOffsetShadow.y), frame.shadowCounts.x), shadow);
        }
    }
    return shadeLightSample(surface, light, arrival, shadow);
}

// The sun, with its cascaded shadow where it has one; skipped, as for punctual lights, where the
// surface faces away from it.
vec3 shadeSun(Surface surface) {
    if (SHADOW_PAGES == PUNCTUAL_SHADOW_PAGES_MARK) return vec3(0.0);  // the cascades stay whole: no pages
    float shadow = 1.0;
    if (SHADOWS && frame.sunShadow.y > 0u && facesLight(surface, frame.sun.directionToLight.xyz)) {
        uint cascade;
        shadow = sunVisibility(surface.position, surface.normal, cascade);
        if (WRITE_SHADOW_FACTORS) {
            recordShadowFactor(PUNCTUAL_SUN_SHADOW_SLOT, shadow);
            sunCascadeWord = cascade < frame.sunShadow.y ? cascade + 1u : 0u;
        }
    }
    return shadeDirectionalLight(surface, frame.sun) * shadow;
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// ---- the steps of main, in order ------------------------------------------------------------------
// Functions cost nothing here (drivers inline them, and none takes an array). The radiance stays
// in main: it is `precise`, so that every method adds its lights in the same order and
// association and the images stay bit-identical, which a parameter would not promise.

// The fragment's base colour and emission. Both textures are sampled before any fragment of the
// quad is discarded: implicit derivatives are undefined once the quad's control flow diverges.
void sampleMaterial(GpuMaterial material, out vec4 baseColor, out vec3 emission) {
    baseColor = material.baseColorFactor;
    if (material.baseColorTexture >= 0)
        baseColor *= sampleMaterialTexture(baseColorTexture, material.baseColorUv[0], material.baseColorUv[1]);
    emission = material.emission.rgb;
    if (material.emissiveTexture >= 0)
        emission *= sampleMaterialTexture(emissiveTexture, material.emissiveUv[0], material.emissiveUv[1]).rgb;
}

// The prepass drew neither a single-sided material's back faces nor masked-out fragments, so
// these fail the EQUAL test already unless another surface lies at exactly their depth; the tests
// make the forward pass agree with the prepass by construction.
void discardWhatThePrepassDropped(GpuMaterial material, bool frontFacing, float alpha) {
    if (materialIsSingleSided(material) && !frontFacing) discard;
    if (materialIsMasked(material) && !alphaMaskKeeps(alpha, material.emission.w)) discard;
}

// The grid sources' lights: the set bits of this pixel's cell (tiled, clustered, tiled-2.5d),
// with GRID_ZBINS (zbin, zbin-2d; URP Forward+ / Drobot) ANDed with the mask of the pixel's z-bin
// (lights/z_bins.h), found by the stored-start search the CPU binned with. The walk reads them
// three words at a time (a triple; words past GRID_WORDS read as 0). (Clustered: walking the
// tile's union of its clusters instead, testing membership per pixel, keeps SIMD lanes uniform but
// measured 10% slower on lavapipe; see bench/RESULTS.md.) With index lists the cell is one header
// word and the walk reads its list (PUNCTUAL_WALK_INDEX_LIST).
struct CellWords {
    uint cellBase;  // the pixel's cell's first word in lightGrid (index lists: its header)
    uint bin;       // GRID_ZBINS: its z-bin
    uint binBase;   // GRID_ZBINS with masks: its z-bin's first word in zBinWords
};

CellWords pixelCellWords() {
    uint bin = 0u;
    if (LIGHT_SOURCE == PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS) {
        PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(bin, gl_FragCoord.z, zBins.binStartDepth, PUNCTUAL_ZBIN_COUNT);
    }
    uint cellWords = LIGHT_LIST_FORM == PUNCTUAL_LIGHT_LIST_INDICES ? 1u : GRID_WORDS;
    return CellWords(pixelGridCell() * cellWords, bin, bin * GRID_WORDS);
}

uint cellWord(CellWords cell, uint word) {
    if (word >= GRID_WORDS) return 0u;
    uint bits = lightGrid[cell.cellBase + word];
    return LIGHT_SOURCE == PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS ? bits & zBinWords[cell.binBase + word] : bits;
}

// Index lists: whether light `light` of the cell's list is in the pixel's z-bin (GRID_ZBINS): its
// rank in depth order within the bin's range of ranks, the test its mask bit stands for.
bool zBinHolds(CellWords cell, uint light) {
    if (LIGHT_SOURCE != PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS) return true;
    uint rank = lightListEntry(zBinWords[light / 2u], light);
    uint range = zBins.binRange[cell.bin];
    return rank >= (range & 0xFFFFu) && rank <= (range >> 16u);
}

uvec3 cellWordTriple(CellWords cell, uint triple) {
    return uvec3(cellWord(cell, 3u * triple), cellWord(cell, 3u * triple + 1u), cellWord(cell, 3u * triple + 2u));
}

// The walk of one triple of `cell`'s words, adding each light's radiance to main's `radiance` and
// counting it in `tested`: a macro, not a function, so that the sum stays main's `precise` one
// (the order and association of brute force's loop, which keeps every method bit-identical).
#define PUNCTUAL_WALK_WORD_TRIPLE(triple)                                                                       \
    {                                                                                                           \
        uvec3 words = cellWordTriple(cell, triple);                                                             \
        while ((words.x | words.y | words.z) != 0u) {                                                           \
            uint word = words.x != 0u ? 0u : (words.y != 0u ? 1u : 2u);                                         \
            uint bits = word == 0u ? words.x : (word == 1u ? words.y : words.z);                                \
            uint light = lightGridFirstLight(3u * (triple) + word) + uint(findLSB(bits));                       \
            bits &= bits - 1u; /* clear the lowest set bit: ascending order */                                  \
            words = uvec3(word == 0u ? bits : words.x, word == 1u ? bits : words.y, word == 2u ? bits : words.z); \
            radiance += shadeLight(surface, lights[light]);                                                     \
            ++tested;                                                                                           \
        }                                                                                                       \
    }

// The walk of the cell's index list (culling.h), entries 1 .. count in order, adding each light of
// the pixel's z-bin (zBinHolds) to main's `radiance` as the mask walk does (a macro for the same
// reason). A list that did not fit the index array (never, once the renderer has sized it) shades
// magenta, as an unknown variant does.
#define PUNCTUAL_WALK_INDEX_LIST()                                                              \
    {                                                                                           \
        uint start = lightGrid[cell.cellBase];                                                  \
        if (start == PUNCTUAL_LIGHT_LIST_OVERFLOW) unknownVariant = true;                       \
        uint count = start < PUNCTUAL_LIGHT_LIST_OVERFLOW ? lightListEntry(lightIndexWords[start], 0u) : 0u; \
        for (uint entry = 1u; entry <= count; ++entry) {                                        \
            uint light = lightListEntry(lightIndexWords[start + entry / 2u], entry);            \
            if (zBinHolds(cell, light)) {                                                       \
                radiance += shadeLight(surface, lights[light]);                                 \
                ++tested;                                                                       \
            }                                                                                   \
        }                                                                                       \
    }

// Validation variant: this pixel's surface (position, normal, the sun's cascade) and the shadow
// factors its lights recorded.
void writeShadowFactors(vec3 normal) {
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    uint index = pixel.y * uint(frame.viewport.x) + pixel.x;
    uint base = index * PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS;
    shadowDebug[base + 0u] = floatBitsToUint(inWorldPosition.x);
    shadowDebug[base + 1u] = floatBitsToUint(inWorldPosition.y);
    shadowDebug[base + 2u] = floatBitsToUint(inWorldPosition.z);
    shadowDebug[base + 3u] = 1u;
    shadowDebug[base + 4u] = floatBitsToUint(normal.x);
    shadowDebug[base + 5u] = floatBitsToUint(normal.y);
    shadowDebug[base + 6u] = floatBitsToUint(normal.z);
    shadowDebug[base + 7u] = sunCascadeWord;
    uint factorBase = uint(frame.viewport.x * frame.viewport.y) * PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS +
                      index * PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS;
    for (uint i = 0u; i < PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS; ++i) shadowDebug[factorBase + i] = shadowFactorWords[i];
}

// Statistics variant: the lights the method tested (`tested`), the shadow lookups and taps, the
// lights really reaching the pixel and the brute-force radiance, against the method's `radiance`.
void writeLightStats(Surface surface, vec3 radiance, vec3 emission, uint tested) {
    uint lightCount = frame.spotCount + frame.pointCount;
    // The method's own lookups, before the brute-force radiance below takes its own.
    uint work = packPixelWork(shadowLookups, shadowTaps);
    uint affecting = 0u;
    // The opaque surface's reaching lights go into its list cell's union (the exact-list floor),
    // a word at a time: `reachingBits` holds those of word `reachingWord` (lightGridWord).
    uint pixels = uint(frame.viewport.x * frame.viewport.y);
    uint listCell = TRANSPARENT ? 0u : pixelListCell();
    uint cellBase = lightStatsCellWord(pixels, GRID_WORDS, listCell, 0u);
    uint reachingWord = 0u;
    uint reachingBits = 0u;
    vec3 bruteRadiance = shadeSun(surface);
    for (uint i = 0u; i < lightCount; ++i) {
        if (punctualAttenuation(lights[i], inWorldPosition) > 0.0) {
            ++affecting;
            if (!TRANSPARENT && lightGridWord(i) != reachingWord) {
                if (reachingBits != 0u) atomicOr(lightStatWords[cellBase + reachingWord], reachingBits);
                reachingWord = lightGridWord(i);
                reachingBits = 0u;
            }
            reachingBits |= 1u << lightGridBit(i);
        }
        bruteRadiance += shadeLight(surface, lights[i]);
    }
    if (!TRANSPARENT && reachingBits != 0u) atomicOr(lightStatWords[cellBase + reachingWord], reachingBits);
    bruteRadiance += emission;
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    uint index = pixel.y * uint(frame.viewport.x) + pixel.x;
    if (TRANSPARENT) {
        uint base = lightStatsWord(PUNCTUAL_LIGHT_STATS_TRANSPARENT, pixels, index, 0u);
        atomicAdd(lightStatWords[base + PUNCTUAL_LIGHT_STATS_TESTED], tested);
        atomicAdd(lightStatWords[base + PUNCTUAL_LIGHT_STATS_REACHING], affecting);
        atomicAdd(lightStatWords[base + PUNCTUAL_LIGHT_STATS_FRAGMENTS], 1u);
        // Light went missing: the statistics' own test (culling_stats.cpp), per fragment.
        if (luminance(radiance) < luminance(bruteRadiance) * (1.0 - 1e-6)) {
            atomicAdd(lightStatWords[base + PUNCTUAL_LIGHT_STATS_MISSING], 1u);
        }
    } else {
        uint base = lightStatsWord(PUNCTUAL_LIGHT_STATS_OPAQUE, pixels, index, 0u);
        lightStatWords[base + PUNCTUAL_LIGHT_STATS_WORK] = work;
        lightStatWords[base + PUNCTUAL_LIGHT_STATS_REACHING] = affecting | PUNCTUAL_LIGHT_STATS_COVERED;
        lightStatWords[base + PUNCTUAL_LIGHT_STATS_LUMINANCE] = floatBitsToUint(luminance(radiance));
        lightStatWords[base + PUNCTUAL_LIGHT_STATS_BRUTE_LUMINANCE] = floatBitsToUint(luminance(bruteRadiance));
        uint list = lightStatsWord(PUNCTUAL_LIGHT_STATS_LIST, pixels, index, 0u);
        lightStatWords[list + PUNCTUAL_LIGHT_STATS_LIST_CELL] = listCell;
        lightStatWords[list + PUNCTUAL_LIGHT_STATS_LIST_TESTED] = tested;
    }
}

void main() {
    if (WRITE_SHADOW_FACTORS) {
        for (uint i = 0u; i < PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS; ++i) shadowFactorWords[i] = 0xFFFFFFFFu;
    }
    GpuObject object = objects[draw.objectIndex];
    GpuMaterial material = materials[object.material.x];
    // object.material.y marks mirrored transforms (negative determinant), whose winding flips.
    bool frontFacing = gl_FrontFacing != (object.material.y != 0u);
    vec4 baseColor;
    vec3 emission;
    sampleMaterial(material, baseColor, emission);
    discardWhatThePrepassDropped(material, frontFacing, baseColor.a);

    // Double-sided faces: the normal is turned towards the viewer on back faces.
    vec3 normal = normalize(inWorldNormal);
    if (!frontFacing) normal = -normal;

    vec3 viewDir = normalize(frame.cameraPosition.xyz - inWorldPosition);
    Surface surface = makeSurface(inWorldPosition, normal, viewDir, baseColor.rgb,
                                  material.metallicRoughness.x, material.metallicRoughness.y);

    precise vec3 radiance = shadeSun(surface);
    uint lightCount = frame.spotCount + frame.pointCount;
    uint tested = 0u;
    bool walkGridWords = false;
    switch (LIGHT_SOURCE) {
        case PUNCTUAL_LIGHT_SOURCE_ALL:
            for (uint i = 0u; i < lightCount; ++i) {
                radiance += shadeLight(surface, lights[i]);
            }
            tested = lightCount;
            break;
        case PUNCTUAL_LIGHT_SOURCE_OBJECT: {
            uint count = object.material.z;
            uint first = draw.objectIndex * PUNCTUAL_MAX_LIGHTS_PER_OBJECT;
            for (uint k = 0u; k < count; ++k) {
                radiance += shadeLight(surface, lights[objectLights[first + k]]);
            }
            tested = count;
            break;
        }
        case PUNCTUAL_LIGHT_SOURCE_GRID:        // tiled, clustered, tiled-2.5d (the tile grid, fewer bits set)
        case PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS:  // zbin, zbin-2d
            walkGridWords = true;
            break;
        default:
            unknownVariant = true;
            break;
    }
    // The grid methods' lights: the set bits of the cell's words, ascending, added to `radiance`
    // one by one in the brute-force loop's order and association. The words come three at a time
    // (cellWordTriple; one triple at the design notes' 96 lights), and one loop walks a triple,
    // each step taking the lowest set bit of the first word with any, by selects rather than
    // branches. Measured on lavapipe, default scene at 1280x720 (A/B, four rounds): a loop per
    // word 40.3 ms with no lights (brute force 32) and 82.8 with the default lights, this one 34.2
    // and 76.4; the same single loop with an if/else chain picking the word was twice as slow with
    // lights. (Evidently a loop there costs about a pass over its body even when it takes no step,
    // as SIMD lanes run under masks.)
    if (walkGridWords) {
        CellWords cell = pixelCellWords();
        switch (LIGHT_LIST_FORM) {
            case PUNCTUAL_LIGHT_LIST_MASKS:
                if (GRID_WORDS <= 3u) {
                    // Up to the design notes' 96 lights: one triple, with no loop around it
                    // (measured on lavapipe: the one-trip loop cost the default scene's forward pass 6%).
                    PUNCTUAL_WALK_WORD_TRIPLE(0u)
                } else {
                    for (uint triple = 0u; triple < (GRID_WORDS + 2u) / 3u; ++triple) PUNCTUAL_WALK_WORD_TRIPLE(triple)
                }
                break;
            case PUNCTUAL_LIGHT_LIST_INDICES:
                PUNCTUAL_WALK_INDEX_LIST()
                break;
            default:
                unknownVariant = true;
                break;
        }
    }
    // Emission last, after every light, in the reference's order. It lights nothing else.
    radiance += emission;
    outRadiance = vec4(unknownVariant ? kUnknownVariantRadiance : radiance,
                       TRANSPARENT && !unknownVariant ? baseColor.a : 1.0);

    if (WRITE_SHADOW_FACTORS) writeShadowFactors(normal);
    if (WRITE_LIGHT_STATS) writeLightStats(surface, radiance, emission, tested);
}
