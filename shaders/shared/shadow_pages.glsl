// Virtual shadow pages (--shadow-res virtual): the marking pass and the lookups through the page
// table (GLSL only; included by forward.frag after its bindings, before shadow_sampling.glsl).
// The addressing (levels, pages, footprints) is in shadow_pages.h, shared with the C++ allocation
// (lights/shadow_page_allocation.h) and its CPU estimate (lights/virtual_pages.h).
//
// A receiver reads one level of its view's virtual map: the level nearest to the resolution at
// which one texel spans 1 / texelsPerPixel of its pixel (virtualShadowReadLevel). The marking pass
// runs the forward shader's own light walk on the same interpolated surfaces, so for every
// (receiver, shadowed light) pair the forward pass will shade it computes the same level, bias and
// view UV, and marks every page the filter will read there (the footprint of its reach, plus
// PUNCTUAL_VIRTUAL_SHADOW_MARK_MARGIN). The allocation (on the CPU) gives each marked page a slot
// of the pool, a 32 x 32 square of the atlas; the lookups read texels through the page table, so
// a filter whose footprint crosses a page border reads each side from its own slot: no seams, and
// no guard bands stored around the pages.
//
// Only the forward shader's virtual-pages build (PUNCTUAL_SHADOW_PAGES, cmake/Shaders.cmake) holds
// this code; the other builds get the stubs at the end, which their pipelines never reach.

#ifdef PUNCTUAL_SHADOW_PAGES

// World size of one screen pixel at `position`: screenPixelWorldSize at its depth along the camera's
// axis (shadows.h), as the CPU estimate measures it along its primary rays.
float pixelWorldSizeAt(vec3 position) {
    float viewDepth = -(frame.view * vec4(position, 1.0)).z;
    return screenPixelWorldSize(viewDepth, frame.shadowPageNeed.y);
}

// Whether the previous frame's marks (from word `first`) hold the page of `level` under view UV `uv`.
bool previouslyMarked(uint first, vec2 uv, uint level) {
    uvec2 page = virtualShadowPage(uv, level, PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_PAGE);
    uint index = virtualShadowPageIndex(page, level, PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_PAGE);
    return (previousPageMarks[first + (index >> 5u)] & (1u << (index & 31u))) != 0u;
}

// The level of view `viewIndex` a receiver at `position`, `linearDepth` along the view's axis, reads:
// the nearest, or one finer where hysteresis may hold it (virtualShadowMayKeepFiner) and the
// previous frame marked that finer level's page under the receiver (its unbiased position in the
// view: the bias depends on the level). Marks are per page, not per pixel, so a receiver holds the
// finer level where any receiver of that page read it (requiring the nearest's page unmarked too,
// a stricter "this receiver read it", held nothing on the walk: bench/RESULTS.md). The marking
// pass and the lookups both come here, so they agree.
uint virtualReadLevel(uint viewIndex, GpuShadowView view, float linearDepth, vec3 position) {
    float needed = resolutionForOneTexelPerPixel(linearDepth, view.params.y, pixelWorldSizeAt(position)) *
                   frame.shadowPageNeed.x;
    uvec4 marks = virtualViews[viewIndex].marks;
    uint level = virtualShadowLevel(needed, PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_LEVELS);
    uint nearest = virtualShadowCoarsened(level, marks.y);
    if (marks.z != PUNCTUAL_NO_SHADOW_PAGE && virtualShadowMayKeepFiner(needed, level, uintBitsToFloat(marks.w))) {
        vec4 clip = view.viewProjection * vec4(position, 1.0);
        uint finer = virtualShadowCoarsened(level - 1u, marks.y);
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        if (clip.w > 0.0 && finer != nearest && previouslyMarked(marks.z, uv, finer)) {
            return finer;
        }
    }
    return nearest;
}

// Marks the pages of `level` that a filter around view UV `uv` reads.
void markVirtualFootprint(uint viewIndex, uint level, vec2 uv) {
    uint base = virtualViews[viewIndex].marks.x;
    if (base == PUNCTUAL_NO_SHADOW_PAGE) return;
    float resolution = float(PUNCTUAL_VIRTUAL_SHADOW_SIZE >> level);
    float reach = shadowKernelReachTexels(SHADOW_KERNEL, SHADOW_FILTER_SIZE, frame.diskRadius * resolution) +
                  PUNCTUAL_VIRTUAL_SHADOW_MARK_MARGIN;
    uvec4 pages = virtualShadowFootprintPages(uv, reach, level, PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_PAGE);
    for (uint y = pages.y; y <= pages.w; ++y) {
        for (uint x = pages.x; x <= pages.z; ++x) {
            uint index = virtualShadowPageIndex(uvec2(x, y), level, PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_PAGE);
            uint bit = 1u << (index & 31u);
            uint word = base + (index >> 5u);
            // Neighbouring pixels mark the same pages: read first, so that most marks cost no atomic.
            if ((pageMarks[word] & bit) == 0u) atomicOr(pageMarks[word], bit);
        }
    }
}

