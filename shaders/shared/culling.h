// Light-culling geometry, written once for GLSL and C++ (see glsl_cpp.h): the cluster slices and
// the light grid's layout (depth_range.comp, light_culling.comp, forward.frag), the lights'
// culling shapes (made on the CPU each frame, tested by light_culling.comp), the spot light's
// bounding sphere (also the CPU's frustum culling and per-object lists), and the CPU reference of
// the culling tests.
//
// Everything here is in view space: the camera at the origin looking down -Z, distances along the
// view axis positive ("view distance" D = -z).
#ifndef PUNCTUAL_CULLING_H
#define PUNCTUAL_CULLING_H

#include "glsl_cpp.h"
#include "gpu_types.h"

PUNCTUAL_NAMESPACE_BEGIN

// Culling is conservative by a small margin, because the forward pass shades interpolated world
// positions while culling sees positions rebuilt from the depth buffer. The camera's depth is
// reversed (1 at the near plane n, 0 at the far plane, about n / D at view distance D: see
// Camera::projection), so a 32-bit float depth holds n / D to 2^-24 relative and rebuilds D to
// about 1e-7 relative at any distance and any near plane; we widen depth ranges and light radii
// by 1e-3 relative, which costs no measurable efficiency.
#define PUNCTUAL_CULL_RELATIVE_MARGIN 1e-3f

// The depth buffer is cleared to 0 (the far plane; the depth prepass keeps GREATER depths), so a
// pixel that kept 0 shows no geometry. Geometry exactly at the far plane is clipped anyway.
#define PUNCTUAL_DEPTH_CLEAR 0.0f

PUNCTUAL_FN bool isBackgroundDepth(float depth) {
    return depth <= PUNCTUAL_DEPTH_CLEAR;
}

// Perspective depth (Vulkan) to view distance. For a projection with P[2][2] = b and
// P[3][2] = a (GLM's column-major layout): clip.z = b z + a and clip.w = -z at view-space z, so
// depth = (b z + a) / (-z) and at z = -D, depth = a / D - b, i.e. D = a / (depth + b).
// `depthToView` = (a, b). This holds for any such matrix; the camera's reversed one
// (near n, far f) has a = f n / (f - n) and b = n / (f - n): depth 1 at D = n, 0 at D = f.
PUNCTUAL_FN float viewDistanceFromDepth(float depth, vec2 depthToView) {
    return depthToView.x / (depth + depthToView.y);
}

// Cluster slices are logarithmic between the nearest and farthest geometry of the frame
// (Dnear, Dfar from the depth-range pass), so every slice is used and each spans the same ratio
// of distances, which matches how perspective spreads pixels: slice s starts at
// D_s = Dnear (Dfar / Dnear)^(s / S). The slice-boundaries pass turns each D_s into the depth
// value where it starts, once per frame; the culling kernel and the forward pass then find a
// pixel's slice by comparing its depth with those stored values. Comparisons are exact, so both
// pipelines agree bit for bit (recomputing a logarithm in each would not: drivers compile each
// pipeline on its own and may round a transcendental differently).
PUNCTUAL_FN float sliceStartDistance(uint slice, float nearDistance, float farDistance, uint sliceCount) {
    return nearDistance * pow(farDistance / nearDistance, float(slice) / float(sliceCount));
}

// Perspective depth of a view distance: the inverse of viewDistanceFromDepth.
PUNCTUAL_FN float depthFromViewDistance(float distance, vec2 depthToView) {
    return depthToView.x / distance - depthToView.y;
}

