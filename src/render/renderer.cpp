#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <array>
#include <cmath>
#include <cstring>
#include <iterator>

#include "core/check.h"
#include "core/error.h"
#include "cascades.h"
#include "core/log.h"
#include "culling.h"
#include "gpu_types.h"
#include "lights/cascade_setup.h"
#include "lights/shadow_drawing_tiles.h"
#include "lights/shadow_page_allocation.h"
#include "lights/shadow_sizing.h"
#include "lights/view_objects.h"
#include "metrics/debug_buffers.h"
#include "metrics/index_lists.h"
#include "render/depth_prepass.h"
#include "render/frame_plan.h"
#include "render/forward_pass.h"
#include "render/frame_bindings.h"
#include "render/pass_list.h"
#include "render/scene_gpu.h"
#include "render/shadow_cache.h"
#include "render/shadow_maps.h"
#include "render/shadow_pass.h"
#include "render/tonemap_pass.h"
#include "render/transparent_depth_pass.h"
#include "vk/buffer.h"
#include "vk/check.h"
#include "vk/command_buffer.h"
#include "vk/context.h"
#include "vk/descriptors.h"
#include "vk/gpu_timer.h"
#include "vk/image.h"

namespace punctual::render {
namespace {

bool usesShadowPages(const RenderSettings& settings) {
    return settings.shadows.enabled && settings.shadows.virtualPages();
}

}  // namespace

// Every GPU resource of the frame. The passes own what they write (depth, light grid, shadow
// maps, tone-mapped pixels); the frame's shared inputs and the debug outputs live here.
struct Renderer::Resources {
    SceneGpu scene;
    vk::Buffer frameUniform;
    vk::Buffer lights;
    vk::Buffer objectLights;
    vk::Buffer lightStats;
    vk::Buffer shadowDebug;
    vk::Buffer shadowPageMarks;  // virtual pages: the marking pass's bits (lights/shadow_page_allocation.h)
    vk::Buffer previousPageMarks;  // virtual pages with hysteresis: the previous frame's (VirtualPageReads)
    vk::Image radiance;
    // The passes in frame order; the typed pointers below point into this list.
    PassList passes;
    // Set 0's images, each in the layout its binding reads it in (the layout check's input).
    std::vector<BoundImage> boundImages;
    DepthPrepass* depth = nullptr;
    LightCullingPass* culling = nullptr;
    ShadowPass* shadows = nullptr;
    ForwardPass* forward = nullptr;  // the opaque one
    TonemapPass* tonemap = nullptr;
    // Debug variants of the forward pass, each recorded into its own command buffer after the
    // passes before `forward`, in its place; never timed.
    std::unique_ptr<ForwardPass> lightStatsPass;     // with collectLightStats
    std::unique_ptr<ForwardPass> transparentStatsPass;  // with collectLightStats: the transparent fragments
    std::unique_ptr<ForwardPass> shadowFactorsPass;  // with collectShadowFactors
    std::unique_ptr<FrameBindings> bindings;
    vk::Buffer readback;
    vk::GpuTimer timer;
    vk::CommandBuffer commandBuffer;
    vk::CommandBuffer lightStatsCommands;
    vk::CommandBuffer shadowFactorsCommands;
    vk::Handle<VkFence> fence;

    // A storage buffer holding `words`, or one word when the frame does not use it (a descriptor
    // cannot point at nothing).
    static vk::Buffer storageWords(vk::Context& context, const std::vector<uint32_t>& words, const char* name) {
        const std::vector<uint32_t> data = words.empty() ? std::vector<uint32_t>{0u} : words;
        vk::Buffer buffer(context, data.size() * sizeof(uint32_t),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          vk::MemoryUse::DeviceLocal, name);
        vk::uploadToBuffer(context, buffer, data.data(), data.size() * sizeof(uint32_t));
        return buffer;
    }

    // A buffer the debug variants write, `bytes` long when requested and 16 bytes otherwise.
    static vk::Buffer debugOutput(const vk::Context& context, bool requested, VkDeviceSize bytes, const char* name) {
        return vk::Buffer(context, requested ? bytes : 16,
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          vk::MemoryUse::DeviceLocal, name);
    }