// The pool slot of page `page` of `level` of view `viewIndex`, or PUNCTUAL_NO_SHADOW_PAGE where the
// allocation gave it none (outside the level's rectangle of entries, or unmarked inside it).
uint virtualPageSlot(uint viewIndex, uint level, uvec2 page) {
    uvec4 entry = virtualViews[viewIndex].levels[level];
    if (entry.x == PUNCTUAL_NO_SHADOW_PAGE) return PUNCTUAL_NO_SHADOW_PAGE;
    uvec2 local = page - uvec2(entry.y & 0xFFFFu, entry.y >> 16u);  // wraps past the rectangle's start
    uvec2 size = uvec2(entry.z & 0xFFFFu, entry.z >> 16u);
    if (local.x >= size.x || local.y >= size.y) return PUNCTUAL_NO_SHADOW_PAGE;
    return pageTable[entry.x + local.y * size.x + local.x];
}

// The atlas texel where pool slot `slot` starts (its top-left texel).
ivec2 virtualSlotOrigin(uint slot) {
    return ivec2(virtualShadowSlotOrigin(slot, frame.shadowPagePool.xy, frame.shadowPagePool.z, frame.shadowPagePool.w));
}

// The pages around one lookup, resolved through the table once: a filter reaching less than a page
// meets at most 2 x 2 pages, from `first`, whose slots' atlas origins its gathers then use. A page
// without a slot (one the filter does not read, at the block's edge) gets the lit slot, cleared to
// the far plane (frame.shadowPageSlots.x), so that no gather branches. (A table read, a slot's
// division and a branch per gather cost the forward pass 3x on lavapipe, measured.)
struct PageBlock {
    int last;       // the level's last texel (clamp to edge)
    ivec2 first;    // the block's first page
    ivec4 originX;  // the atlas origins of pages first + (0, 0), (1, 0), (0, 1), (1, 1)
    ivec4 originY;
};

ivec2 slotOriginOrLit(uint slot) {
    return virtualSlotOrigin(slot == PUNCTUAL_NO_SHADOW_PAGE ? frame.shadowPageSlots.x : slot);
}

// The page whose slot holds the texels corner - 1 and corner (its own texels and its neighbour's
// first: PUNCTUAL_VIRTUAL_SHADOW_SLOT).
ivec2 pageOfCorner(ivec2 corner) { return (corner - 1) / int(PUNCTUAL_VIRTUAL_SHADOW_PAGE); }

// The block of the pages holding the gathers whose corners lie within `reach` texels of `position`
// (texels of `level`).
PageBlock virtualPageBlock(uint viewIndex, uint level, vec2 position, float reach) {
    PageBlock block;
    block.last = int(PUNCTUAL_VIRTUAL_SHADOW_SIZE >> level) - 1;
    ivec2 low = pageOfCorner(clamp(ivec2(floor(position - reach)), ivec2(1), ivec2(block.last)));
    ivec2 high = pageOfCorner(clamp(ivec2(ceil(position + reach)), ivec2(1), ivec2(block.last)));
    block.first = low;
    uvec2 first = uvec2(low);
    ivec2 o0 = slotOriginOrLit(virtualPageSlot(viewIndex, level, first));
    ivec2 o1 = high.x > low.x ? slotOriginOrLit(virtualPageSlot(viewIndex, level, first + uvec2(1u, 0u))) : o0;
    ivec2 o2 = high.y > low.y ? slotOriginOrLit(virtualPageSlot(viewIndex, level, first + uvec2(0u, 1u))) : o0;
    ivec2 o3 = all(greaterThan(high, low)) ? slotOriginOrLit(virtualPageSlot(viewIndex, level, first + uvec2(1u))) : o0;
    block.originX = ivec4(o0.x, o1.x, o2.x, o3.x);
    block.originY = ivec4(o0.y, o1.y, o2.y, o3.y);
    return block;
}

// The 2 x 2 raw depths around texel corner `corner` (texels corner - 1 and corner on each axis; the
// corner clamped to [1, last], so that they stay in the level: clamp to edge), in textureGather's
// order: (u0, v1), (u1, v1), (u1, v0), (u0, v0). One gather from the slot of the corner's page.
vec4 virtualGather(PageBlock block, ivec2 corner) {
    corner = clamp(corner, ivec2(1), ivec2(block.last));
    ivec2 page = pageOfCorner(corner);
    ivec2 d = clamp(page - block.first, ivec2(0), ivec2(1));  // always 0 or 1: the block covers the filter
    int i = d.y * 2 + d.x;
    ivec2 atlas = ivec2(block.originX[i], block.originY[i]) + corner - page * int(PUNCTUAL_VIRTUAL_SHADOW_PAGE);
    return textureGather(shadowAtlasDepth, vec2(atlas) / frame.shadowAtlasSize, 0);
}

// The hardware's bilinear compare at `position` (texels of the block's level), from the four raw
// depths around it (bilinearCompare, shadows.h).
float virtualBilinearCompare(PageBlock block, vec2 position, float reference) {
    vec2 corner = bilinearCorner(position, float(block.last + 1));
    return bilinearCompare(virtualGather(block, ivec2(corner)), reference, bilinearFraction(position, corner));
}

#else  // the build without virtual pages: stubs (SHADOW_PAGES is PUNCTUAL_SHADOW_PAGES_OFF there)

struct PageBlock {
    int last;
};
uint virtualReadLevel(uint viewIndex, GpuShadowView view, float linearDepth, vec3 position) { return 0u; }
void markVirtualFootprint(uint viewIndex, uint level, vec2 uv) {}
PageBlock virtualPageBlock(uint viewIndex, uint level, vec2 position, float reach) { return PageBlock(0); }
vec4 virtualGather(PageBlock block, ivec2 corner) { return vec4(1.0); }
float virtualBilinearCompare(PageBlock block, vec2 position, float reference) { return 1.0; }

#endif