// The cluster slice of a perspective depth: the last slice whose start is at or nearer than it.
// Depth is reversed, so slices run near to far with falling start depths (slice 0 starts at depth
// 1, the near plane, so every depth has one; slices at or past sliceCount start at -1 and are
// never returned), and "at or nearer" is start >= depth. A lower-bound binary search over the
// starts of slices 1 .. sliceCount - 1: `first` is one past the last start known to be >= depth,
// `count` how many starts from `first` on are still unknown; each step halves `count`, so
// ceil(log2(sliceCount)) comparisons. Pure comparisons of stored values: the culling kernel, the
// forward shader and the tests pick the same slice bit for bit.
//
// A macro, not a function taking the array: GLSL passes arrays by value, and lavapipe copies the
// whole array at every call (measured at 640x360 with 96 lights: the culling pass 2.4x slower,
// the forward pass 15-30%), even where the search reads nothing. The macro indexes the caller's
// array where it is (a storage buffer, a shared array, a C++ pointer). It assigns `result`; pass
// plain names, as the other arguments are evaluated at every step.
#define PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(result, depth, sliceStart, sliceCount) \
    {                                                                            \
        uint sliceFirst_ = 1u;                                                   \
        for (uint sliceCount_ = (sliceCount) - 1u; sliceCount_ > 0u;) {          \
            uint sliceStep_ = sliceCount_ / 2u;                                  \
            if ((sliceStart)[sliceFirst_ + sliceStep_] >= (depth)) {             \
                sliceFirst_ += sliceStep_ + 1u;                                  \
                sliceCount_ -= sliceStep_ + 1u;                                  \
            } else {                                                             \
                sliceCount_ = sliceStep_;                                        \
            }                                                                    \
        }                                                                        \
        result = sliceFirst_ - 1u;                                               \
    }

#ifdef __cplusplus
// The search as a C++ function (the tests' CPU reference).
PUNCTUAL_FN uint clusterSliceOfDepth(float depth, const float* sliceStart, uint sliceCount) {
    uint slice = 0u;
    PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(slice, depth, sliceStart, sliceCount);
    return slice;
}
#endif

// A light-grid cell is gridWordsOf(lights) words (gpu_types.h), one bit per packed light (spots
// first, 0 .. spotCount - 1, then points): light L is bit L % 32 of word L / 32, and bit b of word
// w is light 32 w + b. Walking the words in order and each word's set bits upwards visits lights
// in ascending packed order, the order of the brute-force loop, whatever the capacity.
// (Contiguous, not a word range per kind: 64 + 32 lights are the same three words either way, and
// a frame with fewer spots needs no padding between them and its points.)
PUNCTUAL_FN uint lightGridWord(uint light) { return light >> 5u; }

PUNCTUAL_FN uint lightGridBit(uint light) { return light & 31u; }

PUNCTUAL_FN uint lightGridFirstLight(uint word) { return word * 32u; }

// The mask of word `word` holding every light of a frame of `lightCount` lights: the bits of the
// lights 32 word .. min(32 word + 32, lightCount) - 1.
PUNCTUAL_FN uint allLightsWord(uint word, uint lightCount) {
    uint first = word * 32u;
    return lightCount >= first + 32u ? 0xFFFFFFFFu : (lightCount > first ? (1u << (lightCount - first)) - 1u : 0u);
}

// Index lists (--light-lists indices; Olsson et al. 2012 and Harada et al. 2012 keep per cell an
// offset and a count into one compacted array of light indices). A cell's grid entry is then one
// header word, the start of its list in the index words (PUNCTUAL_BINDING_LIGHT_INDICES, after the
// words-used counter): entry 0 is the list's count n, entries 1 .. n its lights in ascending
// packed order (the masks' walk order), 16 bits each, two a word, entry e in the low half of word
// e / 2 when e is even and the high half when odd. A list takes lightListWords(n) words, so its
// memory is its entries, 2 bytes each, plus the header and the count: at the 80 lights a cell of
// 8,192 holds, 4% over the 16-bit floor, where a mask is 1 KiB. The culling kernels take each list's
// words with one atomic add on the counter; a list that would pass the end of the array is not
// written and its header says so (the renderer sizes the array from a counting frame, so this only
// guards against a bug, and the forward pass shades such a cell magenta).
#define PUNCTUAL_LIGHT_LIST_NONE 0xFFFFFFFFu      // header: no lights (an empty or never-written cell)
#define PUNCTUAL_LIGHT_LIST_OVERFLOW 0xFFFFFFFEu  // header: the list did not fit the index array

