// Virtual shadow pages (issue 33): the addressing shared by the C++ page-demand model
// (lights/virtual_pages.h) and, later, the GPU's marking pass and lookups.
//
// Each spot view and point face is a virtual map of `virtualSize` texels a side (a power of two)
// with levels 0 .. levels - 1, level m holding virtualSize / 2^m texels a side, down to a level of
// one page. A level is cut into square pages of `pageSize` texels a side (a power of two no larger
// than virtualSize). A receiver needs the page under it at the level its pixel asks for; only the
// pages some receiver needs would get memory (Unreal's virtual shadow maps, Olsson et al. 2014).
#ifndef PUNCTUAL_SHADOW_PAGES_H
#define PUNCTUAL_SHADOW_PAGES_H

#include "glsl_cpp.h"

// The layout --shadow-res virtual renders (measured against 4096 .. 16384 and pages of 32 .. 256
// by the estimate, bench/RESULTS.md "Virtual shadow pages, first part"): every spot view and point
// slice a 16384-texel virtual map (no receiver of the measured scenes asked for more than 2k, so
// the size costs nothing but the marks' bits) in pages of 32 texels (the page size is what decides
// the memory: 32-texel pages need 2.3x the floor on the hall, 128-texel pages 4.8x), with
// log2(16384 / 32) + 1 = 10 levels.
#define PUNCTUAL_VIRTUAL_SHADOW_SIZE 16384u
#define PUNCTUAL_VIRTUAL_SHADOW_PAGE 32u
#define PUNCTUAL_VIRTUAL_SHADOW_LEVELS 10u
// A page's slot in the pool: its 32 texels a side and the first column and row of its right and
// lower neighbours (drawn with it), so that every 2 x 2 gather whose texels start in the page
// reads one slot, and a filter's taps never branch on page borders: 33 x 33 texels, 6% more than
// the page's own.
#define PUNCTUAL_VIRTUAL_SHADOW_SLOT 33u
// A page-table entry, or a level's first entry, with no page behind it.
#define PUNCTUAL_NO_SHADOW_PAGE 0xFFFFFFFFu
// Texels the marking pass adds to a filter's reach: the lookup reads the footprint it marks from
// the same interpolated surface through the same functions, but the two are separate pipelines and
// a compiler may round them differently; one texel of margin keeps every page the lookup reads
// marked (it costs about 3% more pages on the hall).
#define PUNCTUAL_VIRTUAL_SHADOW_MARK_MARGIN 1.0f

PUNCTUAL_NAMESPACE_BEGIN

// The levels of a virtual map: log2(virtualSize / pageSize) + 1, the last one page a side.
PUNCTUAL_CONSTEXPR_FN uint virtualShadowLevels(uint virtualSize, uint pageSize) {
    uint levels = 1u;
    for (uint side = virtualSize; side > pageSize; side >>= 1u) ++levels;
    return levels;
}

// The level whose resolution is nearest in log scale to `needed` texels a side: --shadow-res
// auto's tier rule (shadowTierFor, lights/shadow_resolution.h), so that a receiver gets between
// 1/sqrt(2) and sqrt(2) times the density it asks for, compared through the geometric midpoints so
// that no log2 rounding decides a boundary. Past the finest level (needed > virtualSize sqrt(2))
// it is level 0, coarser than asked; below the coarsest, the coarsest, finer than asked.
#define PUNCTUAL_SQRT2 1.41421356f  // a level's resolution times this is the midpoint to the next finer
PUNCTUAL_FN uint virtualShadowLevel(float needed, uint virtualSize, uint levels) {
    uint level = levels - 1u;
    float resolution = float(virtualSize >> level);
    while (level > 0u && needed > resolution * PUNCTUAL_SQRT2) {
        level -= 1u;
        resolution *= 2.0f;
    }
    return level;
}

// `level` made `coarser` levels coarser (a view the pool was short for, coarsened by the
// allocation), at most the coarsest.
PUNCTUAL_FN uint virtualShadowCoarsened(uint level, uint coarser) {
    return min(level + coarser, PUNCTUAL_VIRTUAL_SHADOW_LEVELS - 1u);
}

// The level a receiver reads: the nearest level to the resolution it needs (virtualShadowLevel, at
// PUNCTUAL_VIRTUAL_SHADOW_SIZE), coarsened.
PUNCTUAL_FN uint virtualShadowReadLevel(float needed, uint coarser) {
    return virtualShadowCoarsened(virtualShadowLevel(needed, PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_LEVELS),
                                  coarser);
}

// Hysteresis for a receiver's level in a sequence (--shadow-hysteresis H; auto's kept rule,
// shadowTierWithHysteresis): the level one finer than the nearest, `level`, may be kept while the
// need stays within H octaves below the midpoint where that finer level stops being the nearest,
// needed > (virtualSize >> level) sqrt 2 / 2^H (`keep` = 2^H); the caller keeps it where the
// previous frame read it (its page there was marked). Never a level coarser than the nearest:
// holding coarser tiers cost auto accuracy and flipped more (bench/RESULTS.md). With H = 0 it never
// holds (the nearest level's need is at most its midpoint).
PUNCTUAL_FN bool virtualShadowMayKeepFiner(float needed, uint level, float keep) {
    return level > 0u && needed * keep > float(PUNCTUAL_VIRTUAL_SHADOW_SIZE >> level) * PUNCTUAL_SQRT2;
}

