// The shading math, shared by the GPU forward shader and the CPU reference renderer, so the two
// agree by construction. Units: positions in metres, light intensity in candela (spot, point)
// and lux (directional); the result is linear radiance before exposure.
#ifndef PUNCTUAL_SHADING_H
#define PUNCTUAL_SHADING_H

#include "glsl_cpp.h"
#include "gpu_types.h"

PUNCTUAL_NAMESPACE_BEGIN

#define PUNCTUAL_PI 3.14159265358979f

PUNCTUAL_FN float saturate1(float x) { return clamp(x, 0.0f, 1.0f); }

// Distance attenuation (custom SRP "Distance Attenuation"): inverse-square falloff multiplied by
// a smooth window that reaches exactly 0 at the range:
//   s = max(1 - (d^2 / r^2)^2, 0),  att = s^2 / max(d^2, 1e-4).
// We keep the seed's squared window (KHR_lights_punctual suggests the unsquared one) because its
// derivative is also 0 at the range, so the cut-off shows no ring. Beyond the range the result is
// exactly 0.0, which is what lets culled light lists reproduce brute force bit for bit.
PUNCTUAL_FN float distanceAttenuation(float distanceSquared, float invRangeSquared) {
    float ratio = distanceSquared * invRangeSquared;
    float window = max(1.0f - ratio * ratio, 0.0f);
    return window * window / max(distanceSquared, 1e-4f);
}

// Spot angle attenuation: a = saturate(cos(theta) * k - cosOuter * k)^2 with
// k = 1 / max(cosInner - cosOuter, 1e-4): 1 inside the inner cone, 0 outside the outer, a
// smooth square ramp between. theta is measured from the axis (glTF's convention).
// `shineDirection` is the unit direction the light shines, `toLight` the unit vector from the
// surface to the light, so cos(theta) = dot(shineDirection, -toLight). Points pass scale 0,
// offset 1 and get exactly 1.
PUNCTUAL_FN float spotAttenuation(vec3 shineDirection, vec3 toLight, float scale, float offset) {
    float a = saturate1(dot(shineDirection, -toLight) * scale + offset);
    return a * a;
}

PUNCTUAL_FN float spotAngleScale(float cosInner, float cosOuter) {
    return 1.0f / max(cosInner - cosOuter, 1e-4f);
}

// Attenuation (distance x angle) of a packed light at world position `position`.
PUNCTUAL_FN float punctualAttenuation(GpuPunctualLight light, vec3 position) {
    vec3 lightVector = vec3(light.positionInvRangeSq) - position;
    float distanceSquared = dot(lightVector, lightVector);
    float att = distanceAttenuation(distanceSquared, light.positionInvRangeSq.w);
    if (att <= 0.0f) return 0.0f;
    vec3 toLight = lightVector * (1.0f / sqrt(distanceSquared));
    return att * spotAttenuation(vec3(light.directionAngleScale), toLight,
                                 light.directionAngleScale.w, light.angleOffsetShadow.x);
}

// Metallic-roughness surface at one shading point.
struct Surface {
    vec3 position;
    vec3 normal;       // unit, facing the viewer
    vec3 viewDir;      // unit, from the surface to the eye
    vec3 diffuseColor; // (1 - metallic) * baseColor
    vec3 f0;           // specular reflectance at normal incidence
    float alpha;       // GGX alpha = perceptualRoughness^2
};

PUNCTUAL_FN Surface makeSurface(vec3 position, vec3 normal, vec3 viewDir, vec3 baseColor,
                                float metallic, float perceptualRoughness) {
    Surface s;
    s.position = position;
    s.normal = normal;
    s.viewDir = viewDir;
    s.diffuseColor = baseColor * (1.0f - metallic);
    s.f0 = mix(vec3(0.04f), baseColor, metallic);
    // Clamp as Filament does: alpha below ~0.002 makes the GGX peak a spike that neither a
    // rasteriser nor a ray tracer resolves, and it underflows in half precision.
    float r = clamp(perceptualRoughness, 0.045f, 1.0f);
    s.alpha = r * r;
    return s;
}

// GGX (Trowbridge-Reitz) normal distribution.
PUNCTUAL_FN float distributionGgx(float nDotH, float alpha) {
    float a2 = alpha * alpha;
    float f = (nDotH * a2 - nDotH) * nDotH + 1.0f;
    return a2 / (PUNCTUAL_PI * f * f);
}

// Height-correlated Smith visibility term V = G / (4 NoL NoV) (Heitz 2014).
PUNCTUAL_FN float visibilitySmithGgxCorrelated(float nDotV, float nDotL, float alpha) {
    float a2 = alpha * alpha;
    float ggxV = nDotL * sqrt(nDotV * nDotV * (1.0f - a2) + a2);
    float ggxL = nDotV * sqrt(nDotL * nDotL * (1.0f - a2) + a2);
    return 0.5f / max(ggxV + ggxL, 1e-6f);
}

