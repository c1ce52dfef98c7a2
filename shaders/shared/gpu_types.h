// Limits and GPU struct layouts, shared by C++ and GLSL (std430 for buffers, std140-compatible
// for the frame uniform: every member is a vec4/mat4 or packs into one). The C++ side checks
// every size and offset with static_asserts in src/vk/gpu_types_check.cpp.
#ifndef PUNCTUAL_GPU_TYPES_H
#define PUNCTUAL_GPU_TYPES_H

#include "glsl_cpp.h"

// Per-frame light caps. 64 spot + 32 point lights let a tile's light list be three 32-bit words
// (a 64-bit spot mask and a 32-bit point mask), which is what makes culled and brute-force
// images bit-identical: set bits are walked in the same ascending order the brute loop uses.
#define PUNCTUAL_MAX_SPOT_LIGHTS 64
#define PUNCTUAL_MAX_POINT_LIGHTS 32
// Unity's classic forward path gives each object at most 8 lights.
#define PUNCTUAL_MAX_LIGHTS_PER_OBJECT 8

// Descriptor bindings of the frame's set 0 (one set for every pass keeps pipelines simple).
#define PUNCTUAL_BINDING_FRAME 0
#define PUNCTUAL_BINDING_LIGHTS 1
#define PUNCTUAL_BINDING_OBJECTS 2
#define PUNCTUAL_BINDING_MATERIALS 3
#define PUNCTUAL_BINDING_TEXTURES 4

// Specialization constant ids.
#define PUNCTUAL_SPEC_TEXTURE_COUNT 0

PUNCTUAL_NAMESPACE_BEGIN

// A spot or point light. Spots and points share one struct: a point light is a spot whose
// angular attenuation is constant 1 (scale 0, offset 1), so one loop body serves both.
struct GpuPunctualLight {
    vec4 positionInvRangeSq;   // xyz: world position; w: 1 / max(range^2, 1e-4)
    vec4 radiantColor;         // rgb: linear colour x intensity (candela); w: range (metres)
    vec4 directionAngleScale;  // xyz: unit direction the light shines (node -Z); w: k = 1/max(cosInner - cosOuter, 1e-4), 0 for points
    vec4 angleOffsetShadow;    // x: -cosOuter * k (1 for points); y: shadow slot or -1; zw: reserved
};

struct GpuDirectionalLight {
    vec4 directionToLight;  // xyz: unit vector from the surface towards the light; w: 1 if present
    vec4 illuminance;       // rgb: linear colour x intensity (lux)
};

struct GpuFrame {
    mat4 view;
    mat4 projection;
    mat4 viewProjection;
    mat4 inverseViewProjection;
    vec4 cameraPosition;  // xyz: world position
    vec4 viewport;        // xy: size in pixels; zw: 1 / size
    uvec4 lightCounts;    // x: spot lights, y: point lights (stored after the spots), z: directional (0/1)
    vec4 exposure;        // x: linear exposure multiplier applied before tone mapping
    GpuDirectionalLight sun;
};

struct GpuObject {
    mat4 model;
    mat4 normalMatrix;  // inverse transpose of model (mat4 keeps std430 and C++ layouts equal)
    uvec4 material;     // x: material index
};

struct GpuMaterial {
    vec4 baseColorFactor;  // linear RGBA
    vec2 metallicRoughness;
    int baseColorTexture;  // index into the texture array, -1 for none
    uint flags;            // reserved
};

PUNCTUAL_NAMESPACE_END

#endif