    static ForwardVariant forwardVariant(const RenderSettings& settings, const LightGridLayout& grid, bool stats,
                                         bool shadowFactors) {
        ForwardVariant variant;
        variant.lightSource = methodInfo(settings.method).source.value;
        variant.tileSize = grid.tileSize;
        variant.slices = grid.slices;
        variant.gridWords = grid.gridWords;
        variant.listForm = grid.listForm();
        variant.writeLightStats = stats;
        variant.shadows = settings.shadows.enabled;
        const ShadowFilterInfo& filter = shadowFilterInfo(settings.shadows.filter);
        variant.shadowKernel = filter.kernel.value;
        variant.shadowFilterSize = filter.size;
        variant.shadowSamples = settings.shadows.diskSamples;
        variant.pointShadowLayout = uint32_t(settings.shadows.pointLayout);
        variant.writeShadowFactors = shadowFactors;
        variant.shadowReceiverPlane = settings.shadows.receiverPlane;
        variant.cascadeBlend = uint32_t(settings.shadows.cascades.blend);
        const ShadowResolutionModeInfo* mode = findVariant(kShadowResolutionModes, settings.shadows.resolution);
        variant.shadowPages = mode ? mode->pages.value : PUNCTUAL_SHADOW_PAGES_OFF;
        return variant;
    }

    // The transparent objects farthest first (by their bounds' centres), so each blends over the
    // ones behind it; ties keep object order. Per object, not per triangle: an object's own
    // triangles blend in index order (README, "Materials").
    static std::vector<uint32_t> backToFront(const Scene& scene, std::vector<uint32_t> objects, glm::vec3 eye) {
        std::stable_sort(objects.begin(), objects.end(), [&](uint32_t a, uint32_t b) {
            return glm::distance(scene.objects[a].worldBounds.center(), eye) >
                   glm::distance(scene.objects[b].worldBounds.center(), eye);
        });
        return objects;
    }

