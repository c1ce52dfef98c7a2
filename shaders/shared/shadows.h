// Shadow-map geometry shared by the C++ shadow setup and the forward shader: cube-face selection
// and orientation, depth mapping along a face's axis, and the receiver bias of the design notes.
#ifndef PUNCTUAL_SHADOWS_H
#define PUNCTUAL_SHADOWS_H

#include "glsl_cpp.h"

PUNCTUAL_NAMESPACE_BEGIN

// The cube face a direction falls on, in Vulkan's order +X -X +Y -Y +Z -Z: the axis of the
// largest component (ties go to X, then Y, as the hardware does).
PUNCTUAL_FN uint cubeFaceOfDirection(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0f ? 0u : 1u;
    if (a.y >= a.z) return d.y >= 0.0f ? 2u : 3u;
    return d.z >= 0.0f ? 4u : 5u;
}

// A face's unit axis (the direction its centre looks along).
PUNCTUAL_FN vec3 cubeFaceAxis(uint face) {
    float s = (face & 1u) == 0u ? 1.0f : -1.0f;
    if (face < 2u) return vec3(s, 0.0f, 0.0f);
    if (face < 4u) return vec3(0.0f, s, 0.0f);
    return vec3(0.0f, 0.0f, s);
}

// The face's texture axes as Vulkan defines cube sampling (spec, "Cube Map Face Selection"):
// for a direction r on face f, s = (sc / |ma| + 1) / 2 and t = (tc / |ma| + 1) / 2 with
//   +X: sc = -rz, tc = -ry   -X: sc = +rz, tc = -ry
//   +Y: sc = +rx, tc = +rz   -Y: sc = +rx, tc = -rz
//   +Z: sc = +rx, tc = -ry   -Z: sc = -rx, tc = -ry
// cubeFaceU/V return the world directions along which s and t grow. Rendering a face with
// clip.x = dot(r, U), clip.y = dot(r, V), clip.w = dot(r, axis) writes texels exactly where the
// hardware will later read them, with no per-face flips to remember.
PUNCTUAL_FN vec3 cubeFaceU(uint face) {
    if (face == 0u) return vec3(0.0f, 0.0f, -1.0f);
    if (face == 1u) return vec3(0.0f, 0.0f, 1.0f);
    if (face == 5u) return vec3(-1.0f, 0.0f, 0.0f);
    return vec3(1.0f, 0.0f, 0.0f);
}

PUNCTUAL_FN vec3 cubeFaceV(uint face) {
    if (face == 2u) return vec3(0.0f, 0.0f, 1.0f);
    if (face == 3u) return vec3(0.0f, 0.0f, -1.0f);
    return vec3(0.0f, -1.0f, 0.0f);
}

// Perspective depth (0 at near, 1 at far) of a point at distance `linearDepth` along a view's
// axis: depth = f (d - n) / (d (f - n)) = A + B / d with A = f / (f - n), B = -f n / (f - n),
// the same mapping a Vulkan perspective projection (depth 0..1) gives.
PUNCTUAL_FN float perspectiveDepth(float linearDepth, float nearPlane, float farPlane) {
    return farPlane * (linearDepth - nearPlane) / (linearDepth * (farPlane - nearPlane));
}

// World size of one shadow-map texel at a receiver `linearDepth` along the view's axis. A view
// (a spot frustum or a cube face) spans `tanSpan` = 2 tan(field of view / 2) at unit depth across
// `resolution` texels, so one texel spans tanSpan / resolution at unit depth and grows linearly
// with depth. The same size scales the receiver bias (applyShadowBias) and sizes the view
// (shadow_resolution.h).
PUNCTUAL_FN float shadowTexelWorldSize(float linearDepth, float tanSpan, float resolution) {
    return linearDepth * tanSpan / resolution;
}

// World size of one screen pixel on a surface at `viewDepth` along the camera's axis: the frame
// spans 2 tan(yfov / 2) at unit depth over `height` pixels (square pixels), so
// pixelSpanAtUnitDepth = 2 tan(yfov / 2) / height. Surfaces seen at a slant cover more world per
// pixel along the slant; this is the size across the line of sight, the smallest.
PUNCTUAL_FN float screenPixelWorldSize(float viewDepth, float pixelSpanAtUnitDepth) {
    return viewDepth * pixelSpanAtUnitDepth;
}

// The resolution (texels a side) at which one texel of a view covers exactly one screen pixel at a
// receiver: solve shadowTexelWorldSize(linearDepth, tanSpan, r) = pixelWorldSize for r.
//   r = linearDepth tanSpan / pixelWorldSize.
// The density (texels per pixel, 1 the target) of a view of resolution R there is R / r.
PUNCTUAL_FN float resolutionForOneTexelPerPixel(float linearDepth, float tanSpan, float pixelWorldSize) {
    return linearDepth * tanSpan / pixelWorldSize;
}

// ApplyShadowBias (custom SRP, "Shadow Bias and PCF"): moves the receiver towards the light (L)
// and along its normal (N) by multiples of the shadow-map texel's world size at the receiver,
// widened by the filter's penumbra (in texels):
//   depth bias        texel (1 + p) bias.x L
//   slope-scaled      texel (1 + p) tan(theta) bias.y L     (tan clamped to 50)
//   normal offset     texel (1 + p) bias.z N
//   sin-scaled normal texel (1 + p) sin(theta) bias.w N
// where theta is the angle between N and L. Grazing receivers (large tan) move further, which is
// what keeps acne away at up to 80 degrees.
PUNCTUAL_FN vec3 applyShadowBias(vec3 position, vec3 normal, vec3 toLight, float texelSize, float penumbraTexels,
                                 vec4 bias) {
    float cosTheta = clamp(dot(normal, toLight), 0.0f, 1.0f);
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    float tanTheta = clamp(sinTheta / max(cosTheta, 1e-4f), 0.0f, 50.0f);
    float scale = texelSize * (1.0f + penumbraTexels);
    return position + toLight * (scale * (bias.x + tanTheta * bias.y)) + normal * (scale * (bias.z + sinTheta * bias.w));
}