PUNCTUAL_FN uint lightListWords(uint count) { return (count + 2u) / 2u; }

// Entry `entry` of a list, from its word (word entry / 2 of the list).
PUNCTUAL_FN uint lightListEntry(uint word, uint entry) { return (entry & 1u) != 0u ? word >> 16u : word & 0xFFFFu; }

// The word holding entries `low` (even) and `high`.
PUNCTUAL_FN uint lightListPair(uint low, uint high) { return low | (high << 16u); }

// The part of a screen tile between two view distances: a frustum segment. Culling tests a light
// against three bounding shapes of it and culls when any test says the light misses:
//   the four side planes through the eye (tight sideways),
//   the depth interval [nearDistance, farDistance],
//   its view-space AABB (tight for thin segments, where plane tests alone leave the well-known
//   false positives near frustum corners).
// The sphere around the AABB is what the spot-cone test uses.
struct TileVolume {
    vec4 sidePlanes[4];  // xyz: unit normal pointing into the tile; planes pass through the eye
    vec3 aabbMin;
    vec3 aabbMax;
    float nearDistance;
    float farDistance;
    vec3 sphereCenter;
    float sphereRadius;
    vec2 rayMin;  // the xy bounds of the four corner rays at distance 1 (their z is -1): the
    vec2 rayMax;  // cross-section at distance D spans rayMin D .. rayMax D
};

// View-space direction (at distance 1) through an NDC point. `ndcToView` = (1/P00, 1/P11, P20, P21):
// x_ndc = (P00 x + P20 z) / (-z) gives x = D (x_ndc + P20) / P00 at z = -D, and the same for y.
PUNCTUAL_FN vec3 viewRayThroughNdc(vec2 ndc, vec4 ndcToView) {
    return vec3((ndc.x + ndcToView.z) * ndcToView.x, (ndc.y + ndcToView.w) * ndcToView.y, -1.0f);
}

PUNCTUAL_FN vec4 planeThroughEye(vec3 a, vec3 b, vec3 inside) {
    vec3 n = normalize(cross(a, b));
    if (dot(n, inside) < 0.0f) n = -n;
    return vec4(n, 0.0f);
}

PUNCTUAL_FN TileVolume makeTileVolume(vec2 ndcMin, vec2 ndcMax, float nearDistance, float farDistance,
                                      vec4 ndcToView) {
    TileVolume v;
    vec3 c00 = viewRayThroughNdc(vec2(ndcMin.x, ndcMin.y), ndcToView);
    vec3 c10 = viewRayThroughNdc(vec2(ndcMax.x, ndcMin.y), ndcToView);
    vec3 c01 = viewRayThroughNdc(vec2(ndcMin.x, ndcMax.y), ndcToView);
    vec3 c11 = viewRayThroughNdc(vec2(ndcMax.x, ndcMax.y), ndcToView);
    vec3 centre = (c00 + c10 + c01 + c11) * 0.25f;
    v.sidePlanes[0] = planeThroughEye(c00, c01, centre);  // x = min edge
    v.sidePlanes[1] = planeThroughEye(c10, c11, centre);  // x = max edge
    v.sidePlanes[2] = planeThroughEye(c00, c10, centre);  // y = min edge
    v.sidePlanes[3] = planeThroughEye(c01, c11, centre);  // y = max edge
    float nearD = nearDistance * (1.0f - PUNCTUAL_CULL_RELATIVE_MARGIN);
    float farD = farDistance * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN);
    v.nearDistance = nearD;
    v.farDistance = farD;
    // The segment's eight corners are the four rays scaled to the two distances (rays have z = -1).
    vec3 lo = min(min(c00, c10), min(c01, c11));
    vec3 hi = max(max(c00, c10), max(c01, c11));
    v.aabbMin = min(lo * nearD, lo * farD);
    v.aabbMax = max(hi * nearD, hi * farD);
    v.aabbMin.z = -farD;
    v.aabbMax.z = -nearD;
    v.sphereCenter = (v.aabbMin + v.aabbMax) * 0.5f;
    v.sphereRadius = length(v.aabbMax - v.aabbMin) * 0.5f;
    v.rayMin = vec2(lo);
    v.rayMax = vec2(hi);
    return v;
}

