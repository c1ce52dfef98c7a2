// The N x N tent shadow filters (N = 3, 5, 7) as Unity's SampleShadow_ComputeSamples_Tent_NxN
// (Core RP, ShadowSamplingTent.hlsl) computes them: ((N + 1) / 2)^2 bilinear compare fetches whose
// weights and positions depend on where the sample point falls inside its texel, so that together
// they weigh every texel by the exact integral of a continuous tent over it. Shared by the forward
// shader (shadow_sampling.glsl) and the unit test that checks it against brute force
// (tests/unit/test_shadow_tent.cpp).
//
// One axis (the tent is separable: weight(x, y) = weight(x) weight(y)), in texel units, texel j
// covering [j, j + 1] with its centre at j + 0.5:
//
//   The tent: a triangle of base N texels (half-width h = N / 2) and area 1 centred on the sample
//   point t (= uv x resolution), T(x) = max(h - |x - t|, 0) / h^2.
//
//   Its texels: c = floor(t + 0.5) is the texel corner nearest to t, and o = t - c, in
//   [-0.5, 0.5), is where t lies from it. The tent's support [t - h, t + h] then lies within
//   [c - h - 0.5, c + h + 0.5], which is N + 1 whole texels (h + 0.5 = (N + 1) / 2 on each side
//   of the corner c). Texel j = 0 .. N of them has its centre at c - h + j, that is at
//   x_j = j - h - o from the sample point.
//
//   A texel's weight is the integral of T over it (tentTexelWeight below): with d = |x_j| the
//   distance of its centre from the apex,
//   - the apex inside it (d < 0.5): T is linear on either side of the apex, and the mean of
//     |x - t| over the texel is 0.25 + d^2, so the weight is (h - 0.25 - d^2) / h^2;
//   - otherwise T is linear over the part of the texel it covers, h - |x - t| running from
//     h - d + 0.5 at the texel's inner edge to h - d - 0.5 at its outer edge. Integrating the
//     ramp max(y, 0) gives (max(h - d + 0.5, 0)^2 - max(h - d - 0.5, 0)^2) / (2 h^2): the
//     midpoint value (h - d) / h^2 for a texel wholly under the tent, and the small triangle
//     (0.5 -+ o)^2 / (2 h^2) for the two end texels it covers only in part.
//   The N + 1 weights sum to 1 (they tile the support).
//
//   Its fetches: texels 2m and 2m + 1 (m = 0 .. (N - 1) / 2) form one pair, read by one bilinear
//   compare fetch. A bilinear fetch at texel coordinate q between the centres of texels a and
//   a + 1 returns (1 - f) cmp(a) + f cmp(a + 1) with f = q - (a + 0.5). Putting the fetch at
//   f = w(2m + 1) / (w(2m) + w(2m + 1)) and weighting it by w(2m) + w(2m + 1) gives both texels
//   exactly their tent weights. In 2D each fetch reads 2 x 2 texels with the product of the two
//   axes' weights, so (N + 1) / 2 fetches per axis cover the (N + 1) x (N + 1) texels:
//   3x3: 2 x 2 = 4 fetches, 5x5: 3 x 3 = 9, 7x7: 4 x 4 = 16.
//
// A pair's weight is never 0: its inner texel lies wholly under the tent (the last pair's outer
// texel may have weight 0, at o = -0.5, the first pair's never does), so the division is safe.
#ifndef PUNCTUAL_SHADOW_TENT_H
#define PUNCTUAL_SHADOW_TENT_H

#include "glsl_cpp.h"

PUNCTUAL_NAMESPACE_BEGIN

// Bilinear fetches along one axis of the N x N tent, and in all.
PUNCTUAL_CONSTEXPR_FN uint tentFetchesPerAxis(uint n) { return (n + 1u) / 2u; }
PUNCTUAL_CONSTEXPR_FN uint tentFetchCount(uint n) { return tentFetchesPerAxis(n) * tentFetchesPerAxis(n); }

// Integral of the unit-area tent of half-width h centred at 0 over the texel [x - 0.5, x + 0.5].
PUNCTUAL_FN float tentTexelWeight(float x, float h) {
    float d = abs(x);
    float invArea = 1.0f / (h * h);
    if (d < 0.5f) return (h - 0.25f - d * d) * invArea;  // the apex lies inside this texel
    float inner = max(h - d + 0.5f, 0.0f);
    float outer = max(h - d - 0.5f, 0.0f);
    return 0.5f * (inner * inner - outer * outer) * invArea;
}

// Where the sample point lies from the texel corner nearest to it, per axis: o = t - floor(t + 0.5)
// in [-0.5, 0.5), for t the sample point in texel units (uv x resolution).
PUNCTUAL_FN vec2 tentCornerOffset(vec2 texelPosition) { return texelPosition - floor(texelPosition + 0.5f); }

// Texel pair m (0 .. tentFetchesPerAxis(n) - 1) along one axis, texels 2m and 2m + 1 of the
// N + 1 the tent touches, for a sample point at `o` from its nearest texel corner: x = the centre
// of texel 2m relative to the sample point, in texels (texel 2m + 1's is one further), y and z =
// the two texels' tent weights. N = 1 is the hardware's 2 x 2 footprint: the sample point's
// bilinear weights (0.5 - o and 0.5 + o, one minus each centre's distance), which the "tent" of
// base 1 would not give (it is a triangle, bilinear filtering a box).
PUNCTUAL_FN vec3 tentAxisTexelPair(float o, uint n, uint m) {
    float h = 0.5f * float(n);
    float first = float(2u * m) - h - o;  // centre of texel 2m, from the sample point
    if (n == 1u) return vec3(first, 1.0f - abs(first), 1.0f - abs(first + 1.0f));
    return vec3(first, tentTexelWeight(first, h), tentTexelWeight(first + 1.0f, h));
}

// Fetch m (0 .. tentFetchesPerAxis(n) - 1) along one axis for a sample point at `o` from its
// nearest texel corner: x = the fetch's weight (its two texels' weights), y = its position
// relative to the sample point, in texels.
PUNCTUAL_FN vec2 tentAxisFetch(float o, uint n, uint m) {
    vec3 pair = tentAxisTexelPair(o, n, m);
    float weight = pair.y + pair.z;
    return vec2(weight, pair.x + pair.z / weight);
}

// Fetch i (0 .. tentFetchCount(n) - 1, row by row) of the N x N tent around the sample point at
// `texelPosition` (uv x resolution): xy = its offset from the sample point in texels (divide by
// the resolution for UV), z = its weight. The weights of all fetches sum to 1.
PUNCTUAL_FN vec3 tentFetch(vec2 texelPosition, uint n, uint i) {
    vec2 o = tentCornerOffset(texelPosition);
    uint perAxis = tentFetchesPerAxis(n);
    vec2 u = tentAxisFetch(o.x, n, i % perAxis);
    vec2 v = tentAxisFetch(o.y, n, i / perAxis);
    return vec3(u.y, v.y, u.x * v.x);
}

PUNCTUAL_NAMESPACE_END

#endif
