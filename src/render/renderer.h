#pragma once
// One frame, end to end: light setup on the CPU, then the passes in frame order (depth prepass,
// light culling, shadow stage, forward pass, tone mapping; see pass.h) and the readback. Owns every
// GPU resource of the frame, sized to the scene and the output: nothing is allocated for lights,
// objects or textures the scene does not have.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/image.h"
#include "gpu_types.h"
#include "lights/light_setup.h"
#include "lights/per_object_lights.h"
#include "lights/shadow_page_allocation.h"
#include "lights/z_bins.h"
#include "lights/shadow_setup.h"
#include "metrics/culling_stats.h"
#include "metrics/shadow_factor_image.h"
#include "render/frame_plan.h"
#include "render/light_culling_pass.h"
#include "render/light_list_method.h"
#include "render/pass_list.h"
#include "render/pass_timings.h"
#include "render/render_settings.h"
#include "scene/scene.h"

#include <vulkan/vulkan.h>

namespace punctual::vk {
class Buffer;
class Context;
}

namespace punctual::render {

// What the camera's passes draw: the objects whose bounds meet its frustum (all of them with
// RenderSettings::cullObjectsToView off), one draw each per pass that draws its kind.
struct CameraDraws {
    uint64_t objectsInView = 0;
    uint64_t depthDraws = 0;        // the prepass: opaque and masked objects in view
    uint64_t forwardDraws = 0;      // the forward pass: the same objects
    uint64_t transparentDraws = 0;  // the transparent pass (and the transparent depth pass)
    uint64_t triangles = 0;         // the triangles of the objects in view, each object's mesh once
    // The triangles each pass submits (each drawn object's mesh once).
    uint64_t depthTriangles = 0;
    uint64_t forwardTriangles = 0;
    uint64_t transparentTriangles = 0;
};

// The device memory the renderer allocated, by what it holds (docs/BENCH_RESULTS.md).
struct DeviceMemory {
    uint64_t scene = 0;      // vertex, index, object and material buffers, textures
    uint64_t shadows = 0;    // shadow maps (atlas, cube array)
    uint64_t lightGrid = 0;  // the culling pass's grid and depth bounds
    uint64_t frame = 0;      // everything else: depth, radiance, uniforms, lights, statistics, readback
    uint64_t total() const { return scene + shadows + lightGrid + frame; }
};

// What the shadow passes draw: each rendered view's casters, one draw each (in each drawing tile
// they reach, for a view larger than the drawing square: lights/shadow_drawing_tiles.h).
struct ShadowDraws {
    uint64_t total = 0;
    uint64_t maxPerView = 0;
    uint64_t triangles = 0;  // summed over the rendered views, each view's casters once
};

// Virtual shadow pages (--shadow-res virtual): what the marking frames found and the allocation did.
struct ShadowPageStats {
    ShadowPageCounts marked;           // the first marking frame's pages, each view at the level its receivers ask
    uint64_t coarsenedPages = 0;       // pages of `marked` whose views read coarser levels to fit the budget
    uint32_t coarsenedViews = 0;
    uint32_t markingFrames = 0;        // 1, plus one per coarsening round
    uint64_t marksBytes = 0;           // the marking pass's bits
    double allocateMs = 0.0;           // CPU: counting, coarsening, allocating, placing, culling casters per page
};

struct FrameResult {
    ImageRgba8 image;
    PassTimings medianMs;              // per pass, median over the timed frames
    std::vector<PassTimings> framesMs; // every timed frame
};

class ShadowCache;
struct ShadowCacheFrame;

class Renderer {
public:
    // With `shadowCache` (render/shadow_cache.h; made with settings.shadows, outliving the
    // renderer), the shadow stage draws into the cache's maps and keeps the views whose depth
    // the last renderer given it left unchanged.
    Renderer(vk::Context& context, const Scene& scene, const RenderSettings& settings,
             ShadowCache* shadowCache = nullptr);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Renders `warmup` untimed frames (the first frame pays for lazy driver work such as shader
    // compilation on lavapipe), then `frames` timed ones (the same frame each time), and returns
    // the last image with the median per-pass GPU times.
    FrameResult render(uint32_t frames = 1, uint32_t warmup = 1);

    // Depth buffer of the last frame, row-major top to bottom, in [0, 1] (1 = background).
    std::vector<float> readDepth();
    // The light grid of the last frame as masks: gridLayout().gridWordCount() words (the grid
    // methods only; index lists are read back as the masks they stand for, metrics/index_lists.h).
    std::vector<uint32_t> readLightGrid();
    // Index lists: the words of the index array the last frame's lists took (0 with masks).
    uint32_t readLightIndexWordsUsed();
    // The light lists' own memory: the grid's masks, or its headers and the index array (the grid
    // methods only; the culling shapes, the coarse grid and the slices' masks are apart).
    uint64_t lightListBytes() const;
    // The coarse pass's masks of the last frame: coarseTilesX() * coarseTilesY() * gridWords
    // words (gridLayout()); empty without the coarse pass.
    std::vector<uint32_t> readCoarseGrid();
    gpu::GpuDepthRange readDepthRange();
    // Runs the statistics variant of the forward pass (needs settings.collectLightStats).
    LightStatsImage readLightStats();
    // Runs the shadow-validation variant of the forward pass (needs settings.collectShadowFactors).
    ShadowFactorImage readShadowFactors();

    const LightGridLayout& gridLayout() const { return plan_.gridLayout; }
    const PerObjectLightLists& perObjectLists() const { return plan_.perObjectLists; }
    // The z-bin method's bins (lights/z_bins.h); empty (nullopt) for the other methods.
    const std::optional<ZBins>& zBins() const { return plan_.zBins; }
    const ShadowPlan& shadowPlan() const { return plan_.shadows; }
    uint64_t shadowMemoryBytes() const;
    // Device memory the renderer allocated: the scene's buffers and textures, every pass's images
    // and buffers, the frame's own buffers (debug outputs and readback included).
    uint64_t deviceMemoryBytes() const { return deviceMemory().total(); }
    DeviceMemory deviceMemory() const;
    const CameraDraws& cameraDraws() const { return cameraDraws_; }
    // The views drawn (with a shadow cache, not the views it kept).
    ShadowDraws shadowDraws() const;
    // What the shadow cache kept this frame; nullptr without one.
    const ShadowCacheFrame* shadowCacheFrame() const;
    // Virtual shadow pages: the allocation (no pages otherwise) and what made it.
    const ShadowPageAllocation& shadowPages() const { return pageAllocation_; }
    const ShadowPageStats& shadowPageStats() const { return pageStats_; }
    // Virtual pages: the last frame's marks (ShadowPageMarkLayout::of(shadowPlan()) words).
    std::vector<uint32_t> readShadowPageMarks();
    // The pages' draws: draws (a view's caster), instances (a page of it), pages drawn into.
    struct ShadowPageDrawCounts {
        uint64_t draws = 0;
        uint64_t instances = 0;
        uint64_t pagesDrawn = 0;
    };
    ShadowPageDrawCounts shadowPageDraws() const;
    const FrameLights& lights() const { return plan_.lights; }
    const glm::mat4& view() const { return plan_.view; }
    const glm::mat4& projection() const { return plan_.projection; }
    const RenderSettings& settings() const { return settings_; }

    // The names of the frame's passes, in frame order (the keys of PassTimings).
    std::vector<std::string> passNames() const;

private:
    struct Resources;
    // Checks the image layouts of `passes` (pass_list.h; `resting`: where the frame leaves each
    // image) and records them in order into `cmd`. `timed`: the frame render() submits, with a
    // timer scope per pass and the readback of the tone-mapped image; otherwise a debug frame
    // (never timed).
    void recordFrame(VkCommandBuffer cmd, const std::vector<const Pass*>& passes, const ImageLayouts& resting,
                     bool timed);
    void submitAndWait(VkCommandBuffer cmd);
    // Records the frame and its debug variants (their command buffers made anew).
    void recordFrames();
    // Index lists: sizes the index array from a counting frame and records the frames again.
    void sizeIndexLists();
    // Virtual pages: runs marking frames (again after each coarsening round), allocates the pages
    // and records the frames again with them.
    void allocateShadowPages();
    std::vector<uint8_t> readBuffer(const vk::Buffer& buffer);
    std::vector<uint32_t> readWords(const vk::Buffer& buffer);  // readBuffer as 32-bit words

    vk::Context& context_;
    const Scene& scene_;
    RenderSettings settings_;
    FramePlan plan_;  // what the frame needs, decided before anything is allocated (frame_plan.h)
    CameraDraws cameraDraws_;
    ShadowPageAllocation pageAllocation_;
    ShadowPageStats pageStats_;
    ShadowCache* shadowCache_;
    std::unique_ptr<Resources> resources_;
};

}  // namespace punctual::render