// The tile's whole frustum column, from the near plane to the far plane (depths 1 and 0:
// D = a / (1 + b) and a / b, viewDistanceFromDepth), for the tests that read no depth: the z-bin
// method's tiles (the bins hold depth) and the coarse pass's big tiles. b is 0 for an infinite far
// plane, hence the guard.
PUNCTUAL_FN TileVolume makeTileColumn(vec2 ndcMin, vec2 ndcMax, vec2 depthToView, vec4 ndcToView) {
    return makeTileVolume(ndcMin, ndcMax, viewDistanceFromDepth(1.0f, depthToView),
                          depthToView.x / max(depthToView.y, 1e-30f), ndcToView);
}

// True when the sphere (view space) may overlap the tile segment.
PUNCTUAL_FN bool sphereMayTouchTile(vec3 center, float radius, TileVolume v) {
    float distance = -center.z;
    if (distance + radius < v.nearDistance || distance - radius > v.farDistance) return false;
    for (int i = 0; i < 4; ++i) {
        if (dot(vec3(v.sidePlanes[i]), center) < -radius) return false;
    }
    vec3 closest = clamp(center, v.aabbMin, v.aabbMax);
    vec3 offset = center - closest;
    return dot(offset, offset) <= radius * radius;
}

// True when a cone (apex, unit axis, slant length `range`, half-angle with cos/sin) may overlap
// a sphere. Wronski, "Cull that cone!" (2017): the distance from the sphere centre to the cone's
// surface is cos(a) |v x axis| - sin(a) (v . axis) for v = centre - apex; the cone misses when
// that exceeds the radius, or the sphere lies beyond the range or behind the apex.
PUNCTUAL_FN bool coneMayTouchSphere(vec3 apex, vec3 axis, float range, float cosAngle, vec3 center,
                                    float radius) {
    vec3 v = center - apex;
    float lengthSquared = dot(v, v);
    float alongAxis = dot(v, axis);
    float sinAngle = sqrt(max(1.0f - cosAngle * cosAngle, 0.0f));
    float distanceToSurface = cosAngle * sqrt(max(lengthSquared - alongAxis * alongAxis, 0.0f)) - alongAxis * sinAngle;
    if (distanceToSurface > radius) return false;
    if (alongAxis > radius + range) return false;
    if (alongAxis < -radius) return false;
    return true;
}

// A packed light moved to view space, with its conservative culling shapes.
struct CullLight {
    vec3 position;     // view space
    float range;       // widened by the margin
    vec3 axis;         // view space, unit (spots)
    float cosOuter;    // -1 for points
    vec3 sphereCenter; // bounding sphere of everything the light can reach
    float sphereRadius;
};

// Bounding sphere of a spot light, as vec4(centre, radius): the smallest sphere around its cone.
//
// The lit region is the spherical sector {p : |p - P| <= r, angle(p - P, D) <= theta}: the cone of
// apex P, unit axis D, half-angle theta <= 90 deg (given by its cosine) and slant length r, plus
// the spherical cap that closes it. The cone's rim is the circle of radius r sin(theta) centred at
// P + D r cos(theta).
//
// theta > 45 deg (cos theta < sqrt(2)/2): the sphere on the rim circle, centre P + D r cos(theta),
//   radius r sin(theta), is the smallest sphere holding the rim, and it holds the apex too since
//   the apex is r cos(theta) < r sin(theta) from its centre.
// theta <= 45 deg: the apex would stick out of that sphere, so the smallest sphere passes through
//   the apex and the rim. With its centre at P + D t: apex distance t; rim distance
//   sqrt((r cos(theta) - t)^2 + r^2 sin^2(theta)). Equal when r^2 - 2 t r cos(theta) = 0, i.e.
//   t = r / (2 cos(theta)), which is also the radius.
// Both spheres hold the cap as well: a cap point at angle phi <= theta from the axis is at
// distance^2 = r^2 + c^2 - 2 r c cos(phi) from a centre at distance c along the axis, which is
//   <= t^2 (c = t) iff r <= 2 t cos(phi) = r cos(phi)/cos(theta), and
//   <= r^2 sin^2(theta) (c = r cos(theta)) iff cos(theta) <= cos(phi),
// both true for phi <= theta. At theta = 45 deg the two cases give the same sphere.
// sin(theta) = sqrt(1 - cos^2(theta)), clamped at 0 against rounding: every caller knows theta
// by its cosine, and one formula keeps the CPU's frustum culling, the per-object lists and the
// tile culling on the same sphere.
PUNCTUAL_FN vec4 spotBoundingSphere(vec3 apex, vec3 axis, float range, float cosOuter) {
    if (cosOuter < 0.70710678f) {
        float sinOuter = sqrt(max(1.0f - cosOuter * cosOuter, 0.0f));
        return vec4(apex + axis * (range * cosOuter), range * sinOuter);
    }
    float t = range / (2.0f * cosOuter);
    return vec4(apex + axis * t, t);
}