    // `inView`: the objects the camera's passes draw, ascending; `draws` is filled with their counts.
    Resources(vk::Context& context, const Scene& sceneData, const RenderSettings& settings, const FramePlan& plan,
              const ShadowCache* shadowCache, CameraDraws& draws)
        : scene(context, sceneData, plan.perObjectLists.counts),
          frameUniform(context, sizeof(gpu::GpuFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload,
                       "frame"),
          // Sized to the lights this frame really uses; one slot when there are none.
          lights(context, std::max<size_t>(plan.lights.packed.size(), 1) * sizeof(gpu::GpuPunctualLight),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "lights"),
          objectLights(storageWords(context, plan.perObjectLists.lights, "object lights")),
          // The light statistics' blocks (gpu_types.h): opaque surfaces, transparent fragments,
          // the opaque surface's list cell and tested lights, then each list cell's reaching lights.
          lightStats(debugOutput(context, settings.collectLightStats,
                                 lightStatsBytes(settings.width, settings.height, listCellCount(sceneData, settings, plan),
                                                 plan.gridLayout.gridWords),
                                 "light stats")),
          shadowDebug(debugOutput(context, settings.collectShadowFactors, shadowFactorBytes(settings.width, settings.height),
                                  "shadow debug")),
          shadowPageMarks(debugOutput(context, usesShadowPages(settings),
                                      VkDeviceSize(std::max(ShadowPageMarkLayout::of(plan.shadows).words, 1u)) * 4,
                                      "shadow page marks")),
          previousPageMarks(storageWords(context, plan.shadows.virtualReads.previousMarks, "previous shadow page marks")),
          readback(context, VkDeviceSize(settings.width) * settings.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                   vk::MemoryUse::Readback, "readback"),
          timer(context, 16) {
        vk::ImageDesc radianceDesc;
        radianceDesc.format = ForwardPass::kRadianceFormat;
        radianceDesc.width = settings.width;
        radianceDesc.height = settings.height;
        radianceDesc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        radianceDesc.debugName = "radiance";
        radiance = vk::Image(context, radianceDesc);
        if (!plan.lights.packed.empty()) {
            lights.write(plan.lights.packed.data(), plan.lights.packed.size() * sizeof(gpu::GpuPunctualLight));
        }
        addPasses(context, sceneData, settings, plan, shadowCache, draws);
        bindPasses(context);
    }

    // The frame, in order, and the statistics and validation variants of its forward pass. The
    // camera's passes draw the objects in view only, each list in object order as before (so every
    // fragment is drawn in the same order: the same image).
    void addPasses(vk::Context& context, const Scene& sceneData, const RenderSettings& settings, const FramePlan& plan,
                   const ShadowCache* shadowCache, CameraDraws& draws) {
        const std::vector<gpu::CullLight> cullLights = viewCullLights(plan.lights, plan.view);
        const std::vector<uint32_t>& inView = plan.objectsInView;
        const LightGridLayout& gridLayout = plan.gridLayout;
        const glm::vec3 eye(glm::inverse(plan.view)[3]);
        auto visible = [&](std::span<const uint32_t> objects) {
            return keepInView(std::vector<uint32_t>(objects.begin(), objects.end()), inView);
        };
        const std::vector<uint32_t> blended = visible(scene.objectsOfKind(DepthDrawKind::Blended));
        const std::vector<uint32_t> unblended = visible(scene.unblendedObjects());
        std::array<std::vector<uint32_t>, kPrepassDrawKinds> prepassLists;
        for (uint32_t kind = 0; kind < kPrepassDrawKinds; ++kind) {
            prepassLists[kind] = visible(scene.objectsOfKind(DepthDrawKind(kind)));
            draws.depthDraws += prepassLists[kind].size();
            draws.depthTriangles += trianglesOf(sceneData, prepassLists[kind]);
        }
        draws.objectsInView = inView.size();
        draws.forwardDraws = unblended.size();
        draws.transparentDraws = blended.size();
        draws.triangles = trianglesOf(sceneData, inView);
        draws.forwardTriangles = trianglesOf(sceneData, unblended);
        draws.transparentTriangles = trianglesOf(sceneData, blended);
        depth = passes.add<DepthPrepass>(context, settings.width, settings.height, std::move(prepassLists));
        passes.add<TransparentDepthPass>(context, depth->depth(), blended, plan.transparentSpans, settings.width,
                                         settings.height);
        culling = passes.add<LightCullingPass>(context, gridLayout, usesLightGrid(settings.method), settings.width,
                                            settings.height, cullLights, plan.zBins ? &*plan.zBins : nullptr);
        ForwardPass* marking = nullptr;
        if (usesShadowPages(settings)) {
            // The marking pass: the forward shader's light walk over the same surfaces, marking the
            // pages its lookups will read (opaque, then transparent fragments).
            ForwardVariant variant = forwardVariant(settings, gridLayout, false, false);
            variant.shadowPages = PUNCTUAL_SHADOW_PAGES_MARK;
            marking = passes.add<ForwardPass>(context, radiance, depth->depth(), variant, unblended, &shadowPageMarks);
            variant.transparent = true;
            passes.add<ForwardPass>(context, radiance, depth->depth(), variant, backToFront(sceneData, blended, eye),
                                    &shadowPageMarks);
        }
        shadows = passes.add<ShadowPass>(context, plan.shadows, sceneData, settings.shadows, shadowCache);
        if (marking) marking->readUndrawnImages({&shadows->maps().atlas(), &shadows->maps().pointCubes()}, ShadowPass::kReadLayout);
        forward = passes.add<ForwardPass>(context, radiance, depth->depth(),
                                          forwardVariant(settings, gridLayout, false, false), unblended);
        ForwardVariant transparent = forwardVariant(settings, gridLayout, false, false);
        transparent.transparent = true;
        passes.add<ForwardPass>(context, radiance, depth->depth(), transparent, backToFront(sceneData, blended, eye));
        tonemap = passes.add<TonemapPass>(context, radiance, settings.exposure);
        if (settings.collectLightStats) {
            lightStatsPass = std::make_unique<ForwardPass>(
                context, radiance, depth->depth(), forwardVariant(settings, gridLayout, true, false), unblended, &lightStats);
            ForwardVariant transparentStats = forwardVariant(settings, gridLayout, true, false);
            transparentStats.transparent = true;
            transparentStatsPass = std::make_unique<ForwardPass>(
                context, radiance, depth->depth(), transparentStats,
                backToFront(sceneData, blended, eye), &lightStats);
        }
        if (settings.collectShadowFactors) {
            shadowFactorsPass = std::make_unique<ForwardPass>(
                context, radiance, depth->depth(), forwardVariant(settings, gridLayout, false, true), unblended, &shadowDebug);
        }
    }

    // Set 0: the frame's own buffers, then what each pass owns; then every pipeline.
    void bindPasses(vk::Context& context) {
        BindingTable table;
        table.addBuffer(PUNCTUAL_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kAllStages, frameUniform);
        table.addBuffer(PUNCTUAL_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages, lights);
        table.addBuffer(PUNCTUAL_BINDING_OBJECTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kRasterStages, scene.objectBuffer());
        table.addBuffer(PUNCTUAL_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                        scene.materialBuffer());
        table.addBuffer(PUNCTUAL_BINDING_OBJECT_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                        objectLights);
        table.addBuffer(PUNCTUAL_BINDING_LIGHT_STATS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                        lightStats);
        table.addBuffer(PUNCTUAL_BINDING_SHADOW_DEBUG, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                        shadowDebug);
        table.addBuffer(PUNCTUAL_BINDING_SHADOW_PAGE_MARKS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                        shadowPageMarks);
        table.addBuffer(PUNCTUAL_BINDING_SHADOW_PREVIOUS_PAGE_MARKS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                        VK_SHADER_STAGE_FRAGMENT_BIT, previousPageMarks);
        for (const auto& pass : passes.passes()) pass->addBindings(table);
        bindings = std::make_unique<FrameBindings>(context, scene, table);
        boundImages = table.boundImages();
        for (const auto& pass : passes.passes()) pass->createPipelines(context, *bindings);
        for (ForwardPass* variant : {lightStatsPass.get(), transparentStatsPass.get(), shadowFactorsPass.get()}) {
            if (variant) variant->createPipelines(context, *bindings);
        }
    }
};

namespace {

// The frame's constants, all from the plan: packed once, never patched.
gpu::GpuFrame packFrame(const Scene& scene, const RenderSettings& settings, const FramePlan& plan,
                        const ShadowPageAllocation& pages) {
    const glm::mat4& view = plan.view;
    const glm::mat4& projection = plan.projection;
    const FrameLights& lights = plan.lights;
    const LightGridLayout& grid = plan.gridLayout;
    const ShadowPlan& shadowPlan = plan.shadows;
    gpu::GpuFrame frame{};
    frame.view = view;
    frame.projection = projection;
    frame.viewProjection = projection * view;
    frame.inverseViewProjection = glm::inverse(frame.viewProjection);
    frame.cameraPosition = glm::vec4(scene.camera.position(), 1.0f);
    frame.viewport = glm::vec4(float(settings.width), float(settings.height), 1.0f / float(settings.width),
                               1.0f / float(settings.height));
    frame.spotCount = lights.spotCount;
    frame.pointCount = lights.pointCount;
    frame.directionalCount = lights.directionalCount;
    frame.transparentSpans = plan.transparentSpans ? 1u : 0u;
    frame.exposure = glm::vec4(settings.exposure, 0.0f, 0.0f, 0.0f);
    frame.sun = lights.sun;
    frame.lightGrid = glm::uvec4(grid.tileSize, grid.tilesX, grid.tilesY, grid.slices);
    // See culling.h: view distance = a / (depth + b) with a = P[3][2], b = P[2][2]. For the
    // camera's reversed projection (Camera::projection, near n, far f): clip.z = b z + a with
    // b = n / (f - n), a = f n / (f - n), and clip.w = -z = D, so depth = a / D - b, which is 1 at
    // D = n and 0 at D = f, and D = a / (depth + b). View rays through NDC use 1/P00, 1/P11 and
    // the off-centre terms P20, P21.
    frame.depthToView = glm::vec4(projection[3][2], projection[2][2], 0.0f, 0.0f);
    frame.ndcToView = glm::vec4(1.0f / projection[0][0], 1.0f / projection[1][1], projection[2][0], projection[2][1]);
    const ShadowSettings& shadows = settings.shadows;
    frame.shadowBias = shadows.bias;
    frame.shadowAtlasSize = glm::vec2(float(shadowPlan.atlas.width), float(shadowPlan.atlas.height));
    frame.diskRadius = shadows.diskRadius;
    frame.shadowDepthQuantum = shadowDepthQuantum(shadows.format);
    frame.shadowCounts = glm::uvec4(shadowPlan.shadowedSpots, shadowPlan.shadowedPoints, 0u, 0u);
    const CascadePlan& cascades = shadowPlan.cascades;
    if (cascades.count > 0) {
        frame.sunShadow = glm::uvec4(cascades.firstView, cascades.count, 0u, 0u);
        frame.sunShadowFade = glm::vec4(1.0f / cascades.shadowDistance, 1.0f / shadows.cascades.distanceFade,
                                        gpu::cascadeFadeScale(shadows.cascades.cascadeFade), cascades.strength);
        for (uint32_t i = 0; i < PUNCTUAL_MAX_CASCADES; ++i) frame.cascadeSpheres[i] = cascades.selection[i];
    }
    // What sets the level a receiver reads: the plan's, so that the CPU's mirror reads the same.
    const VirtualPageReads& reads = shadowPlan.virtualReads;
    frame.shadowPageNeed = glm::vec4(reads.texelsPerPixel, reads.pixelSpan, 0.0f, 0.0f);
    frame.shadowPagePool = glm::uvec4(pages.squares, pages.besideAcross, pages.belowAcross);
    frame.shadowPageSlots = glm::uvec4(pages.litSlot(), 0u, 0u, 0u);
    return frame;
}

}  // namespace

Renderer::Renderer(vk::Context& context, const Scene& scene, const RenderSettings& settings, ShadowCache* shadowCache)
    : context_(context), scene_(scene), settings_(settings), shadowCache_(settings.shadows.enabled ? shadowCache : nullptr) {
    validateRenderSettings(settings);
    checkCameraPrecision(scene.camera, settings.height, scene.source);
    plan_ = planFrame(context, scene, settings);
    if (shadowCache_) shadowCache_->prepare(plan_.shadows, scene, plan_.lights);
    resources_ = std::make_unique<Resources>(context, scene, settings, plan_, shadowCache_, cameraDraws_);
    Resources& r = *resources_;
    const gpu::GpuFrame frame = packFrame(scene, settings, plan_, pageAllocation_);
    r.frameUniform.write(&frame, sizeof(frame));

    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    vk::check(vkCreateFence(context.device(), &fenceInfo, nullptr, &fence), "vkCreateFence");
    r.fence = vk::Handle<VkFence>(context.device(), fence, vkDestroyFence);

    recordFrames();
    if (usesShadowPages(settings)) allocateShadowPages();
    if (plan_.gridLayout.indexLists) sizeIndexLists();
}

void Renderer::allocateShadowPages() {
    // Every frame of this renderer is the same frame, so the marks of one marking frame are every
    // frame's: they are read back once and allocated on the CPU (as the index lists are sized).
    // The timed frames still run the marking pass, so its time is counted in the shadow stage.
    Resources& r = *resources_;
    ShadowPlan& shadows = plan_.shadows;
    const ShadowPageMarkLayout layout = ShadowPageMarkLayout::of(shadows);
    const uint64_t capacity = shadowPagePoolCapacity(shadows, shadows.budgetBytes, settings_.shadows.texelBytes());
    const std::vector<uint32_t> ranks = shadowViewRanks(shadows, scene_, plan_.lights, scene_.camera.position());
    std::vector<uint32_t> coarser(shadows.views.size(), 0);
    std::vector<uint32_t> marks;
    ShadowPageStats& stats = pageStats_;
    for (;;) {
        r.shadows->setUnallocatedPages(unallocatedPageViews(layout, coarser));
        submitAndWait(r.commandBuffer);
        marks = readWords(r.shadowPageMarks);
        const auto start = std::chrono::steady_clock::now();
        const ShadowPageCounts counts = countMarkedPages(layout, marks);
        if (stats.markingFrames++ == 0) stats.marked = counts;
        if (counts.total() <= capacity) break;
        coarser = coarsenViewsForBudget(shadows, ranks, counts, coarser, capacity,
                                        "--shadow-budget " + std::to_string(shadows.budgetBytes >> 20));
        stats.allocateMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    const auto start = std::chrono::steady_clock::now();
    for (size_t v = 0; v < coarser.size(); ++v) {
        if (coarser[v] > 0) stats.coarsenedPages += stats.marked.perView[v];
        stats.coarsenedViews += coarser[v] > 0;
        shadows.views[v].coarserLevels = coarser[v];
    }
    pageAllocation_ = punctual::allocateShadowPages(layout, marks, coarser);
    const std::vector<std::vector<uint32_t>> casters = shadowPageCasters(scene_, shadows, pageAllocation_);
    std::vector<bool> drawn;  // every page, unless the cache keeps some
    if (shadowCache_) {
        drawn = shadowCache_->placePages(shadows, pageAllocation_, casters, scene_, plan_.lights);
    } else {
        placeShadowPagePool(shadows, pageAllocation_, ShadowMaps::memoryLimits(context_, settings_.shadows).atlasSide);
    }
    ShadowPageDraws draws = punctual::shadowPageDraws(shadows, pageAllocation_, casters, drawn,
                                                      ShadowPageLayers::layersPerBatch(context_));
    stats.allocateMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats.marksBytes = uint64_t(layout.words) * 4;
    if (stats.coarsenedPages > 0 && settings_.warnReducedShadows) {
        log::warn("shadows: " + std::to_string(stats.coarsenedPages) + " virtual page(s) of " +
                  std::to_string(stats.coarsenedViews) + " view(s) read a coarser level than their receivers need, to fit --shadow-budget " +
                  std::to_string(shadows.budgetBytes >> 20) + " (the stats' shadows.virtual_pages counts them)");
    }
    r.shadows->usePages(context_, pageAllocation_, std::move(draws));
    const gpu::GpuFrame frame = packFrame(scene_, settings_, plan_, pageAllocation_);
    r.frameUniform.write(&frame, sizeof(frame));
    r.bindPasses(context_);  // set 0 points at the new atlas and page table
    recordFrames();
}

void Renderer::recordFrames() {
    Resources& r = *resources_;
    // The frame, then the debug frames: the passes before the opaque forward pass, then the debug
    // variant in its place (no tone mapping: the variants' outputs are buffers the caller reads
    // back). Each is checked to find every image in the layout each pass declares it expects.
    const std::vector<const Pass*> frameOrder = r.passes.frame();
    const ImageLayouts resting = restingLayouts(frameOrder, r.boundImages);
    r.commandBuffer = vk::CommandBuffer(context_.device(), context_.commandPool());
    recordFrame(r.commandBuffer, frameOrder, resting, /*timed=*/true);
    if (r.lightStatsPass) {
        r.lightStatsCommands = vk::CommandBuffer(context_.device(), context_.commandPool());
        // The transparent variant adds the transparent fragments' counts.
        const std::array<const Pass*, 2> variants = {r.lightStatsPass.get(), r.transparentStatsPass.get()};
        recordFrame(r.lightStatsCommands, r.passes.frameReplacing(*r.forward, variants), resting, /*timed=*/false);
    }
    if (r.shadowFactorsPass) {
        r.shadowFactorsCommands = vk::CommandBuffer(context_.device(), context_.commandPool());
        const std::array<const Pass*, 1> variants = {r.shadowFactorsPass.get()};
        recordFrame(r.shadowFactorsCommands, r.passes.frameReplacing(*r.forward, variants), resting, /*timed=*/false);
    }
}

void Renderer::sizeIndexLists() {
    // The counting frame: its index array holds one word, so every list overflows, but the kernels
    // count the words each takes. Every frame of this renderer culls the same lights against the
    // same depths, so the next ones take exactly as many: the array is made that long (the lists'
    // order in it may differ from frame to frame, as the atomics fall, but not their contents).
    Resources& r = *resources_;
    submitAndWait(r.commandBuffer);
    const uint32_t used = readWords(r.culling->lightIndices()).front();
    r.culling->sizeIndexLists(context_, used);
    r.bindPasses(context_);  // the frame's set 0 points at the new array
    recordFrames();
}

Renderer::~Renderer() {
    // The command buffers may still be in flight after an error; nothing is freed before the
    // device is idle.
    if (resources_) vkDeviceWaitIdle(context_.device());
}

std::vector<std::string> Renderer::passNames() const { return resources_->passes.names(); }

void Renderer::recordFrame(VkCommandBuffer cmd, const std::vector<const Pass*>& passes, const ImageLayouts& resting,
                           bool timed) {
    Resources& r = *resources_;
    checkImageLayouts(passes, r.boundImages, resting);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vk::check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    PassList::record(FrameContext{cmd, r.scene, *r.bindings}, passes, timed ? &r.timer : nullptr);
    if (timed) {
        // The tone-mapped pixels to the host (the tone-mapping pass made them visible to transfers).
        const VkBufferCopy copy{0, 0, r.readback.size()};
        vkCmdCopyBuffer(cmd, r.tonemap->output().handle(), r.readback.handle(), 1, &copy);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    }
    vk::check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
}

FrameResult Renderer::render(uint32_t frames, uint32_t warmup) {
    PUNCTUAL_CHECK(frames >= 1, "render() needs at least one timed frame");
    Resources& r = *resources_;
    FrameResult result;
    for (uint32_t i = 0; i < warmup; ++i) submitAndWait(r.commandBuffer);
    for (uint32_t i = 0; i < frames; ++i) {
        submitAndWait(r.commandBuffer);
        const std::map<std::string, double> ms = r.timer.resolveMilliseconds();
        auto get = [&](const std::string& name) {
            const auto it = ms.find(name);
            return it == ms.end() ? 0.0 : it->second;
        };
        PassTimings timings;
        for (const std::string& name : passNames()) timings.passes.emplace_back(name, get(name));
        timings.total = get("total");
        result.framesMs.push_back(std::move(timings));
    }
    result.medianMs = medianTimings(result.framesMs);

    r.readback.invalidate();
    result.image.width = settings_.width;
    result.image.height = settings_.height;
    const auto* bytes = static_cast<const uint8_t*>(r.readback.mapped());
    result.image.pixels.assign(bytes, bytes + r.readback.size());
    return result;
}

void Renderer::submitAndWait(VkCommandBuffer cmd) {
    vk::submitAndWait(context_.device(), context_.queue(), cmd, resources_->fence);
}

std::vector<uint8_t> Renderer::readBuffer(const vk::Buffer& buffer) {
    vk::Buffer staging(context_, buffer.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback, "readback");
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        const VkBufferCopy copy{0, 0, buffer.size()};
        vkCmdCopyBuffer(cmd, buffer.handle(), staging.handle(), 1, &copy);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    staging.invalidate();
    const auto* bytes = static_cast<const uint8_t*>(staging.mapped());
    return std::vector<uint8_t>(bytes, bytes + buffer.size());
}

std::vector<uint32_t> Renderer::readWords(const vk::Buffer& buffer) {
    const std::vector<uint8_t> bytes = readBuffer(buffer);
    std::vector<uint32_t> words(bytes.size() / sizeof(uint32_t));
    std::memcpy(words.data(), bytes.data(), words.size() * sizeof(uint32_t));
    return words;
}

std::vector<uint32_t> Renderer::readLightGrid() {
    if (!usesLightGrid(settings_.method)) return {};
    const std::vector<uint32_t> grid = readWords(resources_->culling->grid());
    if (!plan_.gridLayout.indexLists) return grid;
    const std::vector<uint32_t> indices = readWords(resources_->culling->lightIndices());
    return masksFromIndexLists(grid, std::span<const uint32_t>(indices).subspan(1), plan_.gridLayout.gridWords,
                               plan_.lights.spotCount + plan_.lights.pointCount);
}

uint32_t Renderer::readLightIndexWordsUsed() {
    if (!plan_.gridLayout.indexLists) return 0;
    return readWords(resources_->culling->lightIndices()).front();
}

uint64_t Renderer::lightListBytes() const {
    return usesLightGrid(settings_.method) ? resources_->culling->listBytes() : 0;
}

std::vector<uint32_t> Renderer::readCoarseGrid() {
    if (!usesLightGrid(settings_.method) || !plan_.gridLayout.coarseTiles) return {};
    return readWords(resources_->culling->coarseGrid());
}

gpu::GpuDepthRange Renderer::readDepthRange() {
    const std::vector<uint8_t> bytes = readBuffer(resources_->culling->depthRange());
    gpu::GpuDepthRange range;
    std::memcpy(&range, bytes.data(), sizeof(range));
    return range;
}

LightStatsImage Renderer::readLightStats() {
    PUNCTUAL_CHECK(settings_.collectLightStats, "light statistics were not requested (collectLightStats)");
    submitAndWait(resources_->lightStatsCommands);
    return decodeLightStats(readBuffer(resources_->lightStats), settings_.width, settings_.height,
                            listCellCount(scene_, settings_, plan_), plan_.gridLayout.gridWords);
}

ShadowFactorImage Renderer::readShadowFactors() {
    PUNCTUAL_CHECK(settings_.collectShadowFactors, "shadow factors were not requested (collectShadowFactors)");
    submitAndWait(resources_->shadowFactorsCommands);
    return decodeShadowFactors(readBuffer(resources_->shadowDebug), settings_.width, settings_.height,
                               plan_.shadows.shadowedSpots + plan_.shadows.shadowedPoints,
                               plan_.shadows.cascades.count > 0);
}

uint64_t Renderer::shadowMemoryBytes() const { return resources_->shadows->memoryBytes(); }

DeviceMemory Renderer::deviceMemory() const {
    const Resources& r = *resources_;
    DeviceMemory memory;
    memory.scene = r.scene.memoryBytes();
    memory.frame = r.radiance.allocatedBytes();
    for (const vk::Buffer* buffer :
         {&r.frameUniform, &r.lights, &r.objectLights, &r.lightStats, &r.shadowDebug, &r.readback}) {
        memory.frame += buffer->size();
    }
    memory.shadows = r.passes.memoryBytes(MemoryKind::Shadows);
    memory.lightGrid = r.passes.memoryBytes(MemoryKind::LightGrid);
    memory.frame += r.passes.memoryBytes(MemoryKind::Frame);
    return memory;
}

std::vector<uint32_t> Renderer::readShadowPageMarks() {
    PUNCTUAL_CHECK(usesShadowPages(settings_), "shadow page marks read without virtual pages");
    std::vector<uint32_t> marks = readWords(resources_->shadowPageMarks);
    marks.resize(ShadowPageMarkLayout::of(plan_.shadows).words);
    return marks;
}

Renderer::ShadowPageDrawCounts Renderer::shadowPageDraws() const {
    const ShadowPass& shadows = *resources_->shadows;
    return {shadows.pageDraws(), shadows.pageInstances(), shadows.pagesDrawn()};
}

const ShadowCacheFrame* Renderer::shadowCacheFrame() const { return shadowCache_ ? &shadowCache_->lastFrame() : nullptr; }

ShadowDraws Renderer::shadowDraws() const {
    ShadowDraws draws;
    if (!resources_->shadows) return draws;  // shadows off
    const ShadowPass& pass = *resources_->shadows;
    const ShadowPlan& plan = plan_.shadows;
    std::vector<uint64_t> perView(plan.views.size(), 0);
    std::vector<uint32_t> casters;
    // Virtual pages: the pass's instanced draws, a (view, caster) a batch (the cache's kept pages
    // left out).
    for (const ShadowPageDraws::Draw& draw : pass.pageDrawList()) {
        ++perView[draw.view];
        casters.push_back(draw.object);
    }
    draws.triangles += trianglesOf(scene_, casters);
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        const ShadowView& view = plan.views[v];
        if (!view.rendered() || (shadowCache_ && shadowCache_->kept(v))) continue;
        // A view larger than the drawing square draws each caster in the tiles it reaches; one
        // drawn over its kept static depth (mixed caching), only its dynamic casters.
        auto drawn = [&](uint32_t object) { return !shadowCache_ || shadowCache_->draws(v, object); };
        for (const DrawingTile& tile : pass.tilesOf(v)) {
            perView[v] += uint64_t(std::count_if(tile.casters.begin(), tile.casters.end(), drawn));
        }
        casters.clear();
        std::copy_if(view.casters.begin(), view.casters.end(), std::back_inserter(casters), drawn);
        if (!pass.tilesOf(v).empty()) draws.triangles += trianglesOf(scene_, casters);
    }
    for (const uint64_t viewDraws : perView) {
        draws.total += viewDraws;
        draws.maxPerView = std::max(draws.maxPerView, viewDraws);
    }
    return draws;
}

std::vector<float> Renderer::readDepth() {
    const vk::Image& depthImage = resources_->depth->depth();
    const VkDeviceSize bytes = VkDeviceSize(settings_.width) * settings_.height * sizeof(float);
    vk::Buffer staging(context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback, "depth readback");
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, depthImage, DepthPrepass::kFinalLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
        copy.imageExtent = {settings_.width, settings_.height, 1};
        vkCmdCopyImageToBuffer(cmd, depthImage.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &copy);
        vk::imageBarrier(cmd, depthImage, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, DepthPrepass::kFinalLayout,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT, 0);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    staging.invalidate();
    std::vector<float> depth(size_t(settings_.width) * settings_.height);
    std::memcpy(depth.data(), staging.mapped(), bytes);
    return depth;
}

}  // namespace punctual::render
