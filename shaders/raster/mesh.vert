#version 450
// The one vertex shader of the depth prepass and the forward pass. Both passes run this same
// code with the same inputs, and the position math is `precise` (no fused multiply-adds a
// compiler could choose differently per pipeline), so both compute bit-identical depths, which
// the forward pass's EQUAL depth test relies on. (`invariant gl_Position` would say the same, but
// glslang 12 puts it on a gl_PerVertex member, which current validation layers reject.)
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_OBJECTS) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(push_constant) uniform DrawConstants { uint objectIndex; } draw;

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec2 inUv1;

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec2 outUv1;
// The object, for fragment shaders without the push constant's copy (alpha_mask.frag is shared
// with the shadow caster passes).
layout(location = 4) flat out uint outObject;

void main() {
    GpuObject object = objects[draw.objectIndex];
    precise vec4 world = object.model * vec4(inPosition, 1.0);
    outWorldPosition = world.xyz;
    outWorldNormal = mat3(object.normalMatrix) * inNormal;
    outUv = inUv;
    outUv1 = inUv1;
    outObject = draw.objectIndex;
    precise vec4 clip = frame.viewProjection * world;
    gl_Position = clip;
}
