// The sun's cascaded shadow maps (seed: catlike-directional-cascaded-shadows.md), shared by the C++
// cascade setup (lights/cascade_setup.h), the forward shader and the validation: where the
// cascades split the view, the sphere each covers, where its projection sits, which cascade a
// receiver reads, and how shadows fade between cascades and at the shadow distance.
#ifndef PUNCTUAL_CASCADES_H
#define PUNCTUAL_CASCADES_H

#include "glsl_cpp.h"

PUNCTUAL_NAMESPACE_BEGIN

// ---- splits -------------------------------------------------------------------------------------

// The practical split scheme (Zhang et al., "Parallel-split shadow maps", 2006): the far end of the
// cascade that ends at `fraction` (i / n) of the range [nearPlane, farPlane] blends
//   the logarithmic split  near (far / near)^fraction, where every cascade spans the same ratio
//                          of distances and so the same texels per screen pixel at its two ends;
//   the linear split       near + (far - near) fraction, which the log split starves at the far end
// by lambda (1: logarithmic, 0: linear).
PUNCTUAL_FN float practicalSplit(float nearPlane, float farPlane, float fraction, float lambda) {
    float logarithmic = nearPlane * pow(farPlane / nearPlane, fraction);
    float linear = nearPlane + (farPlane - nearPlane) * fraction;
    return linear + (logarithmic - linear) * lambda;
}

// ---- culling spheres ----------------------------------------------------------------------------

// The smallest sphere around the slice of the camera's frustum between the distances d0 and d1
// along its axis. `spread` = tan^2(half fov x) + tan^2(half fov y): a corner of the slice at
// distance d lies d sqrt(spread) off the axis. By symmetry the centre lies on the axis, at c
// with the near and far corners equally far:
//   (c - d0)^2 + d0^2 spread = (d1 - c)^2 + d1^2 spread
//   (d1 - d0) (2c - d0 - d1) = (d1 - d0) (d1 + d0) spread  =>  c = (d0 + d1) (1 + spread) / 2.
// When that lies beyond d1 (a wide, short slice), the far face's circumscribed circle holds the
// near corners too, and the sphere centred on the far face is the smallest.
// Returns x: the centre's distance along the camera's axis, y: the radius. The radius depends on
// d0, d1 and the field of view only, never on where the camera looks: the cascade's projection
// keeps its size as the camera turns, which is what lets texel snapping hold it still.
PUNCTUAL_FN vec2 sliceBoundingSphere(float d0, float d1, float spread) {
    float centre = min(0.5f * (d0 + d1) * (1.0f + spread), d1);
    float farOffset = d1 - centre;
    return vec2(centre, sqrt(farOffset * farOffset + d1 * d1 * spread));
}

// ---- projection ----------------------------------------------------------------------------------

// World size of one texel of a cascade: its orthographic projection spans the sphere's diameter
// across `resolution` texels, at every depth.
PUNCTUAL_FN float cascadeTexelWorldSize(float radius, float resolution) { return 2.0f * radius / resolution; }

// Texel snapping: the cascade's centre in the light's view plane, moved to a whole number of
// texels. The light's axes do not turn with the camera, so as the camera moves the projection
// moves in whole texels only, every texel keeps covering the same square of the world, and shadow
// edges stay put instead of crawling (shimmering) from frame to frame.
PUNCTUAL_FN vec2 snapToTexels(vec2 centre, float texel) { return floor(centre / texel + 0.5f) * texel; }

// ---- which cascade ------------------------------------------------------------------------------

// The first cascade whose sphere (xyz centre, w radius squared) holds `position`, or `count` when
// none does (beyond the shadow distance: no shadow). The radii given here are the culling
// spheres shrunk by the filter's reach (CascadeSetup), so that a receiver's filter never reads past
// its cascade's map (the seed's "cullingSphere.w -= filterSize").
PUNCTUAL_FN uint cascadeOf(vec3 position, vec4 sphere0, vec4 sphere1, vec4 sphere2, vec4 sphere3, uint count) {
    vec3 d0 = position - vec3(sphere0);
    vec3 d1 = position - vec3(sphere1);
    vec3 d2 = position - vec3(sphere2);
    vec3 d3 = position - vec3(sphere3);
    if (count > 0u && dot(d0, d0) < sphere0.w) return 0u;
    if (count > 1u && dot(d1, d1) < sphere1.w) return 1u;
    if (count > 2u && dot(d2, d2) < sphere2.w) return 2u;
    if (count > 3u && dot(d3, d3) < sphere3.w) return 3u;
    return count;
}

// ---- fades --------------------------------------------------------------------------------------

// The seed's FadedShadowStrength: a linear ramp from 1 to 0 as `distance` x `scale` goes from
// 1 - 1 / fade to 1, i.e. saturate((1 - distance scale) fade).
//  - At the shadow distance D with fade range f (a share of D): distance = the view depth,
//    scale = 1 / D, fade = 1 / f: the shadow fades out over the last f D before D.
//  - Across a cascade's edge: distance = squared distance from the sphere's centre, scale =
//    1 / r^2, fade = 1 / (1 - (1 - f)^2): the ramp covers the outer share f of the radius (from
//    (1 - f) r to r), measured in squared distances as the selection already has them.
PUNCTUAL_FN float fadedShadowStrength(float distance, float scale, float fade) {
    return clamp((1.0f - distance * scale) * fade, 0.0f, 1.0f);
}

// The ramp's `fade` argument for a cascade fade covering the outer share f of each radius.
PUNCTUAL_FN float cascadeFadeScale(float share) {
    float inner = 1.0f - share;
    return 1.0f / max(1.0f - inner * inner, 1e-6f);
}

// Interleaved gradient noise (Jimenez, "Next generation post processing in Call of Duty: Advanced
// Warfare", 2014): a per-pixel threshold in [0, 1) from the pixel's position, the seed's dither
// between cascades. Fixed per pixel, so the same frame dithers the same way every run.
PUNCTUAL_FN float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189f * fract(dot(pixel, vec2(0.06711056f, 0.00583715f))));
}

PUNCTUAL_NAMESPACE_END

#endif
