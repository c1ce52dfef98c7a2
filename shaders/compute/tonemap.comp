#version 450
// Tone mapping: exposure, ACES fit, sRGB encoding, 8-bit quantisation (packUnorm4x8 rounds to
// nearest, the same rule the CPU reference uses). Writes packed RGBA8 words, one per pixel, rows
// top to bottom, ready for readback and PNG encoding.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "shading.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D hdrImage;
layout(std430, set = 0, binding = 1) writeonly buffer OutputBlock { uint pixels[]; };
layout(push_constant) uniform ToneMapConstants {
    uvec2 size;
    float exposure;
} constants;

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= constants.size.x || pixel.y >= constants.size.y) return;
    vec3 radiance = texelFetch(hdrImage, ivec2(pixel), 0).rgb;
    vec3 display = linearToSrgb3(toneMapAces(radiance, constants.exposure));
    pixels[pixel.y * constants.size.x + pixel.x] = packUnorm4x8(vec4(display, 1.0));
}
