// Limits and GPU struct layouts, shared by C++ and GLSL (std430 for buffers, std140-compatible
// for the frame uniform: every member is a vec4/mat4 or packs into one). The C++ side checks
// every size and offset with static_asserts in src/vk/gpu_types_check.cpp.
#ifndef PUNCTUAL_GPU_TYPES_H
#define PUNCTUAL_GPU_TYPES_H

#include "glsl_cpp.h"
#include "shadow_pages.h"

// Light capacity. A frame keeps at most S spot and P point lights (--max-lights S,P), the most
// important ones (lights/light_setup.h); the design notes' caps, 64 + 32, are the default. Any
// capacity up to PUNCTUAL_MAX_LIGHT_CAPACITY of each kind works: a light-grid cell holds one bit
// per light the frame keeps (gridWordsOf below), and walking its set bits in ascending order
// visits lights in the brute-force loop's order, which keeps culled and brute-force images
// bit-identical at every capacity.
#define PUNCTUAL_DEFAULT_MAX_SPOT_LIGHTS 64
#define PUNCTUAL_DEFAULT_MAX_POINT_LIGHTS 32
// 16384 of each kind: a z-bin's range holds 16-bit light indices (Drobot's), and every per-pixel
// count of lights (tested, reaching) fits its word with room to spare.
#define PUNCTUAL_MAX_LIGHT_CAPACITY 16384
// Shadowed lights per frame: at most the design notes' 64 spots and 32 points (--shadowed S,P
// caps them lower; at a larger light capacity the most important keep their shadows). Spots take
// one view, points six (256 views at most).
#define PUNCTUAL_MAX_SHADOWED_SPOT_LIGHTS 64
#define PUNCTUAL_MAX_SHADOWED_POINT_LIGHTS 32
// Unity's classic forward path gives each object at most 8 lights.
#define PUNCTUAL_MAX_LIGHTS_PER_OBJECT 8

// Descriptor bindings of the frame's set 0 (one set for every pass keeps pipelines simple). Set 1
// holds one base-colour texture per material (see forward.frag).
#define PUNCTUAL_BINDING_FRAME 0
#define PUNCTUAL_BINDING_LIGHTS 1
#define PUNCTUAL_BINDING_OBJECTS 2
#define PUNCTUAL_BINDING_MATERIALS 3
#define PUNCTUAL_BINDING_DEPTH 5          // depth prepass result, read by the culling passes
#define PUNCTUAL_BINDING_LIGHT_GRID 6     // per tile (or cluster): GRID_WORDS mask words, or one index-list header (culling.h)
#define PUNCTUAL_BINDING_DEPTH_RANGE 7    // GpuDepthRange, then each slice's lights (GRID_WORDS words a slice)
#define PUNCTUAL_BINDING_OBJECT_LIGHTS 8  // per object: PUNCTUAL_MAX_LIGHTS_PER_OBJECT packed-light indices
// Debug: per pixel uvec4 (tested, affecting | covered bit, luminances) of the opaque surface; then
// per pixel the sums over its transparent fragments (tested, affecting, fragments, fragments
// missing light).
#define PUNCTUAL_BINDING_LIGHT_STATS 9
#define PUNCTUAL_BINDING_CULL_LIGHTS 10   // CullLight per packed light: view-space culling shapes (culling.h)
#define PUNCTUAL_BINDING_SHADOW_VIEWS 11  // GpuShadowView per rendered shadow view
// (12: the atlas through a compare sampler, until its lookups gathered raw depths; see shadows.h's
// bilinearCompare.)
#define PUNCTUAL_BINDING_POINT_SHADOWS 13 // samplerCubeArrayShadow: one cube per shadowed point (cube layout)
#define PUNCTUAL_BINDING_SHADOW_ATLAS_DEPTH 14 // sampler2D: every spot view and point slice's raw depths (lights/shadow_atlas.h), gathered
#define PUNCTUAL_BINDING_SHADOW_DEBUG 15  // validation: per-pixel surface and shadow factors (see below)
// Per pixel, the float bits of the nearest (first width x height words) and the farthest (the next
// width x height) depth of the alphaMode BLEND surfaces in front of the opaque ones; 0 and
// 0xFFFFFFFF where there are none. Written by transparent_depth.frag, read by the culling kernels.
#define PUNCTUAL_BINDING_TRANSPARENT_DEPTH 16
#define PUNCTUAL_BINDING_ZBINS 17             // GpuZBins, then each bin's mask or each light's rank (lights/z_bins.h)
#define PUNCTUAL_BINDING_COARSE_GRID 18       // per coarse tile: GRID_WORDS mask words, as the light grid's (coarse_culling.comp)
// Index lists (--light-lists indices): the words used, then the cells' lists of 16-bit light
// indices, two a word (culling.h, "Index lists"); one word with masks.
#define PUNCTUAL_BINDING_LIGHT_INDICES 19
// Virtual shadow pages (--shadow-res virtual, shadow_pages.h): a GpuVirtualShadowView per plan
// view; the page table (per level a view uses, its pages' rectangle of entries, each a page's slot
// in the pool or PUNCTUAL_NO_SHADOW_PAGE); and the marking pass's bits, one per page of every
// level, per view with casters (GpuVirtualShadowView::marks).
#define PUNCTUAL_BINDING_SHADOW_PAGE_VIEWS 20
#define PUNCTUAL_BINDING_SHADOW_PAGE_TABLE 21
#define PUNCTUAL_BINDING_SHADOW_PAGE_MARKS 22
// The shadow pass's instances: per instance, the page it draws (view, level, column | row << 16,
// pool slot); read by shadow.vert and shadow_masked.vert (shadow_page_draw.glsl).
#define PUNCTUAL_BINDING_SHADOW_PAGE_DRAWS 23
// The previous frame's page marks (--shadow-hysteresis in a sequence), laid out as this frame's:
// read by the marking pass and the lookups alike (GpuVirtualShadowView::marks.z).
#define PUNCTUAL_BINDING_SHADOW_PREVIOUS_PAGE_MARKS 24