// The light in view space, with its bounding sphere (points: the range sphere; spots:
// spotBoundingSphere), range and sphere widened by the margin.
PUNCTUAL_FN CullLight makeCullLight(GpuPunctualLight light, mat4 view) {
    CullLight c;
    c.position = vec3(view * vec4(vec3(light.positionInvRangeSq), 1.0f));
    c.axis = normalize(mat3(view) * vec3(light.directionAngleScale));
    c.range = light.radiantColor.w * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN);
    c.cosOuter = light.angleOffsetShadow.z;
    if (c.cosOuter <= -1.0f) {
        c.sphereCenter = c.position;
        c.sphereRadius = c.range;
    } else {
        vec4 sphere = spotBoundingSphere(c.position, c.axis, c.range, c.cosOuter);
        c.sphereCenter = vec3(sphere);
        c.sphereRadius = sphere.w;
    }
    c.sphereRadius *= 1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN;
    return c;
}

// How far a spot light reaches along unit direction u: the largest u . x over the points x it
// lights, padded. The lit region is the spherical sector (apex P, unit axis D, half-angle theta,
// slant r; see spotBoundingSphere): its points are P + t w with 0 <= t <= r and angle(w, D) <=
// theta. The w nearest to u turns from D towards u by theta (or reaches u itself), so the largest
// u . w is cos(max(0, angle(u, D) - theta)) = cos(alpha) cos(theta) + sin(alpha) sin(theta) once
// alpha = angle(u, D) > theta, and 1 before; t = r when that is positive, else t = 0 (the apex).
// Padded by the margin of r: its few roundings are ~1e-7 r. A spot seen side-on (alpha = 90 deg,
// theta = 30 deg) reaches r/2 along the view axis, where its bounding sphere reaches about 0.58 r
// past the apex; one pointing away reaches r one way and 0 the other.
PUNCTUAL_FN float spotReachAlong(CullLight light, vec3 u) {
    float cosTheta = light.cosOuter;
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    float cosAlpha = dot(u, light.axis);
    float sinAlpha = sqrt(max(1.0f - cosAlpha * cosAlpha, 0.0f));
    float reach = cosAlpha >= cosTheta ? 1.0f : max(cosAlpha * cosTheta + sinAlpha * sinTheta, 0.0f);
    return dot(u, light.position) + light.range * (reach + PUNCTUAL_CULL_RELATIVE_MARGIN);
}

// A light's view-distance extent, vec2(nearest, farthest): the range of -z over all it can reach.
// Points: the range sphere's, centre -/+ radius. Spots: the sector's reach along -z and +z, cut by
// the bounding sphere's extent (both are conservative).
PUNCTUAL_FN vec2 lightDistanceExtent(CullLight light) {
    float centre = -light.sphereCenter.z;
    vec2 sphere = vec2(centre - light.sphereRadius, centre + light.sphereRadius);
    if (light.cosOuter <= -1.0f) return sphere;
    return vec2(max(sphere.x, -spotReachAlong(light, vec3(0.0f, 0.0f, 1.0f))),
                min(sphere.y, spotReachAlong(light, vec3(0.0f, 0.0f, -1.0f))));
}

