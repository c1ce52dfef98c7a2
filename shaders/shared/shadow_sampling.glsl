// Shadow lookups of the forward shader (GLSL only; included by forward.frag after its bindings,
// specialization constants, unknownVariant flag and countShadowLookup, which the statistics
// variant counts each filtered read with). The geometry (faces, depth mapping, bias) is
// in shadows.h, shared with the C++ shadow setup.

// A per-pixel random angle for the disk filter: a hash of the position's bits (PCG), so the
// pattern is fixed in the world and identical run to run.
float hashToUnit(vec3 p) {
    uvec3 v = floatBitsToUint(p);
    uint h = v.x * 747796405u + v.y * 2891336453u + v.z * 277803737u + 2246822519u;
    h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
    h = (h >> 22u) ^ h;
    return float(h >> 8u) * (1.0 / 16777216.0);
}

// The filter is a kernel and a size (SHADOW_KERNEL, SHADOW_FILTER_SIZE: the C++ table's row,
// lights/shadow_filters.h); each kernel's samples, taps and reach are in shadow_kernels.h, where
// an unknown kernel sets unknownVariant (forward.frag), which shades magenta: it never passes for
// another filter. The samples come one at a time (`count` samples with offsets and weights), so
// 2D layers and cube faces share one loop. The tents are Unity's (shadow_tent.h): ((N + 1) / 2)^2
// bilinear compare fetches placed and weighted from where the sample point falls inside its
// texel, which weigh every texel of the footprint by the continuous N x N tent's integral over it.

// The footprint filters' size N (1: the hardware's 2 x 2, else the N x N tent), 0 for the disk.
uint filterFootprint() { return shadowKernelFootprint(SHADOW_KERNEL, SHADOW_FILTER_SIZE); }

// Receiver-plane compares apply to the footprint filters on the atlas; the disk's rotated samples
// and the cube array's hardware lookups keep the notes' per-tap compares. The C++ side makes the
// same choice for the bias (ShadowSettings::biasPenumbraTexels).
bool receiverPlaneCompares() { return SHADOW_RECEIVER_PLANE && filterFootprint() > 0u; }

uint filterSampleCount() {
    uint count = shadowKernelTaps(SHADOW_KERNEL, SHADOW_FILTER_SIZE, SHADOW_SAMPLES);
    if (count == 0u) unknownVariant = true;  // a kernel shadow_kernels.h does not know
    return count;
}

// Offset (xy, UV units) and weight (z) of sample i around the position uv (in [0, 1] over the view
// or cube face, `resolution` texels a side). `angle` rotates the disk per pixel.
vec3 filterSample(uint i, float angle, vec2 uv, float resolution) {
    return shadowKernelSample(SHADOW_KERNEL, SHADOW_FILTER_SIZE, i, angle, uv, resolution, SHADOW_SAMPLES,
                              frame.diskRadius);
}

// The per-pixel angle of the kernels that rotate (the disk), 0 for the others.
float filterAngle(vec3 position) {
    return shadowKernelRotates(SHADOW_KERNEL) ? hashToUnit(position) * 6.28318531 : 0.0;
}

// [[dont_unroll]] on the two filter loops below is a lavapipe tuning, measured (bench/RESULTS.md,
// "Tent filters as the seed computes them"): llvmpipe fully unrolls loops of up to 32 iterations
// (its NIR max_unroll_iterations), and the unrolled sample loops ran up to 2x slower than rolled
// ones with twice the samples (the old 16-tap tent5: 440 ms forward against 260 ms for the 36-tap
// tent7; the 32-sample disk 540-610 ms against 283 ms for 33 samples). Kept rolled, the cost grows
// with the taps. A GPU driver may unroll anyway; the attribute is only a hint to the compiler.

// Where a receiver reads a shadowed light's map: the view (a spot's, or the point face its biased
// position falls on), its resolution there and, with virtual pages, the level, and the receiver
// moved by the bias (applyShadowBias, at the texel size it reads).
struct ShadowRead {
    uint view;         // index into shadowViews (and virtualViews)
    uint level;        // virtual pages: the level it reads; 0 otherwise
    float resolution;  // texels a side of what it reads: the view's square, or the level
    vec3 biased;
    bool hasMap;       // false: the view has no map (no caster, or no storage): lit
    bool paged;        // read through the page table (virtual pages; never a cascade), else the view's square
};

