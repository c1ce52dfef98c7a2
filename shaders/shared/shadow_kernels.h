// Shadow filter kernels: how a filter reads the shadow map around its sample point. A filter of
// the C++ table (src/lights/shadow_filters.h) is a kernel and a size: hw is the bilinear kernel
// of size 1, tent3/5/7 the tent kernel of size 3/5/7, disk the disk kernel (its size unused, its
// taps and radius from --shadow-samples and --shadow-penumbra). The forward shader receives the
// two as specialization constants (SHADOW_KERNEL, SHADOW_FILTER_SIZE), so a filter that reuses a
// kernel at a new size is a table row and nothing here. A new kernel is its define below, its
// case in every switch of this file (its taps, its reach, and in the GLSL part its samples and,
// for a kernel with a texel footprint, its per-texel weights), and its table row.
//
// Shared by the C++ tables and shadow setup (taps, reach: the statistics' counts and the bias's
// penumbra) and the forward shader (shadow_sampling.glsl), so both count and reach alike.
#ifndef PUNCTUAL_SHADOW_KERNELS_H
#define PUNCTUAL_SHADOW_KERNELS_H

#include "glsl_cpp.h"
#include "shadow_tent.h"

#define PUNCTUAL_SHADOW_KERNEL_BILINEAR 0u  // the hardware's one 2 x 2 bilinear compare (size 1)
#define PUNCTUAL_SHADOW_KERNEL_TENT 1u      // Unity's N x N tent (size N, odd): shadow_tent.h
#define PUNCTUAL_SHADOW_KERNEL_DISK 2u      // Vogel disk rotated per pixel, per-tap compares
#define PUNCTUAL_SHADOW_KERNEL_COUNT 3u

PUNCTUAL_NAMESPACE_BEGIN

// The texel footprint a kernel of size N reads: N for the kernels that read an N x N square of
// texels around the sample point, whose texels receiver-plane compares can weigh one by one
// (shadow_sampling.glsl); 0 for those that do not (the disk keeps the design notes' per-tap
// compares). 0 for an unknown kernel.
PUNCTUAL_CONSTEXPR_FN uint shadowKernelFootprint(uint kernel, uint size) {
    switch (kernel) {
        case PUNCTUAL_SHADOW_KERNEL_BILINEAR: return 1u;
        case PUNCTUAL_SHADOW_KERNEL_TENT: return size;
        case PUNCTUAL_SHADOW_KERNEL_DISK: return 0u;
        default: return 0u;
    }
}

// Hardware compare lookups per shadow test, with `diskSamples` taps for the disk. The tent's
// ((N + 1) / 2)^2 bilinear fetches cover its (N + 1) x (N + 1) texels (shadow_tent.h). 0 for an
// unknown kernel, which the shader then flags (filterSampleCount).
PUNCTUAL_CONSTEXPR_FN uint shadowKernelTaps(uint kernel, uint size, uint diskSamples) {
    switch (kernel) {
        case PUNCTUAL_SHADOW_KERNEL_BILINEAR: return 1u;
        case PUNCTUAL_SHADOW_KERNEL_TENT: return tentFetchCount(size);
        case PUNCTUAL_SHADOW_KERNEL_DISK: return diskSamples;
        default: return 0u;
    }
}

// How far from the sample point the kernel reads, in texels (the design notes' penumbra, which
// widens the bias and the slices layout's guard band): half its footprint (the bilinear 2 x 2
// reaches half a texel, an N x N tent N / 2), or the disk's radius in texels. 0.5 for an unknown
// kernel, the least any kernel reads.
PUNCTUAL_FN float shadowKernelReachTexels(uint kernel, uint size, float diskRadiusTexels) {
    switch (kernel) {
        case PUNCTUAL_SHADOW_KERNEL_BILINEAR: return 0.5f;
        case PUNCTUAL_SHADOW_KERNEL_TENT: return 0.5f * float(size);
        case PUNCTUAL_SHADOW_KERNEL_DISK: return diskRadiusTexels;
        default: return 0.5f;
    }
}

PUNCTUAL_NAMESPACE_END

#ifndef __cplusplus
// ---- GLSL: the kernels' samples (shadow_sampling.glsl's loops call these) ------------------------
// An unknown kernel takes no sample and sets unknownVariant (forward.frag), which shades magenta:
// it never passes for another kernel. tests/unit/test_variant_tables.cpp checks that every switch
// on `kernel` here names every kernel.

// Offset (xy, UV units) and weight (z) of sample i (0 .. shadowKernelTaps - 1) around the position
// uv (in [0, 1] over the view or cube face, `resolution` texels a side). `angle` rotates the disk
// per pixel; `diskSamples` and `diskRadius` (UV units) are its settings.
vec3 shadowKernelSample(uint kernel, uint size, uint i, float angle, vec2 uv, float resolution, uint diskSamples,
                        float diskRadius) {
    switch (kernel) {
        case PUNCTUAL_SHADOW_KERNEL_BILINEAR: return vec3(0.0, 0.0, 1.0);
        case PUNCTUAL_SHADOW_KERNEL_TENT: {
            vec3 fetch = tentFetch(uv * resolution, size, i);
            return vec3(fetch.xy / resolution, fetch.z);
        }
        case PUNCTUAL_SHADOW_KERNEL_DISK: {
            // Vogel disk: radius sqrt((i + 0.5) / N) of the full radius, golden-angle steps, so
            // samples cover the disk evenly for any N.
            float r = sqrt((float(i) + 0.5) / float(diskSamples)) * diskRadius;
            float a = float(i) * 2.39996323 + angle;
            return vec3(r * cos(a), r * sin(a), 1.0);
        }
        default: unknownVariant = true; return vec3(0.0);
    }
}

// The footprint kernels' texels (receiver-plane compares): texel pair m of the N + 1 along one
// axis, for a sample point at `o` from its nearest texel corner (shadow_tent.h): x = the centre of
// texel 2m from the sample point, in texels, y and z = the two texels' weights. Only kernels with
// a footprint (shadowKernelFootprint > 0) are asked.
vec3 shadowKernelTexelPair(uint kernel, float o, uint size, uint m) {
    switch (kernel) {
        case PUNCTUAL_SHADOW_KERNEL_BILINEAR: return tentAxisTexelPair(o, 1u, m);  // the bilinear weights
        case PUNCTUAL_SHADOW_KERNEL_TENT: return tentAxisTexelPair(o, size, m);
        case PUNCTUAL_SHADOW_KERNEL_DISK: unknownVariant = true; return vec3(0.0);  // no footprint
        default: unknownVariant = true; return vec3(0.0);
    }
}

// Whether the kernel turns its samples by a per-pixel angle (hashToUnit in shadow_sampling.glsl).
bool shadowKernelRotates(uint kernel) { return kernel == PUNCTUAL_SHADOW_KERNEL_DISK; }
#endif

#endif