// Shadow validation buffer (forward shader's WRITE_SHADOW_FACTORS variant), in 32-bit words:
// per pixel PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS words (world position xyz, 1 if covered, shading
// normal xyz, 0), then per pixel PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS words holding one byte per
// shadowed light (slot order: spots, then points; the sun in slot PUNCTUAL_SUN_SHADOW_SLOT): the GPU
// shadow factor x 254, or 255 where the light does not reach the pixel. The surface's last word
// is the sun's cascade there plus one (0: none).
#define PUNCTUAL_MAX_SHADOWED_LIGHTS (PUNCTUAL_MAX_SHADOWED_SPOT_LIGHTS + PUNCTUAL_MAX_SHADOWED_POINT_LIGHTS)
#define PUNCTUAL_SUN_SHADOW_SLOT PUNCTUAL_MAX_SHADOWED_LIGHTS
// Light statistics variant (PUNCTUAL_SPEC_WRITE_LIGHT_STATS), a covered pixel's work word: the
// shadow-map lookups its lights took (a lookup: one filtered read of one view, cube face or
// cascade; the sun's blend zone reads two) and the texture instructions those lookups issued (a
// tap: one compare sample or one gather). Bits 0-7 and 8-31: at most 96 shadowed lights + 2
// lookups of at most 64 taps each fit. (The lights it tested have a word of their own.)
#define PUNCTUAL_STATS_LOOKUP_BITS 8u
#define PUNCTUAL_STATS_TAP_SHIFT 8u
#define PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS 8
#define PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS ((PUNCTUAL_MAX_SHADOWED_LIGHTS + 1 + 3) / 4)
#define PUNCTUAL_SHADOW_FACTOR_NOT_REACHED 255u