// Pages a side of level `level`.
PUNCTUAL_FN uint virtualShadowPagesAcross(uint level, uint virtualSize, uint pageSize) {
    return max((virtualSize >> level) / pageSize, 1u);
}

// The pages a filter reading `reach` texels around view UV `uv` at level `level` needs, as
// uvec4(first column, first row, last column, last row): the pages of the texels t - reach ..
// t + reach on each axis, t = uv x the level's texels (uv clamped), clamped to the level. A
// receiver near a page's border reads its neighbour's texels, so the neighbour must exist too.
PUNCTUAL_FN uvec4 virtualShadowFootprintPages(vec2 uv, float reach, uint level, uint virtualSize, uint pageSize) {
    vec2 texel = clamp(uv, vec2(0.0f), vec2(1.0f)) * float(virtualSize >> level);
    vec2 last = vec2(float(virtualShadowPagesAcross(level, virtualSize, pageSize) - 1u));
    vec2 first = clamp(floor((texel - reach) / float(pageSize)), vec2(0.0f), last);
    return uvec4(uvec2(first), uvec2(clamp(floor((texel + reach) / float(pageSize)), vec2(0.0f), last)));
}

// The page under view UV `uv` (0 .. 1 across the view, clamped) at level `level`: its column and
// row among the level's pages (the footprint of a filter that reaches no texel away).
PUNCTUAL_FN uvec2 virtualShadowPage(vec2 uv, uint level, uint virtualSize, uint pageSize) {
    return uvec2(virtualShadowFootprintPages(uv, 0.0f, level, virtualSize, pageSize));
}

// The square a page's slot holds (PUNCTUAL_VIRTUAL_SHADOW_SLOT texels from the page's first) of
// `level` in its view's NDC (the view's clip space over w): xy its centre, z its half side. The
// level spans NDC [-1, 1] in r = (virtualSize >> level) texels, so s texels are 2 s / r wide, and
// the slot's square starts at 2 page pageSize / r - 1. The shadow pass draws a page by mapping
// this square onto the slot; the allocation culls casters against it.
PUNCTUAL_FN vec3 virtualShadowPageNdc(uint level, uvec2 page) {
    float texelNdc = 2.0f / float(PUNCTUAL_VIRTUAL_SHADOW_SIZE >> level);
    float halfSide = 0.5f * float(PUNCTUAL_VIRTUAL_SHADOW_SLOT) * texelNdc;
    return vec3(vec2(page) * (float(PUNCTUAL_VIRTUAL_SHADOW_PAGE) * texelNdc) - 1.0f + halfSide, halfSide);
}

// Where pool slot `slot` starts in the atlas (its top-left texel). The pool fills what the squares
// of the sun's cascades (the atlas's top-left `squares` texels: x wide, y tall) leave: first the
// band beside them (from column squares.x, `beside` slots across, squares.y / slot side rows),
// then the rows below them, `across` slots wide from row squares.y. So the pool's memory is its
// slots', with no band of unused texels where the atlas is wider than the cascades.
PUNCTUAL_FN uvec2 virtualShadowSlotOrigin(uint slot, uvec2 squares, uint beside, uint across) {
    uint besideSlots = beside * (squares.y / PUNCTUAL_VIRTUAL_SHADOW_SLOT);
    if (slot < besideSlots) {
        return uvec2(squares.x + (slot % beside) * PUNCTUAL_VIRTUAL_SHADOW_SLOT, (slot / beside) * PUNCTUAL_VIRTUAL_SHADOW_SLOT);
    }
    uint below = slot - besideSlots;
    return uvec2((below % across) * PUNCTUAL_VIRTUAL_SHADOW_SLOT, squares.y + (below / across) * PUNCTUAL_VIRTUAL_SHADOW_SLOT);
}

// A page's index among all the map's pages, level 0's first, row by row: level m starts after
// the pages of the levels before it. Level k is 2^(L - 1 - k) pages across (L levels, the last one
// page), so the levels before m hold sum over k < m of 4^(L - 1 - k) = (4^L - 4^(L - m)) / 3 pages.
PUNCTUAL_FN uint virtualShadowPageIndex(uvec2 page, uint level, uint virtualSize, uint pageSize) {
    uint levels = virtualShadowLevels(virtualSize, pageSize);
    uint first = ((1u << (2u * levels)) - (1u << (2u * (levels - level)))) / 3u;
    return first + page.y * virtualShadowPagesAcross(level, virtualSize, pageSize) + page.x;
}

PUNCTUAL_NAMESPACE_END

#endif