// True when a spot's sector may overlap the segment: it reaches inside each side plane (planes
// through the eye, unit normals pointing in: a sector whose largest n . x is negative lies wholly
// outside) and its reach along +-x and +-y overlaps the AABB's sides (its depth extent is tested
// by the caller). These are the exact separating planes the bounding sphere only approximates.
PUNCTUAL_FN bool spotMayTouchTile(CullLight light, TileVolume v) {
    for (int i = 0; i < 4; ++i) {
        if (spotReachAlong(light, vec3(v.sidePlanes[i])) < 0.0f) return false;
    }
    if (spotReachAlong(light, vec3(1.0f, 0.0f, 0.0f)) < v.aabbMin.x) return false;
    if (-spotReachAlong(light, vec3(-1.0f, 0.0f, 0.0f)) > v.aabbMax.x) return false;
    if (spotReachAlong(light, vec3(0.0f, 1.0f, 0.0f)) < v.aabbMin.y) return false;
    if (-spotReachAlong(light, vec3(0.0f, -1.0f, 0.0f)) > v.aabbMax.y) return false;
    return true;
}

// The part of segment `v` between distances nearD <= farD (within its own, widened ones): the
// same side planes, its AABB the cross-sections' bounds scaled to both ends (as makeTileVolume)
// and the sphere around that. A light meets the segment only within its own depth extent, so it
// is tested against that part, whose box and sphere are smaller where the segment is long.
PUNCTUAL_FN TileVolume clipSegment(TileVolume v, float nearD, float farD) {
    TileVolume part = v;
    part.nearDistance = nearD;
    part.farDistance = farD;
    part.aabbMin = vec3(min(v.rayMin * nearD, v.rayMin * farD), -farD);
    part.aabbMax = vec3(max(v.rayMax * nearD, v.rayMax * farD), -nearD);
    part.sphereCenter = (part.aabbMin + part.aabbMax) * 0.5f;
    part.sphereRadius = length(part.aabbMax - part.aabbMin) * 0.5f * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN);
    return part;
}

// The smallest n . x over segment `v`: over its eight corners, since the segment is their convex
// hull. A tile's screen rectangle is axis-aligned, so its corner rays are (x, y, -1) with x in
// {rayMin.x, rayMax.x} and y in {rayMin.y, rayMax.y} independently, and a corner at distance D is
// D times its ray: per distance the smallest is D (min over x of n.x x + min over y of n.y y - n.z),
// linear in D, so at one of the two ends.
PUNCTUAL_FN float segmentMinAlong(TileVolume v, vec3 n) {
    float perDistance = min(n.x * v.rayMin.x, n.x * v.rayMax.x) + min(n.y * v.rayMin.y, n.y * v.rayMax.y) - n.z;
    return min(perDistance * v.nearDistance, perDistance * v.farDistance);
}

// Separating planes between a spot's sector and segment `v`, tested against the segment's corners
// (segmentMinAlong):
//   the cone's tangent plane facing the segment's centre c: with c - P split into a part along the
//     axis D and the unit u across it, the cone's generator nearest to c is cos(theta) D +
//     sin(theta) u, and the plane through the apex holding it and the normal of the (D, u) plane
//     has the outward normal n = cos(theta) u - sin(theta) D; the cone (theta <= 90 deg) lies where
//     n . (x - P) <= 0;
//   the plane through the apex across the axis: the sector lies where D . (x - P) >= 0;
//   the plane across the axis at the range: the sector lies where D . (x - P) <= r.
// Each keeps the light unless the whole segment lies beyond the plane by the margin of r. These are
// the sector's own planes, where coneMayTouchSphere bounds the segment by a sphere. (Planes facing
// the segment's two ends as well were measured: 0.2% fewer lights tested, the culling pass about
// 1.5x slower on lavapipe.)
PUNCTUAL_FN bool coneMayTouchSegment(CullLight light, TileVolume v) {
    float pad = light.range * PUNCTUAL_CULL_RELATIVE_MARGIN;
    float apexAlongAxis = dot(light.axis, light.position);
    if (segmentMinAlong(v, light.axis) - apexAlongAxis > light.range + pad) return false;
    if (-segmentMinAlong(v, -light.axis) - apexAlongAxis < -pad) return false;
    vec3 offset = v.sphereCenter - light.position;
    vec3 across = offset - light.axis * dot(offset, light.axis);
    float acrossLength = length(across);
    if (acrossLength <= 1e-6f * light.range) return true;  // the centre on the axis: no plane faces it
    float sinTheta = sqrt(max(1.0f - light.cosOuter * light.cosOuter, 0.0f));
    vec3 n = light.cosOuter * (across / acrossLength) - sinTheta * light.axis;
    return segmentMinAlong(v, n) - dot(n, light.position) <= pad;
}

