// Virtual shadow pages: the paged casters' vertex shaders (shadow_paged.vert,
// shadow_paged_masked.vert) draw each caster once per page it meets, as instances (GLSL only). Instance i is
// pageDraws[i]: its view, level, page and pool slot. The vertex goes through the view's projection,
// then the slot's square of the view (virtualShadowPageNdc) is mapped onto the slot's square of the
// atlas; four clip distances cut every triangle at the page's edges, as a scissor per page would.
// One draw per (view, caster) instead of one per (page, caster): on lavapipe a draw costs about
// 50 us whatever it draws (the hall's 9,256 pages took 23,000 draws), and on a GPU each draw is
// CPU work and state.

layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_VIEWS) readonly buffer ShadowViewBlock { GpuShadowView shadowViews[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_PAGE_DRAWS) readonly buffer PageDrawBlock { uvec4 pageDraws[]; };
layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };

out gl_PerVertex {
    vec4 gl_Position;
    float gl_ClipDistance[4];
};

// The clip position of world point `world` drawn into instance `instance`'s page, with the clip
// distances that keep it inside the page's slot.
vec4 pagedShadowPosition(vec4 world, uint instance) {
    uvec4 page = pageDraws[instance];  // view, level, column | row << 16, slot
    vec4 clip = shadowViews[page.x].viewProjection * world;
    vec3 square = virtualShadowPageNdc(page.y, uvec2(page.z & 0xFFFFu, page.z >> 16u));
    vec2 local = (clip.xy - square.xy * clip.w) / square.z;  // the page's own clip space: [-w, w]
    gl_ClipDistance[0] = clip.w - local.x;
    gl_ClipDistance[1] = clip.w + local.x;
    gl_ClipDistance[2] = clip.w - local.y;
    gl_ClipDistance[3] = clip.w + local.y;
    // The slot's square in the atlas's NDC: its centre and half side.
    vec2 origin = vec2(virtualShadowSlotOrigin(page.w, frame.shadowPagePool.xy, frame.shadowPagePool.z, frame.shadowPagePool.w));
    vec2 halfSide = float(PUNCTUAL_VIRTUAL_SHADOW_SLOT) / frame.shadowAtlasSize;
    vec2 centre = (origin + 0.5 * float(PUNCTUAL_VIRTUAL_SHADOW_SLOT)) / frame.shadowAtlasSize * 2.0 - 1.0;
    return vec4(centre * clip.w + halfSide * local, clip.z, clip.w);
}
