// Virtual shadow pages: the paged casters' vertex shaders (shadow_paged.vert,
// shadow_paged_masked.vert) draw each caster once per page it meets, as instances (GLSL only).
// Instance i is pageDraws[i]: its view, level, page, and the layer of the drawing array it is
// drawn into (render/shadow_page_layers.h). The vertex goes through the view's projection, then
// the slot's square of the view (virtualShadowPageNdc) is stretched over the whole layer, 33 x 33
// texels: the viewport's clipping cuts every triangle at the slot's edges. Each page is so
// rasterized at the same origin whichever slot of the pool it is copied into, and a page kept
// from an earlier frame (--shadow-cache on) is the page this frame would draw, bit for bit.
// One draw per (view, caster) instead of one per (page, caster): on lavapipe a draw costs about
// 50 us whatever it draws (the hall's 9,256 pages took 23,000 draws), and on a GPU each draw is
// CPU work and state.
#extension GL_ARB_shader_viewport_layer_array : require

layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_VIEWS) readonly buffer ShadowViewBlock { GpuShadowView shadowViews[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_SHADOW_PAGE_DRAWS) readonly buffer PageDrawBlock { uvec4 pageDraws[]; };

// The clip position of world point `world` drawn into instance `instance`'s page (its layer set).
vec4 pagedShadowPosition(vec4 world, uint instance) {
    uvec4 page = pageDraws[instance];  // view, level, column | row << 16, layer
    vec4 clip = shadowViews[page.x].viewProjection * world;
    vec3 square = virtualShadowPageNdc(page.y, uvec2(page.z & 0xFFFFu, page.z >> 16u));
    vec2 local = (clip.xy - square.xy * clip.w) / square.z;  // the slot's own clip space: [-w, w]
    gl_Layer = int(page.w);
    return vec4(local, clip.z, clip.w);
}
