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

PUNCTUAL_NAMESPACE_BEGIN

// The levels of a virtual map: log2(virtualSize / pageSize) + 1, the last one page a side.
PUNCTUAL_FN uint virtualShadowLevels(uint virtualSize, uint pageSize) {
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

// A page's index among all the map's pages, level 0's first, row by row: level m starts after
// the pages of the levels before it, sum over k < m of (pages across level k)^2.
PUNCTUAL_FN uint virtualShadowPageIndex(uvec2 page, uint level, uint virtualSize, uint pageSize) {
    uint first = 0u;
    for (uint k = 0u; k < level; ++k) {
        uint across = virtualShadowPagesAcross(k, virtualSize, pageSize);
        first += across * across;
    }
    return first + page.y * virtualShadowPagesAcross(level, virtualSize, pageSize) + page.x;
}

PUNCTUAL_NAMESPACE_END

#endif
