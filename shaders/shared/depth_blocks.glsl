// The prepass depth read 2x2 pixels at a time, and the rectangle of marked columns and rows, for
// the culling kernels (light_culling.comp, tile_culling.comp, cluster_culling.comp). GLSL only (it
// gathers); include in a shader that declares `depthImage` (the prepass depth, clamp-to-edge) and
// `frame` (GpuFrame), after culling.h.

// `extent` (nearest depth, farthest depth) widened by the geometry of the 2x2 block whose top-left
// pixel is `corner`, its pixels at or past `tileEnd` left out. One gather fetches the block (fewer
// fetches and address computations than four single-texel reads). It samples the block's centre,
// (corner + 1) / size: u * width - 0.5 = corner + 0.5, whose floor is the corner, half a texel from
// any rounding; texels past the image's edge read the edge (clamp-to-edge sampler) and are left out
// with the rest past tileEnd. Its result's order (the Vulkan specification's): x (0,1), y (1,1),
// z (1,0), w (0,0) from the corner. Written out rather than looped: lavapipe keeps a dynamically
// indexed vector in memory. An extent with x = 0 holds no geometry.
vec2 quadExtent(uvec2 corner, uvec2 tileEnd, vec2 extent) {
    if (corner.x >= tileEnd.x || corner.y >= tileEnd.y) return extent;
    vec4 quad = textureGather(depthImage, (vec2(corner) + 1.0) * frame.viewport.zw);
    bool right = corner.x + 1u < tileEnd.x;
    bool below = corner.y + 1u < tileEnd.y;
    // Background texels (depth 0) never raise the nearest; they are kept out of the farthest.
    const float kNone = 2.0;  // above any depth: min() ignores it
    vec4 geometry = vec4(below && !isBackgroundDepth(quad.x) ? quad.x : kNone,
                         right && below && !isBackgroundDepth(quad.y) ? quad.y : kNone,
                         right && !isBackgroundDepth(quad.z) ? quad.z : kNone, !isBackgroundDepth(quad.w) ? quad.w : kNone);
    vec4 nearest = vec4(below ? quad.x : 0.0, right && below ? quad.y : 0.0, right ? quad.z : 0.0, quad.w);
    return vec2(max(extent.x, max(max(nearest.x, nearest.y), max(nearest.z, nearest.w))),
                min(extent.y, min(min(geometry.x, geometry.y), min(geometry.z, geometry.w))));
}

// The NDC rectangle (min corner in xy, max corner in zw) of the pixels of a tile whose top-left
// pixel is `tileOrigin` that lie in the tile-local columns set in `columns` and rows set in `rows`
// (bit i: column or row i): from the first column's left edge to the last one's right edge, cut at
// the viewport. The culling kernels cut a slice's or depth cell's segment to it.
vec4 columnsRowsRectNdc(uvec2 tileOrigin, uint columns, uint rows, vec2 pixelToNdc) {
    uvec2 first = tileOrigin + uvec2(findLSB(columns), findLSB(rows));
    uvec2 last = tileOrigin + uvec2(findMSB(columns), findMSB(rows)) + 1u;
    vec2 a = vec2(first) * pixelToNdc - 1.0;
    vec2 b = min(vec2(last), frame.viewport.xy) * pixelToNdc - 1.0;
    return vec4(min(a, b), max(a, b));
}

// The depth-mask cells (culling.h, tiled-2.5d) the geometry of the 2x2 block whose top-left pixel
// is `corner` occupies, its pixels at or past `tileEnd` left out (quadExtent's block and gather).
uint quadDepthCells(uvec2 corner, uvec2 tileEnd, float maskNear, float maskScale) {
    if (corner.x >= tileEnd.x || corner.y >= tileEnd.y) return 0u;
    vec4 quad = textureGather(depthImage, (vec2(corner) + 1.0) * frame.viewport.zw);
    bool right = corner.x + 1u < tileEnd.x;
    bool below = corner.y + 1u < tileEnd.y;
    vec2 toView = frame.depthToView.xy;
    uint cells = 0u;
    if (!isBackgroundDepth(quad.w)) cells |= 1u << depthMaskCell(viewDistanceFromDepth(quad.w, toView), maskNear, maskScale);
    if (right && !isBackgroundDepth(quad.z)) cells |= 1u << depthMaskCell(viewDistanceFromDepth(quad.z, toView), maskNear, maskScale);
    if (below && !isBackgroundDepth(quad.x)) cells |= 1u << depthMaskCell(viewDistanceFromDepth(quad.x, toView), maskNear, maskScale);
    if (right && below && !isBackgroundDepth(quad.y)) {
        cells |= 1u << depthMaskCell(viewDistanceFromDepth(quad.y, toView), maskNear, maskScale);
    }
    return cells;
}