// Whether a light's view-distance extent (lightDistanceExtent) overlaps the segment's distances:
// the tile test's first step, and all of it that depends on depth alone (a light failing it fails
// the tile test of every segment within these distances).
PUNCTUAL_FN bool lightDepthMeetsSegment(vec2 lightExtent, TileVolume segment) {
    return !(lightExtent.y < segment.nearDistance || lightExtent.x > segment.farDistance);
}

// The tile test. A light meets the segment only within its own depth extent
// (lightDistanceExtent), so the tests run on that part of the segment (clipSegment): the light's
// bounding sphere against its planes and box; for spots also the sector's range sphere (around
// the apex), the sector's reach against the planes and box (spotMayTouchTile), the cone against
// the part's bounding sphere (coneMayTouchSphere) and the sector's own planes against the part's
// corners (coneMayTouchSegment). Each is conservative; the light is culled when any says it misses.
PUNCTUAL_FN bool lightMayTouchTile(CullLight light, TileVolume segment) {
    vec2 extent = lightDistanceExtent(light);
    if (!lightDepthMeetsSegment(extent, segment)) return false;
    TileVolume v = clipSegment(segment, max(segment.nearDistance, extent.x), min(segment.farDistance, extent.y));
    if (!sphereMayTouchTile(light.sphereCenter, light.sphereRadius, v)) return false;
    if (light.cosOuter <= -1.0f) return true;
    if (!sphereMayTouchTile(light.position, light.range, v)) return false;
    if (!spotMayTouchTile(light, v)) return false;
    if (!coneMayTouchSphere(light.position, light.axis, light.range, light.cosOuter, v.sphereCenter, v.sphereRadius)) return false;
    return coneMayTouchSegment(light, v);
}

// ---- the culling kernels' flags -----------------------------------------------------------------
// A light-list method that changes only how the culling kernels fill its grid is a flag here, in
// its table row's `cullFlags` (src/render/light_list_method.h), which reaches the kernels as the
// specialization constant CULL_FLAGS: each kernel turns its flags into constant bools. The general
// kernel (light_culling.comp) implements every flag; the one-subgroup kernels implement those in
// their masks below, and LightGridLayout::forMethod keeps a method with any other flag on the
// general kernel, so a new flag needs its case in light_culling.comp alone.
#define PUNCTUAL_CULL_DEPTH_MASK 1u        // tiled-2.5d: also against the tile's 2.5D depth mask (below)
#define PUNCTUAL_CULL_DEPTHLESS_TILES 2u   // zbin-2d: tile masks over the whole column, no depth read (makeTileColumn)
#define PUNCTUAL_TILE_KERNEL_CULL_FLAGS (PUNCTUAL_CULL_DEPTH_MASK | PUNCTUAL_CULL_DEPTHLESS_TILES)  // tile_culling.comp
#define PUNCTUAL_CLUSTER_KERNEL_CULL_FLAGS 0u  // cluster_culling.comp

// Whether a method with these flags culls against the depths its pixels have (tiles' depth
// extents, slices, depth cells): every method but those whose tiles span the whole column.
PUNCTUAL_FN bool cullFlagsReadDepth(uint flags) { return (flags & PUNCTUAL_CULL_DEPTHLESS_TILES) == 0u; }