// Receiver-plane depth (Isidoro, "Shadow mapping: GPU-based tips and techniques", GDC 2006): the
// slope of the receiver's depth across a shadow view, so that each texel a filter reads is
// compared with the receiver's own depth under that texel rather than under the sample point. The
// notes' bias has to cover the difference (the slope times the filter's reach), which is why it
// grows with the penumbra; this compare does not need it to.
//
// The plane through `position` with normal `normal` maps, under the view's perspective projection
// VP, to a plane in the view's NDC: with w affine over a world plane, x/w, y/w and z/w are ratios
// of affine functions with the same denominator, and eliminating the two plane parameters leaves
// z_ndc affine in (x_ndc, y_ndc). So one gradient gives the depth under every texel, exactly.
// The slope comes from the normal, not from screen derivatives, which the forward shader's
// per-light loop (non-uniform control flow) leaves undefined. With s, t two unit tangents and
// c = VP (position, 1):
//   d(ndc)/ds = ((VP s).xyz c.w - c.xyz (VP s).w) / c.w^2    (quotient rule; s a direction, w = 0)
//   J = [d(uv)/ds  d(uv)/dt] with uv = ndc.xy / 2 + 1/2, so d(uv) = d(ndc.xy) / 2
//   dz/d(uv) = [dz/ds  dz/dt] J^-1                             (chain rule, row vector)
// Returns dz/du, dz/dv (NDC depth per UV unit of the view). A plane seen edge-on (J singular:
// every texel under it is the same line) has no defined slope and returns 0.
PUNCTUAL_FN vec2 receiverPlaneDepthSlope(mat4 viewProjection, vec3 position, vec3 normal) {
    vec3 s = normalize(abs(normal.x) > 0.5f ? cross(normal, vec3(0.0f, 1.0f, 0.0f)) : cross(normal, vec3(1.0f, 0.0f, 0.0f)));
    vec3 t = cross(normal, s);
    vec4 c = viewProjection * vec4(position, 1.0f);
    vec4 cs = viewProjection * vec4(s, 0.0f);
    vec4 ct = viewProjection * vec4(t, 0.0f);
    vec3 ds = (vec3(cs) * c.w - vec3(c) * cs.w) / (c.w * c.w);
    vec3 dt = (vec3(ct) * c.w - vec3(c) * ct.w) / (c.w * c.w);
    mat2 uvJacobian = mat2(0.5f * vec2(ds), 0.5f * vec2(dt));  // columns d(uv)/ds, d(uv)/dt
    // Singular relative to the Jacobian's own scale (metres per texel vary with the scene's units).
    float det = determinant(uvJacobian);
    if (abs(det) <= 1e-6f * (dot(uvJacobian[0], uvJacobian[0]) + dot(uvJacobian[1], uvJacobian[1]))) return vec2(0.0f);
    return vec2(ds.z, dt.z) * inverse(uvJacobian);
}

// A bilinear compare (the hardware's sampler2DShadow tap) in the shader, from the four raw depths
// around the sample point (one textureGather), so that it depends only on the sample's place in
// its own view's texels: the hardware tap takes the atlas's UV, into which the view's square
// enters in floating point, and so rounds differently where the square lies elsewhere (the shadow
// cache's atlas). `position` is the sample point in texels of a square `side` texels wide (texel
// i's centre at i + 1/2). The four texels nearest it are corner - 1 and corner on each axis, the
// corner they share being floor(position + 1/2), kept in [1, side - 1] so that the four stay in
// the square (clamp to edge).
PUNCTUAL_FN vec2 bilinearCorner(vec2 position, float side) {
    return clamp(floor(position + 0.5f), vec2(1.0f), vec2(side - 1.0f));
}

// The sample's place between the four texel centres around `corner` (0 at corner - 1's centre,
// corner - 1/2; 1 at corner's, corner + 1/2), each axis in [0, 1].
PUNCTUAL_FN vec2 bilinearFraction(vec2 position, vec2 corner) {
    return clamp(position + 0.5f - corner, vec2(0.0f), vec2(1.0f));
}

// The four compares weighted by the fractions `f`: each is 1 (lit) where the reference is no
// deeper than the caster (VK_COMPARE_OP_LESS_OR_EQUAL, as the compare sampler), `casters` in
// textureGather's order (u0, v1), (u1, v1), (u1, v0), (u0, v0).
PUNCTUAL_FN float bilinearCompare(vec4 casters, float reference, vec2 f) {
    float u0v1 = reference <= casters.x ? 1.0f : 0.0f;
    float u1v1 = reference <= casters.y ? 1.0f : 0.0f;
    float u1v0 = reference <= casters.z ? 1.0f : 0.0f;
    float u0v0 = reference <= casters.w ? 1.0f : 0.0f;
    return mix(mix(u0v0, u1v0, f.x), mix(u0v1, u1v1, f.x), f.y);
}

PUNCTUAL_NAMESPACE_END

#endif