// A bilinear compare at `position` (texels of the view's square, `resolution` a side), from one
// gather of the four raw depths around it (bilinearCompare, shadows.h): in the view's own texels,
// so that where its square lies cannot round it (the gather's corner is half a texel from any
// change of texels).
float atlasBilinearCompare(GpuShadowView view, vec2 position, float resolution, float reference) {
    vec2 corner = bilinearCorner(position, resolution);
    vec4 casters = textureGather(shadowAtlasDepth, view.atlasRect.xy + corner / resolution * view.atlasRect.zw, 0);
    return bilinearCompare(casters, reference, bilinearFraction(position, corner));
}

// Filters the view's square of the atlas around `uv` (the view's own UV, 0..1 across its square),
// or with virtual pages its level, each tap a bilinear compare through the page table.
// Samples are clamped half a texel inside the square, so a bilinear tap never reads a neighbour's
// texels: near its edge a view filters as if its edge texels went on (clamp to edge). A receiver
// outside the view is lit, as the spot's white border made it before the atlas.
float filterAtlas(ShadowRead read, GpuShadowView view, vec2 uv, float reference, float angle) {
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    float texelSize = 1.0 / read.resolution;
    vec2 lowest = vec2(0.5 * texelSize);
    vec2 highest = vec2(1.0 - 0.5 * texelSize);
    countShadowLookup(filterSampleCount());
    // Virtual pages: the pages the taps reach (a bilinear tap reads a texel beyond its reach).
    // (Tested through the specialization constant first: the other modes' pipelines then drop this
    // code before the compiler inlines it, which measured 0.1 s of lavapipe's build per pipeline.)
    bool paged = SHADOW_PAGES != PUNCTUAL_SHADOW_PAGES_OFF && read.paged;
    PageBlock block;
    if (paged) {
        float reach = shadowKernelReachTexels(SHADOW_KERNEL, SHADOW_FILTER_SIZE, frame.diskRadius * read.resolution) + 1.0;
        block = virtualPageBlock(read.view, read.level, uv * read.resolution, reach);
    }
    float sum = 0.0;
    float weights = 0.0;
    [[dont_unroll]] for (uint i = 0u; i < filterSampleCount(); ++i) {
        vec3 s = filterSample(i, angle, uv, read.resolution);
        vec2 tap = clamp(uv + s.xy, lowest, highest);
        if (paged) {
            sum += s.z * virtualBilinearCompare(block, tap * read.resolution, reference);
        } else {
            sum += s.z * atlasBilinearCompare(view, tap * read.resolution, read.resolution, reference);
        }
        weights += s.z;
    }
    return sum / weights;
}

// The receiver's depth to compare, at most 1: the far plane is fitted to the deepest object in the
// view (shadow_setup.cpp), and a receiver the bias pushes beyond it lies behind every caster the
// map holds, which is what comparing it at the far plane says (a cleared texel, 1, stays lit).
float shadowReference(float depth) { return min(depth, 1.0); }

// One texel's compare with the receiver plane (receiverPlaneDepthSlope, shadows.h): lit (1) when
// the plane's depth under the texel's centre, at most 1 (shadowReference), is no deeper than the
// caster's. The planes are exact, so what is left to cover is the depth format's rounding
// (frame.shadowDepthQuantum, a constant in depth units like a rasterizer's constant depth bias).
float compareWithPlane(float casterDepth, float planeDepth) {
    return shadowReference(planeDepth) - frame.shadowDepthQuantum <= casterDepth ? 1.0 : 0.0;
}