// Variants chosen by specialization constant. Each kind has a C++ table with one entry per variant
// (names, help text, parameters): src/render/light_list_method.h, src/lights/shadow_filters.h,
// src/lights/cascade_settings.h. A light-list method reaches the shaders as its parameters (its
// light source below, its slices, its culling flags: culling.h), a shadow filter as its kernel and
// size (shadow_kernels.h), so a variant that reuses those is a table row alone. The values of each
// kind are 0 .. COUNT - 1; a unit test checks that every value a table uses has its explicit case
// in the shaders (a value without one shades magenta rather than passing for another variant).
//
// Point-light shadow layouts (PUNCTUAL_SPEC_POINT_SHADOW_LAYOUT).
#define PUNCTUAL_POINT_SHADOW_CUBE 0u    // a cube depth array, hardware face selection
#define PUNCTUAL_POINT_SHADOW_SLICES 1u  // six 2D layers with a widened field of view (URP)
#define PUNCTUAL_POINT_SHADOW_LAYOUT_COUNT 2u
// How a receiver near a cascade's edge reads the sun's cascades (PUNCTUAL_SPEC_CASCADE_BLEND).
#define PUNCTUAL_CASCADE_BLEND_HARD 0u    // one cascade: the first whose sphere holds it
#define PUNCTUAL_CASCADE_BLEND_SOFT 1u    // the cascade's outer share mixes it with the next one
#define PUNCTUAL_CASCADE_BLEND_DITHER 2u  // the outer share picks one of the two per pixel
#define PUNCTUAL_CASCADE_BLEND_COUNT 3u
#define PUNCTUAL_MAX_CASCADES 4
// How the forward shader reads spot and point shadows (PUNCTUAL_SPEC_SHADOW_PAGES).
#define PUNCTUAL_SHADOW_PAGES_OFF 0u     // each view's square of the atlas (fixed and auto resolution)
#define PUNCTUAL_SHADOW_PAGES_LOOKUP 1u  // virtual maps: each receiver its level's pages, through the page table
#define PUNCTUAL_SHADOW_PAGES_MARK 2u    // the marking pass: each receiver marks the pages it will read, shades nothing
#define PUNCTUAL_SHADOW_PAGES_COUNT 3u

// GpuMaterial::flags.
#define PUNCTUAL_MATERIAL_ALPHA_MASK 1u    // glTF alphaMode MASK: dropped where alpha < cutoff
#define PUNCTUAL_MATERIAL_ALPHA_BLEND 2u   // glTF alphaMode BLEND: the transparent pass
#define PUNCTUAL_MATERIAL_SINGLE_SIDED 4u  // not doubleSided: back faces are not drawn

// Clusters use at most 32 depth slices, so a tile's occupied slices fit one 32-bit mask.
#define PUNCTUAL_MAX_CLUSTER_SLICES 32

// Where the forward pass finds a pixel's lights (specialization constant PUNCTUAL_SPEC_LIGHT_SOURCE),
// each light-list method's `source` in its table row.
#define PUNCTUAL_LIGHT_SOURCE_ALL 0u         // every light (brute force)
#define PUNCTUAL_LIGHT_SOURCE_OBJECT 1u      // the object's list, built on the CPU (per-object)
#define PUNCTUAL_LIGHT_SOURCE_GRID 2u        // the set bits of the pixel's light-grid cell (tiled, clustered, ...)
#define PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS 3u  // those AND its z-bin's range (zbin, zbin-2d)
#define PUNCTUAL_LIGHT_SOURCE_COUNT 4u

// How a light-grid cell holds its lights (PUNCTUAL_SPEC_LIGHT_LIST_FORM), each list form's `gpu`
// in its table row (src/render/light_list_form.h); culling.h describes both.
#define PUNCTUAL_LIGHT_LIST_MASKS 0u    // GRID_WORDS words, one bit per light
#define PUNCTUAL_LIGHT_LIST_INDICES 1u  // a header word: where its list of 16-bit indices starts
#define PUNCTUAL_LIGHT_LIST_FORM_COUNT 2u

