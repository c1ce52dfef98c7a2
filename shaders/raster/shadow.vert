#version 450
// Shadow casters into one shadow view (a spot frustum or a point-light face). Depth only; no
// depth clamp, so casters in front of the near plane are clipped rather than flattened onto it
// ("no pancaking": for spot and point lights pancaking would leak light).
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"

// The failure study's "pancaking" (Unity's ShadowCaster clamp): vertex depth clamped onto the
// near plane, which distorts the depth interpolated across triangles that cross it. Off for
// every real render.
layout(constant_id = 0) const bool PANCAKING = false;

layout(std430, set = 0, binding = PUNCTUAL_BINDING_OBJECTS) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(push_constant) uniform ShadowDraw {
    mat4 viewProjection;
    uint objectIndex;
} draw;

layout(location = 0) in vec3 inPosition;

void main() {
    gl_Position = draw.viewProjection * (objects[draw.objectIndex].model * vec4(inPosition, 1.0));
    if (PANCAKING) gl_Position.z = max(gl_Position.z, 0.0);  // Vulkan depth: the near plane is z = 0
}