// The hardware 2 x 2 or N x N tent footprint (filterFootprint) with each texel compared with the
// receiver plane under its own centre, `slopeUv` the plane's depth per UV unit. The N + 1 texels a
// side (shadow_tent.h) are read as ((N + 1) / 2)^2 gathers of 2 x 2 raw depths, each at the
// corner its four texels share (the gather's most robust position, half a texel from a change of
// texels), and weighed by the tent's exact per-texel weights. Gathers are clamped inside the
// view's square (clamp to edge, as filterAtlas); a clamped texel's plane depth is taken under the
// texel actually read.
float filterAtlasReceiverPlane(ShadowRead read, GpuShadowView view, vec2 uv, float depth, vec2 slopeUv) {
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    uint n = filterFootprint();
    float resolution = read.resolution;
    vec2 position = uv * resolution;    // the sample point, in texels
    vec2 slope = slopeUv / resolution;  // the plane's depth per texel
    vec2 o = tentCornerOffset(position);
    uint perAxis = tentFetchesPerAxis(n);
    countShadowLookup(perAxis * perAxis);
    // Virtual pages: the pages of the N + 1 texels a side around the sample point.
    bool paged = SHADOW_PAGES != PUNCTUAL_SHADOW_PAGES_OFF && read.paged;  // (as in filterAtlas)
    PageBlock block;
    if (paged) block = virtualPageBlock(read.view, read.level, position, 0.5 * float(n) + 1.0);
    float sum = 0.0;
    [[dont_unroll]] for (uint i = 0u; i < perAxis * perAxis; ++i) {
        vec3 u = shadowKernelTexelPair(SHADOW_KERNEL, o.x, n, i % perAxis);
        vec3 v = shadowKernelTexelPair(SHADOW_KERNEL, o.y, n, i / perAxis);
        vec2 gatherCorner = clamp(position + vec2(u.x, v.x) + 0.5, vec2(1.0), vec2(resolution - 1.0));
        vec2 low = gatherCorner - 0.5 - position;  // centres of the texels read, from the sample point
        vec2 high = low + 1.0;
        vec4 casters = paged ? virtualGather(block, ivec2(round(gatherCorner)))
                           : textureGather(shadowAtlasDepth, view.atlasRect.xy + gatherCorner / resolution * view.atlasRect.zw, 0);
        // textureGather's order: (u0, v1), (u1, v1), (u1, v0), (u0, v0).
        sum += u.y * v.z * compareWithPlane(casters.x, depth + dot(slope, vec2(low.x, high.y)));
        sum += u.z * v.z * compareWithPlane(casters.y, depth + dot(slope, high));
        sum += u.z * v.y * compareWithPlane(casters.z, depth + dot(slope, vec2(high.x, low.y)));
        sum += u.y * v.y * compareWithPlane(casters.w, depth + dot(slope, low));
    }
    return sum;  // the tent's weights sum to 1
}

// A spot view or point slice of the atlas (or its virtual pages), from the biased receiver and its
// normal: per-texel receiver-plane compares where they apply (receiverPlaneCompares), the notes'
// per-tap compares otherwise.
float filterAtlasView(ShadowRead read, GpuShadowView view, vec3 normal, float angle) {
    vec4 clip = view.viewProjection * vec4(read.biased, 1.0);
    if (clip.w <= 0.0) return 1.0;
    vec3 ndc = clip.xyz / clip.w;  // perspective: divide by w
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (receiverPlaneCompares()) {
        return filterAtlasReceiverPlane(read, view, uv, ndc.z, receiverPlaneDepthSlope(view.viewProjection, read.biased, normal));
    }
    return filterAtlas(read, view, uv, shadowReference(ndc.z), angle);
}

// Cube faces: the direction's position on face f is uv = (sc / |ma| + 1) / 2 with sc = r.U,
// tc = r.V (shadows.h), and a UV offset d moves the lookup direction by 2 d |ma| along the face's
// U or V axis (the face spans [-1, 1] in sc / |ma| over UV [0, 1]).
float filterCube(vec3 direction, uint face, float cube, float reference, float angle, float resolution) {
    float major = abs(dot(direction, cubeFaceAxis(face)));
    vec2 uv = (vec2(dot(direction, cubeFaceU(face)), dot(direction, cubeFaceV(face))) / major + 1.0) * 0.5;
    vec3 u = cubeFaceU(face) * (2.0 * major);
    vec3 v = cubeFaceV(face) * (2.0 * major);
    countShadowLookup(filterSampleCount());
    float sum = 0.0;
    float weights = 0.0;
    [[dont_unroll]] for (uint i = 0u; i < filterSampleCount(); ++i) {
        vec3 s = filterSample(i, angle, uv, resolution);
        sum += s.z * texture(pointShadows, vec4(direction + u * s.x + v * s.y, cube), reference);
        weights += s.z;
    }
    return sum / weights;
}


// The resolution a receiver `linearDepth` along view `viewIndex`'s axis reads: the view's square, or
// with virtual pages its level's (virtualReadLevel, which `level` receives; 0 otherwise).
float shadowResolutionAt(uint viewIndex, GpuShadowView view, float linearDepth, vec3 position, out uint level) {
    level = 0u;
    switch (SHADOW_PAGES) {
        case PUNCTUAL_SHADOW_PAGES_OFF: return view.texel.x;
        case PUNCTUAL_SHADOW_PAGES_LOOKUP:
        case PUNCTUAL_SHADOW_PAGES_MARK:
            level = virtualReadLevel(viewIndex, view, linearDepth, position);
            return float(PUNCTUAL_VIRTUAL_SHADOW_SIZE >> level);
        default: unknownVariant = true; return view.texel.x;
    }
}