// Specialization constant ids.
#define PUNCTUAL_SPEC_LIGHT_SOURCE 1
#define PUNCTUAL_SPEC_TILE_SIZE 2
#define PUNCTUAL_SPEC_SLICE_COUNT 3
#define PUNCTUAL_SPEC_WRITE_LIGHT_STATS 4
#define PUNCTUAL_SPEC_SHADOW_KERNEL 5
#define PUNCTUAL_SPEC_SHADOW_SAMPLES 6
#define PUNCTUAL_SPEC_POINT_SHADOW_LAYOUT 7
#define PUNCTUAL_SPEC_SHADOWS 8
#define PUNCTUAL_SPEC_WRITE_SHADOW_FACTORS 9
#define PUNCTUAL_SPEC_SHADOW_RECEIVER_PLANE 10
#define PUNCTUAL_SPEC_CASCADE_BLEND 11
#define PUNCTUAL_SPEC_TRANSPARENT 12
#define PUNCTUAL_SPEC_CULL_FLAGS 13  // culling kernels: the method's PUNCTUAL_CULL_* flags (culling.h)
#define PUNCTUAL_SPEC_SHADOW_FILTER_SIZE 14  // forward: the shadow kernel's size (shadow_kernels.h)
#define PUNCTUAL_SPEC_COARSE_TILES 15  // culling: fine tiles a side of a coarse tile (0: no coarse pass)
#define PUNCTUAL_SPEC_TILE_THREADS 16  // tile_culling.comp: invocations per tile (the device's subgroup size)
#define PUNCTUAL_SPEC_GRID_WORDS 17  // words per light-grid cell (gridWordsOf the frame's lights)
#define PUNCTUAL_SPEC_LIGHT_LIST_FORM 18  // culling kernels and forward: PUNCTUAL_LIGHT_LIST_MASKS or _INDICES
#define PUNCTUAL_SPEC_SHADOW_PAGES 19     // forward: PUNCTUAL_SHADOW_PAGES_*
// tile_culling.comp's workgroups: at most this many invocations (a power of two, at least the 32 or
// 64 of GPU subgroups; one lane per 2x2 block of a 16-pixel tile).
#define PUNCTUAL_MAX_TILE_THREADS 64u
// depth_range.comp: pixels a side of the square each invocation folds (even: whole 2x2 blocks),
// and invocations a workgroup (no shared memory, no barriers: the size only groups the work).
#define PUNCTUAL_DEPTH_RANGE_SIDE 8u
#define PUNCTUAL_DEPTH_RANGE_THREADS 64u

PUNCTUAL_NAMESPACE_BEGIN

PUNCTUAL_FN uint packPixelWork(uint lookups, uint taps) { return lookups | (taps << PUNCTUAL_STATS_TAP_SHIFT); }
PUNCTUAL_FN uint unpackShadowLookups(uint word) { return word & ((1u << PUNCTUAL_STATS_LOOKUP_BITS) - 1u); }
PUNCTUAL_FN uint unpackShadowTaps(uint word) { return word >> PUNCTUAL_STATS_TAP_SHIFT; }

// Words per light-grid cell for a frame keeping `lightCount` lights: one bit each (culling.h,
// lightGridWord), at least one word. The grid, the coarse grid, the slices' and the z-bins' masks
// all have this many words a cell; the shaders get it as PUNCTUAL_SPEC_GRID_WORDS.
PUNCTUAL_FN uint gridWordsOf(uint lightCount) { return lightCount == 0u ? 1u : (lightCount + 31u) / 32u; }

