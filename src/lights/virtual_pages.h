#pragma once
// Virtual shadow pages (issue 33), first part: which pages a frame's visible receivers would need,
// on the CPU, and what they would cost beside the floor and beside --shadow-res auto's atlas.
//
// Each spot view and point face with casters is a virtual map (shaders/shared/shadow_pages.h).
// At every pixel (one primary ray through its centre, forEachVisibleReceiver), each view that
// shades the surface there (resolutionNeededAt > 0: in range, in the cone or on the face, facing
// the light; the tests of --shadow-res auto and of --shadow-density) is one shaded pair. The pair
// needs the resolution at which one texel spans 1 / texelsPerPixel pixels there, so the level
// nearest it (virtualShadowLevel) and the page under the surface at that level, and the pages
// its filter's footprint reaches there (a receiver near a page's border reads its neighbour's
// texels: virtualShadowFootprintPages, the filter's reach at the level's resolution). A page is
// marked once, however many pairs need it; the pages under the receivers alone are counted too.
//
// What it leaves out, for the GPU pass to settle:
//  - pages whose frustum meets no caster (they need no memory, only a "lit" entry);
//  - transparent receivers (the opaque surface only).
// The floor is the design notes' one texel per shaded pair (DESIGN.md, "Shadows fitted to the
// frame"): shadedPairs x the texel's bytes.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "scene/scene.h"

namespace punctual {

struct VirtualPageLayout {
    uint32_t virtualSize = 16384;  // texels a side of level 0 (a power of two)
    uint32_t pageSize = 128;       // texels a side of a page (a power of two, at most virtualSize)

    uint32_t levels() const;
    uint32_t pagesAcross(uint32_t level) const;
    uint32_t pagesPerView() const;  // over every level
};

// The layouts the estimate compares (RESULTS, issue 33): virtual sizes 4096 .. 16384 (auto's
// largest tier is 2048) by pages of 32 .. 256 texels.
std::vector<VirtualPageLayout> virtualPageLayoutsToCompare();

struct VirtualPageDemand {
    VirtualPageLayout layout;
    std::vector<uint64_t> markedPerLevel;  // pages marked at each level, over every view (with the filters' reach)
    uint64_t centrePages = 0;              // pages under the receivers alone, without the filters' reach
    uint64_t viewsWithPages = 0;           // views with at least one marked page
    uint64_t usedLevelEntries = 0;         // pages of the levels where a view has a marked page, over the views
    uint64_t pairsCoarserThanAsked = 0;    // shaded pairs whose need passed level 0's (density < 1/sqrt 2)

    uint64_t markedPages() const;
    // The marked pages' texels at `texelBytes` each: what the page pool must hold.
    uint64_t physicalBytes(uint32_t texelBytes) const;
    // One 32-bit entry per page of every level, for each view with a marked page (a whole table
    // per virtual map, as Unreal's), and only for the levels where the view has one.
    uint64_t pageTableBytes() const;
    uint64_t usedLevelsPageTableBytes() const { return usedLevelEntries * 4; }
};

struct VirtualPageEstimate {
    uint64_t shadedPairs = 0;  // (pixel, view with casters) pairs the frame shades
    std::vector<VirtualPageDemand> layouts;

    uint64_t floorBytes(uint32_t texelBytes) const { return shadedPairs * texelBytes; }
};

// The pages each of `layouts` would mark for a width x height frame of `scene` lit by `lights`
// with shadow views `plan` (cascades are left out: they stay whole), at the settings' texels a
// pixel (--shadow-texels-per-pixel) and with their filter's reach.
VirtualPageEstimate estimateVirtualPages(const Scene& scene, const FrameLights& lights, const ShadowPlan& plan,
                                         uint32_t width, uint32_t height, const ShadowSettings& settings,
                                         std::span<const VirtualPageLayout> layouts);

// Where a receiver at `position` (unit `normal`) reads `light`'s virtual map, as the forward
// shader's shadowReadOf does (shaders/shared/shadow_sampling.glsl): the view, its level and the
// biased receiver's UV, and the filter's reach in texels; nullopt where it reads none (no shadow,
// no light arriving, facing away, a view without a map, outside the view). `plan` must be sized
// for virtual pages.
struct VirtualRead {
    uint32_t view = 0;
    uint32_t level = 0;
    glm::vec2 uv{0.0f};
    float reach = 0.0f;
};
std::optional<VirtualRead> virtualReadOnCpu(const ShadowPlan& plan, const gpu::GpuPunctualLight& light,
                                            const glm::vec3& position, const glm::vec3& normal,
                                            const ShadowSettings& settings);

// The marking pass on the CPU (the GPU pass's oracle in the tests): one primary ray through every
// pixel of a width x height frame; at each surface it reaches (attenuation > 0) and faces, each
// shadowed light with a map marks, as shaders/shared/shadow_sampling.glsl's markShadowPages does,
// the pages its filter will read: the level of shadowResolutionRead, the receiver biased at that
// level's texel, its view (for a point light the face of the biased point), and the footprint of
// the filter's reach plus PUNCTUAL_VIRTUAL_SHADOW_MARK_MARGIN. `plan` must be sized for virtual
// pages (sizeShadowViews with --shadow-res virtual). Returns the marks in the GPU's layout
// (ShadowPageMarkLayout::of(plan)). The surfaces differ from the rasterized ones by what a ray
// hit differs from an interpolated fragment (a fraction of a pixel); so may a few pages.
std::vector<uint32_t> markVirtualPagesOnCpu(const Scene& scene, const FrameLights& lights, const ShadowPlan& plan,
                                            uint32_t width, uint32_t height, const ShadowSettings& settings);

}  // namespace punctual