// The penumbra that widens the bias (ShadowSettings::biasPenumbraTexels): the view's, or with
// virtual pages the same rule at the level's resolution (the disk's reach grows with it).
float biasPenumbraAt(GpuShadowView view, float resolution) {
    if (SHADOW_PAGES == PUNCTUAL_SHADOW_PAGES_OFF) return view.texel.z;
    return receiverPlaneCompares() ? 0.0
                                   : shadowKernelReachTexels(SHADOW_KERNEL, SHADOW_FILTER_SIZE, frame.diskRadius * resolution);
}

// Where the receiver reads `light`'s map. Spot: its one view; linear depth along the spot axis
// sizes the texel (design notes). Point: the face is the major axis of the light-to-point
// direction, sized there, and then the face the biased point falls on.
ShadowRead shadowReadOf(GpuPunctualLight light, vec3 toLight, vec3 position, vec3 normal) {
    uint first = uint(light.angleOffsetShadow.y);
    vec3 lightPosition = light.positionInvRangeSq.xyz;
    ShadowRead read;
    if (light.angleOffsetShadow.z > -1.0) {
        read.view = first;
        GpuShadowView view = shadowViews[first];
        float linearDepth = abs(dot(lightPosition - position, light.directionAngleScale.xyz));
        read.resolution = shadowResolutionAt(first, view, linearDepth, position, read.level);
        float texel = shadowTexelWorldSize(linearDepth, view.params.y, read.resolution);
        read.biased = applyShadowBias(position, normal, toLight, texel, biasPenumbraAt(view, read.resolution), frame.shadowBias);
    } else {
        vec3 direction = position - lightPosition;
        uint face = cubeFaceOfDirection(direction);
        float linearDepth = abs(dot(direction, cubeFaceAxis(face)));
        GpuShadowView unbiasedView = shadowViews[first + face];
        read.resolution = shadowResolutionAt(first + face, unbiasedView, linearDepth, position, read.level);
        float texel = shadowTexelWorldSize(linearDepth, unbiasedView.params.y, read.resolution);
        read.biased = applyShadowBias(position, normal, toLight, texel, biasPenumbraAt(unbiasedView, read.resolution),
                                      frame.shadowBias);
        read.view = first + cubeFaceOfDirection(read.biased - lightPosition);
        // Whole views: the face read may have another tier than the one that sized the bias, and
        // its lookups are in its own texels (read with the other face's, near the edge a tap
        // fell half a texel outside its square, into a neighbour's). Virtual levels follow the
        // receiver's pixel, the same level on either face.
        if (SHADOW_PAGES == PUNCTUAL_SHADOW_PAGES_OFF) read.resolution = shadowViews[read.view].texel.x;
    }
    read.hasMap = shadowViews[read.view].params.x >= 0.0;  // no caster in its frustum, or no storage: lit
    read.paged = SHADOW_PAGES != PUNCTUAL_SHADOW_PAGES_OFF;
    return read;
}

// The marking pass (PUNCTUAL_SHADOW_PAGES_MARK): marks the pages the lookup below will read for
// this receiver and light, where it will read any (a view with a map, the receiver inside it).
void markShadowPages(GpuPunctualLight light, vec3 toLight, vec3 position, vec3 normal) {
    ShadowRead read = shadowReadOf(light, toLight, position, normal);
    if (!read.hasMap) return;
    vec4 clip = shadowViews[read.view].viewProjection * vec4(read.biased, 1.0);
    if (clip.w <= 0.0) return;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return;
    markVirtualFootprint(read.view, read.level, uv);
}