PUNCTUAL_FN vec3 fresnelSchlick(vec3 f0, float vDotH) {
    float f = pow(1.0f - vDotH, 5.0f);
    return f0 + (vec3(1.0f) - f0) * f;
}

// Whether light arriving along `toLight` can reflect at all: N.L > 0. Where it is false (N.L <= 0),
// shadeBrdf returns exactly 0 whatever the light's radiance, so a caller may skip work that only
// scales that radiance (the shadow lookup). (For a NaN N.L it is false too, and shadeBrdf returns
// NaN, again whatever the radiance.)
PUNCTUAL_FN bool facesLight(Surface s, vec3 toLight) { return dot(s.normal, toLight) > 0.0f; }

// Radiance reflected towards the eye from light arriving along `toLight` with irradiance-scale
// `lightRadiance` (colour x intensity x attenuation): (diffuse/pi + D V F) x E x NoL.
PUNCTUAL_FN vec3 shadeBrdf(Surface s, vec3 toLight, vec3 lightRadiance) {
    float nDotL = dot(s.normal, toLight);
    if (nDotL <= 0.0f) return vec3(0.0f);  // !facesLight
    vec3 h = normalize(s.viewDir + toLight);
    float nDotV = max(dot(s.normal, s.viewDir), 1e-4f);
    float nDotH = saturate1(dot(s.normal, h));
    float vDotH = saturate1(dot(s.viewDir, h));
    vec3 specular = distributionGgx(nDotH, s.alpha) * visibilitySmithGgxCorrelated(nDotV, nDotL, s.alpha)
                    * fresnelSchlick(s.f0, vDotH);
    vec3 diffuse = s.diffuseColor * (1.0f / PUNCTUAL_PI);
    return (diffuse + specular) * lightRadiance * nDotL;
}

// Where a spot/point light arrives at a surface point: the unit vector towards it and its
// attenuation (distance x angle; exactly 0 outside its range and cone).
struct LightSample {
    vec3 toLight;
    float attenuation;
};

PUNCTUAL_FN LightSample sampleLight(GpuPunctualLight light, vec3 position) {
    LightSample result;
    vec3 lightVector = vec3(light.positionInvRangeSq) - position;
    float distanceSquared = dot(lightVector, lightVector);
    result.toLight = vec3(0.0f);
    result.attenuation = distanceAttenuation(distanceSquared, light.positionInvRangeSq.w);
    if (result.attenuation <= 0.0f) return result;
    result.toLight = lightVector * (1.0f / sqrt(distanceSquared));
    result.attenuation *= spotAttenuation(vec3(light.directionAngleScale), result.toLight, light.directionAngleScale.w,
                                          light.angleOffsetShadow.x);
    return result;
}

// Contribution of a light at a sample, `shadow` in [0, 1] (1 = fully lit).
PUNCTUAL_FN vec3 shadeLightSample(Surface s, GpuPunctualLight light, LightSample arrival, float shadow) {
    if (arrival.attenuation <= 0.0f) return vec3(0.0f);
    return shadeBrdf(s, arrival.toLight, vec3(light.radiantColor) * (arrival.attenuation * shadow));
}

PUNCTUAL_FN vec3 shadePunctualLight(Surface s, GpuPunctualLight light, float shadow) {
    return shadeLightSample(s, light, sampleLight(light, s.position), shadow);
}

PUNCTUAL_FN vec3 shadeDirectionalLight(Surface s, GpuDirectionalLight sun) {
    if (sun.directionToLight.w <= 0.0f) return vec3(0.0f);
    return shadeBrdf(s, vec3(sun.directionToLight), vec3(sun.illuminance));
}

// Tone mapping: exposure, then the ACES filmic fit of Narkowicz (2015), clamped to [0, 1].
// The exposed value is capped first at PUNCTUAL_ACES_MAX_INPUT: the curve reaches 1 at x = 7.24
// (0.08 x^2 - 0.56 x - 0.14 = 0) and stays above it, so the cap changes no output, but it keeps
// x^2 finite. Without it a huge exposure (x > 1.8e19, or radiance x exposure overflowing to inf)
// gives inf / inf = NaN, which the clamp turns to black where the image should be white.
#define PUNCTUAL_ACES_MAX_INPUT 1e4f
PUNCTUAL_FN vec3 toneMapAces(vec3 radiance, float exposure) {
    vec3 x = min(radiance * exposure, vec3(PUNCTUAL_ACES_MAX_INPUT));
    vec3 mapped = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    return clamp(mapped, vec3(0.0f), vec3(1.0f));
}

// sRGB transfer function (IEC 61966-2-1) for one channel in [0, 1].
PUNCTUAL_FN float linearToSrgb(float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

PUNCTUAL_FN vec3 linearToSrgb3(vec3 c) {
    return vec3(linearToSrgb(c.x), linearToSrgb(c.y), linearToSrgb(c.z));
}

PUNCTUAL_NAMESPACE_END

#endif
