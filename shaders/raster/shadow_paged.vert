#version 450
// shadow.vert for virtual shadow pages: each instance draws the caster into one page's layer of
// the drawing array (shadow_page_draw.glsl). A file of its own, not a specialization of
// shadow.vert: it writes gl_Layer, which needs a device feature (shaderOutputLayer) that only
// --shadow-res virtual should ask for.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "shadow_pages.h"

layout(std430, set = 0, binding = PUNCTUAL_BINDING_OBJECTS) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(push_constant) uniform ShadowDraw {
    mat4 viewProjection;  // unused: each instance's page has its own (shadow_page_draw.glsl)
    uint objectIndex;
} draw;

#include "shadow_page_draw.glsl"

layout(location = 0) in vec3 inPosition;

void main() {
    gl_Position = pagedShadowPosition(objects[draw.objectIndex].model * vec4(inPosition, 1.0), gl_InstanceIndex);
}