// Light statistics buffer (PUNCTUAL_BINDING_LIGHT_STATS, the forward shader's WRITE_LIGHT_STATS
// variant), in 32-bit words: three blocks, each PUNCTUAL_LIGHT_STATS_PIXEL_WORDS words for every
// pixel of the frame (width x height), in this order:
//   OPAQUE      the pixel's opaque surface: WORK packPixelWork(lookups, taps); REACHING the lights
//               that reach it, with PUNCTUAL_LIGHT_STATS_COVERED set (every shaded pixel: 0 marks
//               background); LUMINANCE and BRUTE_LUMINANCE the float bits of the method's and
//               brute force's luminance there.
//   TRANSPARENT summed by atomics over the pixel's alphaMode BLEND fragments: TESTED, REACHING,
//               FRAGMENTS, and MISSING, the fragments whose luminance fell short of brute force's.
//   LIST        the opaque surface's light list: LIST_CELL the cell the pixel read, LIST_TESTED
//               the lights it tested.
// Then, for the exact-list floor (metrics/culling_stats.h), per list cell GRID_WORDS words: the
// union (atomicOr) of the masks (culling.h, lightGridWord) of the lights reaching its opaque pixels.
// Per cell, not per pixel: a pixel's own mask would be GRID_WORDS words, 1 KiB at 8,192 lights.
#define PUNCTUAL_LIGHT_STATS_PIXEL_WORDS 4u
#define PUNCTUAL_LIGHT_STATS_BLOCKS 3u
#define PUNCTUAL_LIGHT_STATS_OPAQUE 0u
#define PUNCTUAL_LIGHT_STATS_TRANSPARENT 1u
#define PUNCTUAL_LIGHT_STATS_LIST 2u
#define PUNCTUAL_LIGHT_STATS_WORK 0u            // OPAQUE's words
#define PUNCTUAL_LIGHT_STATS_REACHING 1u
#define PUNCTUAL_LIGHT_STATS_LUMINANCE 2u
#define PUNCTUAL_LIGHT_STATS_BRUTE_LUMINANCE 3u
#define PUNCTUAL_LIGHT_STATS_TESTED 0u          // TRANSPARENT's words (REACHING is word 1 in both)
#define PUNCTUAL_LIGHT_STATS_FRAGMENTS 2u
#define PUNCTUAL_LIGHT_STATS_MISSING 3u
#define PUNCTUAL_LIGHT_STATS_LIST_CELL 0u       // LIST's words
#define PUNCTUAL_LIGHT_STATS_LIST_TESTED 1u
#define PUNCTUAL_LIGHT_STATS_COVERED 0x80000000u

// A shadowed light's slot among the validation buffer's factor bytes (spots, then points), from
// the index of its first shadow view: the plan lists every shadowed spot's one view first, then
// each shadowed point's six faces, so a spot's slot is its view and a point's is the spots'
// count plus its cube's index. The forward shader writes by it; shadow validation reads by it.
PUNCTUAL_FN uint shadowSlot(uint firstView, uint shadowedSpots) {
    return firstView < shadowedSpots ? firstView : shadowedSpots + (firstView - shadowedSpots) / 6u;
}

// The index of word `word` of `pixel` in `block`, for a frame of `pixels` pixels.
PUNCTUAL_FN uint lightStatsWord(uint block, uint pixels, uint pixel, uint word) {
    return (block * pixels + pixel) * PUNCTUAL_LIGHT_STATS_PIXEL_WORDS + word;
}

// The index of mask word `word` of list cell `cell`'s reaching lights, after the pixel blocks.
PUNCTUAL_FN uint lightStatsCellWord(uint pixels, uint gridWords, uint cell, uint word) {
    return PUNCTUAL_LIGHT_STATS_BLOCKS * pixels * PUNCTUAL_LIGHT_STATS_PIXEL_WORDS + cell * gridWords + word;
}

// A spot or point light. Spots and points share one struct: a point light is a spot whose
// angular attenuation is constant 1 (scale 0, offset 1), so one loop body serves both.
struct GpuPunctualLight {
    vec4 positionInvRangeSq;   // xyz: world position; w: 1 / max(range^2, 1e-4)
    vec4 radiantColor;         // rgb: linear colour x intensity (candela); w: range (metres)
    vec4 directionAngleScale;  // xyz: unit direction the light shines (node -Z); w: k = 1/max(cosInner - cosOuter, 1e-4), 0 for points
    vec4 angleOffsetShadow;    // x: -cosOuter * k (1 for points); y: first shadow view or -1 (no shadow);
                               // z: cos outer (-1 for points, for culling); w: shadow strength (0..1)
};