// Fraction of `light` reaching `position` past the shadow casters (1 = lit), blended by the
// light's shadow strength. Called only where the light's attenuation is non-zero.
float shadowVisibility(GpuPunctualLight light, vec3 toLight, vec3 position, vec3 normal) {
    ShadowRead read = shadowReadOf(light, toLight, position, normal);
    if (!read.hasMap) return 1.0;
    GpuShadowView view = shadowViews[read.view];
    float angle = filterAngle(position);
    float visibility = 1.0;
    bool spot = light.angleOffsetShadow.z > -1.0;
    // One call site for the atlas's views (spots, and points as slices): the shader compiler
    // inlines every call, and the filters are the shader's largest code.
    bool cube = false;
    if (!spot) {
        switch (POINT_SHADOW_LAYOUT) {
            case PUNCTUAL_POINT_SHADOW_CUBE: cube = true; break;
            case PUNCTUAL_POINT_SHADOW_SLICES: break;
            default: unknownVariant = true; return 1.0;
        }
    }
    if (cube) {
        vec3 biasedDirection = read.biased - light.positionInvRangeSq.xyz;
        uint face = read.view - uint(light.angleOffsetShadow.y);
        float reference = shadowReference(
            perspectiveDepth(abs(dot(biasedDirection, cubeFaceAxis(face))), view.params.z, view.params.w));
        visibility = filterCube(biasedDirection, face, view.atlasRect.x, reference, angle, view.texel.x);
    } else {
        visibility = filterAtlasView(read, view, normal, angle);
    }
    return mix(1.0, visibility, light.angleOffsetShadow.w);
}

// ---- the sun's cascades (cascades.h, lights/cascade_setup.h) ------------------------------------

// Cascade `cascade`'s shadow at the receiver, through the same atlas lookups as a spot view. The
// seed's normal bias per cascade: its texel widened by sqrt 2 (the texel's diagonal), through the
// same bias formula as every light.
float cascadeShadow(uint cascade, vec3 position, vec3 normal, vec3 toSun, float angle) {
    GpuShadowView view = shadowViews[frame.sunShadow.x + cascade];
    if (view.params.x < 0.0) return 1.0;  // no caster, or no storage
    float texel = cascadeTexelWorldSize(0.5 * view.params.y, view.texel.x) * 1.41421356;
    ShadowRead read;
    read.view = frame.sunShadow.x + cascade;
    read.level = 0u;
    read.resolution = view.texel.x;
    read.biased = applyShadowBias(position, normal, toSun, texel, view.texel.z, frame.shadowBias);
    read.hasMap = true;
    read.paged = false;  // the cascades stay whole views of the atlas
    return filterAtlasView(read, view, normal, angle);
}

// The sun's visibility at the receiver (1 = lit), and the cascade it read (frame.sunShadow.y when
// none: beyond the shadow distance). As the seed's GetShadowData and GetDirectionalShadowAttenuation:
//  - the shadow fades out over the last distanceFade of the shadow distance (view depth);
//  - the first cascade whose selection sphere holds the receiver is read; within the outer
//    cascadeFade of its radius the last cascade fades out, and any other blends with the next
//    (CASCADE_BLEND: hard ignores it, soft mixes the two, dither picks the next where the fade is
//    below the pixel's noise).
float sunVisibility(vec3 position, vec3 normal, out uint cascade) {
    uint count = frame.sunShadow.y;
    float viewDepth = -(frame.view * vec4(position, 1.0)).z;
    float strength = frame.sunShadowFade.w * fadedShadowStrength(viewDepth, frame.sunShadowFade.x, frame.sunShadowFade.y);
    cascade = cascadeOf(position, frame.cascadeSpheres[0], frame.cascadeSpheres[1], frame.cascadeSpheres[2],
                        frame.cascadeSpheres[3], count);
    if (cascade >= count || strength <= 0.0) return 1.0;
    vec4 sphere = frame.cascadeSpheres[cascade];
    vec3 fromCentre = position - sphere.xyz;
    float fade = fadedShadowStrength(dot(fromCentre, fromCentre), 1.0 / max(sphere.w, 1e-20), frame.sunShadowFade.z);
    float blend = 1.0;
    if (cascade == count - 1u) {
        strength *= fade;
    } else {
        blend = fade;
    }
    switch (CASCADE_BLEND) {
        case PUNCTUAL_CASCADE_BLEND_HARD: blend = 1.0; break;
        case PUNCTUAL_CASCADE_BLEND_SOFT: break;
        case PUNCTUAL_CASCADE_BLEND_DITHER:
            if (blend < interleavedGradientNoise(gl_FragCoord.xy)) cascade += 1u;
            blend = 1.0;
            break;
        default: unknownVariant = true; return 1.0;
    }
    vec3 toSun = frame.sun.directionToLight.xyz;
    float angle = filterAngle(position);
    float shadow = cascadeShadow(cascade, position, normal, toSun, angle);
    if (blend < 1.0) shadow = mix(cascadeShadow(cascade + 1u, position, normal, toSun, angle), shadow, blend);
    return mix(1.0, shadow, strength);
}
