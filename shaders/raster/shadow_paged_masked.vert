#version 450
// shadow_paged.vert for alpha-masked casters: the same position math, plus what alpha_mask.frag
// tests (shadow_masked.vert's interface).
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "shadow_pages.h"

layout(std430, set = 0, binding = PUNCTUAL_BINDING_OBJECTS) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(push_constant) uniform ShadowDraw {
    mat4 viewProjection;  // unused
    uint objectIndex;
} draw;

#include "shadow_page_draw.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec2 inUv1;

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;  // not needed by the alpha test: zero
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec2 outUv1;
layout(location = 4) flat out uint outObject;

void main() {
    vec4 world = objects[draw.objectIndex].model * vec4(inPosition, 1.0);
    gl_Position = pagedShadowPosition(world, gl_InstanceIndex);
    outWorldPosition = world.xyz;
    outWorldNormal = vec3(0.0);
    outUv = inUv;
    outUv1 = inUv1;
    outObject = draw.objectIndex;
}