// Harada's 2.5D culling (Harada, McKee and Yang, "Forward+: A step toward film-style shading in
// real time", GPU Pro 4, 2013; "2.5D culling for Forward+", SIGGRAPH Asia 2012): a tile's depth
// extent [nearDistance, farDistance] is cut into 32 equal cells, one bit each; the tile's mask has
// the bit of every cell a pixel of the tile lies in, a light's mask the bits of the cells its depth
// extent spans. The light is kept when the two masks share a bit: a light that only reaches the
// empty gap between a foreground and a background surface is dropped, which a min/max depth test
// cannot do.
//
// The cell of a view distance D: floor(32 (D - near) / (far - near)), clamped to 0..31. Lossless by
// monotony: the subtraction, the product with the positive scale and the clamp never decrease as
// D grows (IEEE round-to-nearest is monotone), so a light whose extent [lo, hi] contains a pixel's
// distance D gets cells cell(lo) <= cell(D) <= cell(hi), and its mask holds the pixel's bit. The
// kernel and the CPU reference compute cells with this one function on the same stored distances.
// A tile whose pixels all lie at one distance (far = near) has the scale 0: every pixel and every
// light overlapping it is in cell 0.
#define PUNCTUAL_DEPTH_MASK_CELLS 32u

PUNCTUAL_FN float depthMaskScale(float nearDistance, float farDistance) {
    return farDistance > nearDistance ? float(PUNCTUAL_DEPTH_MASK_CELLS) / (farDistance - nearDistance) : 0.0f;
}

PUNCTUAL_FN uint depthMaskCell(float distance, float nearDistance, float scale) {
    return uint(clamp((distance - nearDistance) * scale, 0.0f, float(PUNCTUAL_DEPTH_MASK_CELLS - 1u)));
}

// The bits of cells first .. last (first <= last <= 31): ones shifted up to `first`, cut above
// `last`. (A shift by 32 is undefined in both languages, hence the two-step form.)
PUNCTUAL_FN uint depthMaskBits(uint first, uint last) {
    uint upToLast = last >= 31u ? 0xFFFFFFFFu : (1u << (last + 1u)) - 1u;
    return upToLast & ~((1u << first) - 1u);
}

// A light's mask in a tile: the cells of its view-distance extent (lightDistanceExtent).
PUNCTUAL_FN uint lightDepthMask(CullLight light, float nearDistance, float scale) {
    vec2 extent = lightDistanceExtent(light);
    return depthMaskBits(depthMaskCell(extent.x, nearDistance, scale), depthMaskCell(extent.y, nearDistance, scale));
}

// The tile's frustum segment of depth cell `cell` of the extent [nearDistance, farDistance]: from
// the cell's start to the next cell's, the last cell ending at farDistance. A distance D lands in
// cell floor(32 (D - near) / (far - near)) (depthMaskCell), so it lies within the cell's bounds up
// to a few float roundings of D, which makeTileVolume's relative margin (1e-3 of the distance)
// covers. A light whose shapes miss every occupied cell's segment reaches no pixel of the tile:
// tighter than the depth-extent test alone, which keeps a light whose sphere spans an occupied
// cell's depths anywhere in the tile's column, not only inside the tile.
PUNCTUAL_FN TileVolume makeDepthCellVolume(vec2 ndcMin, vec2 ndcMax, uint cell, float nearDistance, float farDistance,
                                           vec4 ndcToView) {
    float cells = float(PUNCTUAL_DEPTH_MASK_CELLS);
    float start = nearDistance + (farDistance - nearDistance) * (float(cell) / cells);
    float end = cell + 1u >= PUNCTUAL_DEPTH_MASK_CELLS ? farDistance
                                                       : nearDistance + (farDistance - nearDistance) * (float(cell + 1u) / cells);
    return makeTileVolume(ndcMin, ndcMax, start, end, ndcToView);
}

PUNCTUAL_NAMESPACE_END

#endif