struct GpuDirectionalLight {
    vec4 directionToLight;  // xyz: unit vector from the surface towards the light; w: 1 if present
    vec4 illuminance;       // rgb: linear colour x intensity (lux)
};

struct GpuFrame {
    mat4 view;
    mat4 projection;
    mat4 viewProjection;
    mat4 inverseViewProjection;
    vec4 cameraPosition;  // xyz: world position
    vec4 viewport;        // xy: size in pixels; zw: 1 / size
    uint spotCount;        // spot lights (the light array's first)
    uint pointCount;       // point lights (stored after the spots)
    uint directionalCount; // 0 or 1
    uint transparentSpans; // 1: the frame has alphaMode BLEND surfaces, and the kernels bound tiles and
                           // clusters by their depth spans (PUNCTUAL_BINDING_TRANSPARENT_DEPTH); 0: none
    vec4 exposure;        // x: linear exposure multiplier applied before tone mapping
    GpuDirectionalLight sun;
    uvec4 lightGrid;      // x: tile size in pixels, y: tiles across, z: tiles down, w: depth slices (1 = tiled)
    vec4 depthToView;     // xy: (a, b) with view distance = a / (depth + b) (see culling.h); zw: unused
    vec4 ndcToView;       // (1/P00, 1/P11, P20, P21): view ray through an NDC point (see culling.h)
    vec4 shadowBias;      // depth, slope-scaled depth, normal, sin-scaled normal offsets (x texel size x (1 + penumbra))
    vec2 shadowAtlasSize;      // the shadow atlas's size in texels
    float diskRadius;          // the disk filter's radius (a view's UV units)
    float shadowDepthQuantum;  // the depth format's rounding, subtracted by receiver-plane compares
    uvec4 shadowCounts;   // x: shadowed spots (their views come first), y: shadowed points
    // The sun's cascades (shaders/shared/cascades.h, lights/cascade_setup.h):
    uvec4 sunShadow;      // x: the first cascade's view (after the points'), y: cascades (0: unshadowed)
    vec4 sunShadowFade;   // x: 1 / shadow distance, y: 1 / distance fade share, z: cascadeFadeScale,
                          // w: the sun's shadow strength
    vec4 cascadeSpheres[PUNCTUAL_MAX_CASCADES];  // xyz: centre; w: the selection radius squared
    // Virtual shadow pages (PUNCTUAL_SPEC_SHADOW_PAGES): x: the texels a screen pixel should span
    // (--shadow-texels-per-pixel), y: a screen pixel's world size at unit view depth
    // (screenPixelWorldSize, shadows.h); zw: unused.
    vec4 shadowPageNeed;
    uvec4 shadowPagePool;  // x: the cascades' squares' width, y: their height (the pool fills the rest:
                           // virtualShadowSlotOrigin), z: slots across beside them, w: slots across below
    uvec4 shadowPageSlots; // x: the lit page's slot (cleared, never drawn); yzw: unused
};

// One rendered shadow view: a spot light's frustum, or one face of a point light (+X -X +Y -Y +Z
// -Z, consecutive). World -> light clip space (Vulkan depth 0..1).
struct GpuShadowView {
    mat4 viewProjection;
    vec4 params;     // x: 1 when the view has a map, -1 when not (no caster, or no storage: always lit);
                     // y: 2 tan(fov / 2), the view's span at unit depth (shadowTexelWorldSize); a
                     // cascade: its width (orthographic, the same at every depth);
                     // z: near, w: far (metres along the view axis)
    vec4 atlasRect;  // xy: the view's top-left corner in atlas UV, zw: its size in atlas UV;
                     // cube layout: x is the light's cube in the cube array
    vec4 texel;      // x: resolution (texels a side), y: 1 / resolution, z: the bias's penumbra in
                     // texels (ShadowSettings::biasPenumbraTexels), w: unused
};

