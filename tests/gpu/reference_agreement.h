#pragma once
// The GPU image against the Embree reference, pixel by pixel: how many agree within a tolerance,
// and whether the ones that differ all lie on silhouettes (where rasteriser and ray tracer may
// legitimately pick different surfaces). Shared by the GPU tests that compare the two images.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "reference/reference_renderer.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace punctual::testing {

struct Agreement {
    size_t pixels = 0;
    size_t within = 0;                // every channel within the tolerance
    size_t offSilhouette = 0;         // differing pixels not on a silhouette or crease
    double withinFraction() const { return double(within) / double(pixels); }
};

// A pixel is on a silhouette when its 3x3 neighbourhood in the GPU depth buffer holds background
// or a view-distance jump above 3%, or when the reference's neighbouring hits cross an object
// boundary or a crease (geometric normals apart by more than ~8 degrees). There, a pixel centre
// can lie on the edge itself, and the rasteriser's tie-breaking and Embree's may pick different
// sides; anywhere else the two must agree.
// Saves NAME-gpu, NAME-reference and NAME-diff (grey: difference x 32, blue: allowed, red: not).
Agreement compare(const ImageRgba8& gpu, const std::vector<float>& depth, const glm::mat4& projection,
                  const ImageRgba8& ref, const std::vector<reference::SurfaceHit>& hits, const std::string& name,
                  int tolerance = 2);

struct GpuFrame {
    ImageRgba8 image;
    std::vector<float> depth;
    glm::mat4 projection;
};

// One unshadowed brute-force frame (the unshadowed reference's counterpart) and its depth.
GpuFrame renderGpu(vk::Context& context, const Scene& scene, uint32_t width, uint32_t height);

// At least 99.9% of the pixels within the tolerance, and none off silhouettes beyond it.
void expectAgreement(const Agreement& agreement, const std::string& what);

}  // namespace punctual::testing