// A view's virtual map (--shadow-res virtual): where its marks are and, per level, its page table.
struct GpuVirtualShadowView {
    uvec4 marks;  // x: the view's first word of page marks (PUNCTUAL_NO_SHADOW_PAGE: no caster, no
                  // marks); y: levels coarser than asked (the allocation's coarsening); z: the first
                  // word of the previous frame's marks of the same light and face
                  // (PUNCTUAL_NO_SHADOW_PAGE: none, no hysteresis); w: the float bits of 2^H, H
                  // the octaves of hysteresis (virtualShadowMayKeepFiner)
    // Per level: x: its first page-table entry (PUNCTUAL_NO_SHADOW_PAGE: no page at this level);
    // y: the first column | first row << 16 of the rectangle of pages the table covers;
    // z: its columns | rows << 16; w: unused.
    uvec4 levels[PUNCTUAL_VIRTUAL_SHADOW_LEVELS];
};

// Written on the GPU each frame (clustered culling): depth-range pass, then slice-boundaries pass.
struct GpuDepthRange {
    // Float bits of the smallest and largest geometry depth (non-negative floats sort as uints).
    // The depth is reversed (culling.h): the smallest is the farthest geometry, the largest the
    // nearest.
    uint minDepthBits;
    uint maxDepthBits;
    uint sliceCount;
    // Subgroups of depth_range.comp done with their atomics (0 at the frame's start): the last one
    // cuts the slices.
    uint finishedSubgroups;
    // Depth where slice s begins; slice 0 = nearest (depth 1), starts falling with s.
    float sliceStartDepth[PUNCTUAL_MAX_CLUSTER_SLICES];
    // The buffer goes on, after this header, with each slice's lights: per slice (all
    // PUNCTUAL_MAX_CLUSTER_SLICES), GRID_WORDS mask words (lightGridWord in culling.h) of the lights
    // whose view-distance extent meets the slice's distances: the only lights a segment of that
    // slice can meet (cluster_culling.comp tests no other).
};

// The z-bin method's bins (URP Forward+ after Drobot 2017; lights/z_bins.h builds them on the
// CPU each frame). Bin b covers the depths from binStartDepth[b] down to binStartDepth[b + 1]
// (reversed depth: bin 0 starts at the near plane, depth 1; the last runs to the far plane), the
// same stored-start search as the cluster slices (culling.h), so the CPU and the forward pass
// put a depth in the same bin. binRange[b]: the bin's range of depth-sorted light indices, first |
// last << 16 (16-bit indices, as Drobot's; first > last: an empty bin). The buffer goes on, after
// this header, with each bin's range expanded into a packed-order mask (GRID_WORDS words a bin;
// lightGridWord), which the forward pass ANDs with its tile's; or, with index lists, with each
// light's 16-bit rank in depth order (two a word), which it tests against the bin's range.
#define PUNCTUAL_ZBIN_COUNT 64u
struct GpuZBins {
    float binStartDepth[PUNCTUAL_ZBIN_COUNT];
    uint binRange[PUNCTUAL_ZBIN_COUNT];
};

struct GpuObject {
    mat4 model;
    mat4 normalMatrix;  // inverse transpose of model (mat4 keeps std430 and C++ layouts equal)
    uvec4 material;     // x: material index, y: 1 if the transform mirrors (winding flips),
                        // z: per-object light count (<= PUNCTUAL_MAX_LIGHTS_PER_OBJECT), w: unused
};

struct GpuMaterial {
    vec4 baseColorFactor;  // linear RGBA
    vec4 emission;         // rgb: emitted radiance (emissiveFactor x emissive strength); w: alpha cutoff (MASK)
    vec4 baseColorUv[2];   // KHR_texture_transform rows U, V (xyz, materials.h); [0].w: texcoord set
    vec4 emissiveUv[2];    // the same for the emissive texture
    vec2 metallicRoughness;
    int baseColorTexture;  // index into the scene's textures, -1 for none (a white texel is bound)
    uint flags;            // PUNCTUAL_MATERIAL_* bits
    int emissiveTexture;   // -1 for none (a white texel is bound)
    uint reserved0;
    uint reserved1;
    uint reserved2;
};

PUNCTUAL_NAMESPACE_END

#endif
