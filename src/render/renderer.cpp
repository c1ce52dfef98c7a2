#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "culling.h"
#include "gpu_types.h"
#include "render/depth_prepass.h"
#include "render/forward_pass.h"
#include "render/frame_bindings.h"
#include "render/scene_gpu.h"
#include "render/shadow_pass.h"
#include "render/tonemap_pass.h"
#include "vk/buffer.h"
#include "vk/check.h"
#include "vk/context.h"
#include "vk/descriptors.h"
#include "vk/gpu_timer.h"
#include "vk/image.h"

namespace punctual::render {

struct Renderer::Resources {
    SceneGpu scene;
    vk::Buffer frameUniform;
    vk::Buffer lights;
    vk::Image depth;
    vk::Image radiance;
    vk::Handle<VkSampler> depthSampler;
    LightGridBuffers grid;
    vk::Buffer objectLights;
    vk::Buffer lightStats;
    vk::Buffer shadowDebug;    vk::Buffer cullLights;
    vk::Buffer shadowViews;
    ShadowMaps shadowMaps;
    FrameBindings bindings;
    DepthPrepass depthPrepass;
    std::unique_ptr<LightCullingPass> cullingPass;  // tiled and clustered only
    std::unique_ptr<ShadowPass> shadowPass;         // always: it also puts unused placeholders in their layout
    ForwardPass forwardPass;
    // Debug variants of the forward pass, each with its own command buffer; never timed.
    struct DebugVariant : Renderer::DebugVariantBase {
        std::unique_ptr<ForwardPass> pass;
        const vk::Buffer* output = nullptr;  // cleared before the pass
        VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
    };
    DebugVariant lightStatsVariant;     // with collectLightStats
    DebugVariant shadowFactorsVariant;  // with collectShadowFactors
    TonemapPass tonemapPass;
    vk::Buffer readback;
    vk::GpuTimer timer;
    VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
    vk::Handle<VkFence> fence;

    static vk::Image makeImage(const vk::Context& context, VkFormat format, VkImageUsageFlags usage,
                               const RenderSettings& settings, const char* name) {
        vk::ImageDesc desc;
        desc.format = format;
        desc.width = settings.width;
        desc.height = settings.height;
        desc.usage = usage;
        desc.debugName = name;
        return vk::Image(context, desc);
    }

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

    static ForwardVariant forwardVariant(const RenderSettings& settings, const LightGridLayout& grid, bool stats,
                                         bool shadowFactors = false) {
        ForwardVariant variant;
        variant.lightList = uint32_t(settings.method);
        variant.tileSize = grid.tileSize;
        variant.slices = grid.slices;
        variant.writeLightStats = stats;
        variant.shadows = settings.shadows.enabled;
        variant.shadowFilter = uint32_t(settings.shadows.filter);
        variant.shadowSamples = settings.shadows.diskSamples;
        variant.pointShadowLayout = uint32_t(settings.shadows.pointLayout);
        variant.writeShadowFactors = shadowFactors;
        return variant;
    }

    Resources(vk::Context& context, const Scene& sceneData, const RenderSettings& settings,
              const FrameLights& frameLights, const PerObjectLightLists& perObject, const LightGridLayout& gridLayout,
              const ShadowPlan& shadowPlan)
        : scene(context, sceneData, perObject.counts),
          frameUniform(context, sizeof(gpu::GpuFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload,
                       "frame"),
          // Sized to the lights this frame really uses; one slot when there are none.
          lights(context, std::max<size_t>(frameLights.packed.size(), 1) * sizeof(gpu::GpuPunctualLight),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "lights"),
          depth(makeImage(context, DepthPrepass::kDepthFormat,
                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                          settings, "depth")),
          radiance(makeImage(context, ForwardPass::kRadianceFormat,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, settings, "radiance")),
          depthSampler(vk::createSampler(context.device(), VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE)),
          grid(context, gridLayout, usesLightGrid(settings.method)),
          objectLights(storageWords(context, perObject.lights, "object lights")),
          lightStats(context,
                     settings.collectLightStats ? VkDeviceSize(settings.width) * settings.height * 16 : 16,
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                         VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     vk::MemoryUse::DeviceLocal, "light stats"),
          shadowDebug(context,
                      settings.collectShadowFactors
                          ? VkDeviceSize(settings.width) * settings.height *
                                (PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS + PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS) * 4
                          : 16,
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                          VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      vk::MemoryUse::DeviceLocal, "shadow debug"),
          cullLights(context, std::max<size_t>(frameLights.packed.size(), 1) * sizeof(gpu::CullLight),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "cull lights"),
          shadowViews(context, std::max<size_t>(shadowPlan.views.size(), 1) * sizeof(gpu::GpuShadowView),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "shadow views"),
          shadowMaps(context, shadowPlan, settings.shadows),
          bindings(context, scene,
                   FrameBindingResources{frameUniform, lights, depth.view(), depthSampler, grid.grid, grid.depthRange,
                                         objectLights, lightStats, cullLights, shadowViews, shadowMaps.spots().view(),
                                         shadowMaps.pointCubes().view(), shadowMaps.pointSlices().view(),
                                         shadowMaps.sampler(), shadowDebug}),
          depthPrepass(context, bindings, depth),
          forwardPass(context, bindings, radiance, depth, forwardVariant(settings, gridLayout, false)),
          tonemapPass(context, radiance, settings.exposure),
          readback(context, VkDeviceSize(settings.width) * settings.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                   vk::MemoryUse::Readback, "readback"),
          timer(context, 16) {
        if (usesLightGrid(settings.method)) {
            cullingPass = std::make_unique<LightCullingPass>(context, bindings, gridLayout, settings.width, settings.height);
        }
        if (settings.collectLightStats) {
            lightStatsVariant.pass = std::make_unique<ForwardPass>(context, bindings, radiance, depth,
                                                                   forwardVariant(settings, gridLayout, true));
            lightStatsVariant.output = &lightStats;
        }
        if (settings.collectShadowFactors) {
            shadowFactorsVariant.pass = std::make_unique<ForwardPass>(context, bindings, radiance, depth,
                                                                      forwardVariant(settings, gridLayout, false, true));
            shadowFactorsVariant.output = &shadowDebug;
        }
        shadowPass = std::make_unique<ShadowPass>(context, bindings, shadowMaps, shadowPlan, settings.shadows);
    }
};

namespace {

void validateSettings(const RenderSettings& settings) {
    constexpr uint32_t kMaxDimension = 8192;
    if (settings.width == 0 || settings.height == 0 || settings.width > kMaxDimension ||
        settings.height > kMaxDimension) {
        throw Error("--size", "width and height must be between 1 and " + std::to_string(kMaxDimension));
    }
    if (!(settings.exposure > 0.0f) || !std::isfinite(settings.exposure)) {
        throw Error("--exposure", "must be a finite number > 0");
    }
    if (settings.tileSize < 4 || settings.tileSize > 128) throw Error("--tile-size", "must be from 4 to 128 pixels");
    if (settings.clusterSlices < 1 || settings.clusterSlices > PUNCTUAL_MAX_CLUSTER_SLICES) {
        throw Error("--slices", "must be from 1 to " + std::to_string(PUNCTUAL_MAX_CLUSTER_SLICES));
    }
}

gpu::GpuFrame packFrame(const Scene& scene, const RenderSettings& settings, const glm::mat4& view,
                        const glm::mat4& projection, const FrameLights& lights, const LightGridLayout& grid,
                        const ShadowPlan& shadowPlan) {
    gpu::GpuFrame frame{};
    frame.view = view;
    frame.projection = projection;
    frame.viewProjection = projection * view;
    frame.inverseViewProjection = glm::inverse(frame.viewProjection);
    frame.cameraPosition = glm::vec4(scene.camera.position(), 1.0f);
    frame.viewport = glm::vec4(float(settings.width), float(settings.height), 1.0f / float(settings.width),
                               1.0f / float(settings.height));
    frame.lightCounts = glm::uvec4(lights.spotCount, lights.pointCount, lights.directionalCount, 0u);
    frame.exposure = glm::vec4(settings.exposure, 0.0f, 0.0f, 0.0f);
    frame.sun = lights.sun;
    frame.lightGrid = glm::uvec4(grid.tileSize, grid.tilesX, grid.tilesY, grid.slices);
    // See culling.h: view distance = a / (depth + b) with a = P[3][2], b = P[2][2]; view rays
    // through NDC use 1/P00, 1/P11 and the off-centre terms P20, P21.
    frame.depthToView = glm::vec4(projection[3][2], projection[2][2], 0.0f, 0.0f);
    frame.ndcToView = glm::vec4(1.0f / projection[0][0], 1.0f / projection[1][1], projection[2][0], projection[2][1]);
    const ShadowSettings& shadows = settings.shadows;
    frame.shadowBias = shadows.bias;
    frame.shadowMap = glm::vec4(float(shadows.resolution), 1.0f / float(shadows.resolution), shadows.diskRadius,
                                shadows.penumbraTexels());
    frame.shadowCounts = glm::uvec4(shadowPlan.shadowedSpots, shadowPlan.shadowedPoints, 0u, 0u);
    return frame;
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const size_t mid = values.size() / 2;
    return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

}  // namespace

Renderer::Renderer(vk::Context& context, const Scene& scene, const RenderSettings& settings)
    : context_(context), scene_(scene), settings_(settings) {
    validateSettings(settings);
    validateShadowSettings(settings.shadows);
    view_ = scene.camera.view;
    projection_ = scene.camera.projection(float(settings.width) / float(settings.height));
    lights_ = setupFrameLights(scene, view_, projection_);
    shadowPlan_ = planShadows(scene, lights_, scene.camera.position(), settings.shadows);
    if (settings.method == LightListMethod::PerObject) perObjectLists_ = buildPerObjectLightLists(scene, lights_);
    const uint32_t slices = settings.method == LightListMethod::Clustered ? settings.clusterSlices : 1u;
    gridLayout_ = LightGridLayout::forFrame(settings.width, settings.height, settings.tileSize, slices);
    resources_ = std::make_unique<Resources>(context, scene, settings, lights_, perObjectLists_, gridLayout_, shadowPlan_);
    if (!shadowPlan_.views.empty()) {
        std::vector<gpu::GpuShadowView> views;
        for (const ShadowView& view : shadowPlan_.views) views.push_back(view.gpu);
        resources_->shadowViews.write(views.data(), views.size() * sizeof(gpu::GpuShadowView));
    }

    const gpu::GpuFrame frame = packFrame(scene, settings, view_, projection_, lights_, gridLayout_, shadowPlan_);
    resources_->frameUniform.write(&frame, sizeof(frame));
    if (!lights_.packed.empty()) {
        resources_->lights.write(lights_.packed.data(), lights_.packed.size() * sizeof(gpu::GpuPunctualLight));
        // The culling shapes in view space, once per frame (the same function the culling tests
        // of the CPU reference use).
        std::vector<gpu::CullLight> cullLights;
        for (const gpu::GpuPunctualLight& light : lights_.packed) cullLights.push_back(gpu::makeCullLight(light, view_));
        resources_->cullLights.write(cullLights.data(), cullLights.size() * sizeof(gpu::CullLight));
    }

    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = context.commandPool();
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocInfo.commandBufferCount = 1;
    vk::check(vkAllocateCommandBuffers(context.device(), &allocInfo, &resources_->commandBuffer),
              "vkAllocateCommandBuffers");
    for (Resources::DebugVariant* variant : {&resources_->lightStatsVariant, &resources_->shadowFactorsVariant}) {
        if (!variant->pass) continue;
        vk::check(vkAllocateCommandBuffers(context.device(), &allocInfo, &variant->commandBuffer),
                  "vkAllocateCommandBuffers");
    }
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    vk::check(vkCreateFence(context.device(), &fenceInfo, nullptr, &fence), "vkCreateFence");
    resources_->fence = vk::Handle<VkFence>(context.device(), fence, vkDestroyFence);
    recordFrame(resources_->commandBuffer, nullptr);
    for (Resources::DebugVariant* variant : {&resources_->lightStatsVariant, &resources_->shadowFactorsVariant}) {
        if (variant->pass) recordFrame(variant->commandBuffer, variant);
    }
}

Renderer::~Renderer() {
    if (resources_) {
        vkDeviceWaitIdle(context_.device());
        vkFreeCommandBuffers(context_.device(), context_.commandPool(), 1, &resources_->commandBuffer);
        for (Resources::DebugVariant* variant : {&resources_->lightStatsVariant, &resources_->shadowFactorsVariant}) {
            if (variant->commandBuffer) vkFreeCommandBuffers(context_.device(), context_.commandPool(), 1, &variant->commandBuffer);
        }
    }
}

// One frame: depth prepass, light culling (tiled, clustered), forward, tone mapping, readback.
// The statistics variant swaps in the forward shader that also writes per-pixel light counts
// and skips tone mapping; it is never timed.
void Renderer::recordFrame(VkCommandBuffer cmd, const DebugVariantBase* debugVariant) {
    const auto* debug = static_cast<const Resources::DebugVariant*>(debugVariant);
    const bool withStats = debug != nullptr;
    Resources& r = *resources_;
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vk::check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    if (!withStats) r.timer.reset(cmd);
    auto timed = [&](const char* name, auto&& work) {
        if (withStats) return work();
        const uint32_t scope = r.timer.begin(cmd, name);
        work();
        r.timer.end(cmd, scope);
    };
    const uint32_t total = withStats ? 0 : r.timer.begin(cmd, "total");

    timed("depth", [&] { r.depthPrepass.record(cmd, r.scene, r.bindings); });
    // Depth writes of the prepass must land before the culling kernel samples them and the
    // forward pass's EQUAL test reads them.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_SHADER_READ_BIT);
    if (r.cullingPass) timed("culling", [&] { r.cullingPass->record(cmd, r.bindings, r.grid); });
    // With no shadowed light the stage only moves the placeholder maps into their layout: not
    // a pass worth timing ("shadows" stays 0, as for a pass not run).
    if (shadowPlan_.views.empty()) {
        r.shadowPass->record(cmd, r.scene, r.bindings);
    } else {
        timed("shadows", [&] { r.shadowPass->record(cmd, r.scene, r.bindings); });
    }

    if (debug) {
        vkCmdFillBuffer(cmd, debug->output->handle(), 0, VK_WHOLE_SIZE, 0u);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
        debug->pass->record(cmd, r.scene, r.bindings);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        vk::check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
        return;
    }

    timed("forward", [&] { r.forwardPass.record(cmd, r.scene, r.bindings); });
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    timed("tonemap", [&] { r.tonemapPass.record(cmd); });
    r.timer.end(cmd, total);

    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferCopy copy{0, 0, r.readback.size()};
    vkCmdCopyBuffer(cmd, r.tonemapPass.output().handle(), r.readback.handle(), 1, &copy);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
    vk::check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
}

FrameResult Renderer::render(uint32_t frames, uint32_t warmup) {
    if (frames == 0) throw Error("--frames", "must be at least 1");
    Resources& r = *resources_;
    FrameResult result;
    for (uint32_t i = 0; i < warmup; ++i) submitAndWait(r.commandBuffer);
    for (uint32_t i = 0; i < frames; ++i) {
        submitAndWait(r.commandBuffer);
        const auto ms = r.timer.resolveMilliseconds();
        auto get = [&](const char* name) {
            const auto it = ms.find(name);
            return it == ms.end() ? 0.0 : it->second;
        };
        result.framesMs.push_back({get("depth"), get("culling"), get("shadows"), get("forward"), get("tonemap"),
                                   get("total")});
    }
    auto medianOf = [&](double PassTimings::*field) {
        std::vector<double> values;
        for (const PassTimings& t : result.framesMs) values.push_back(t.*field);
        return median(values);
    };
    result.medianMs = {medianOf(&PassTimings::depth),   medianOf(&PassTimings::culling),
                       medianOf(&PassTimings::shadows), medianOf(&PassTimings::forward),
                       medianOf(&PassTimings::tonemap), medianOf(&PassTimings::total)};

    r.readback.invalidate();
    result.image.width = settings_.width;
    result.image.height = settings_.height;
    const auto* bytes = static_cast<const uint8_t*>(r.readback.mapped());
    result.image.pixels.assign(bytes, bytes + r.readback.size());
    return result;
}

void Renderer::submitAndWait(VkCommandBuffer cmd) {
    Resources& r = *resources_;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VkFence fence = r.fence;
    vk::check(vkResetFences(context_.device(), 1, &fence), "vkResetFences");
    vk::check(vkQueueSubmit(context_.queue(), 1, &submit, fence), "vkQueueSubmit");
    // A generous timeout turns a hung GPU into an error instead of a hung process.
    constexpr uint64_t kTimeoutNs = 600ull * 1000 * 1000 * 1000;
    vk::check(vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, kTimeoutNs), "vkWaitForFences");
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

std::vector<uint32_t> Renderer::readLightGrid() {
    if (!usesLightGrid(settings_.method)) return {};
    const std::vector<uint8_t> bytes = readBuffer(resources_->grid.grid);
    std::vector<uint32_t> words(bytes.size() / sizeof(uint32_t));
    std::memcpy(words.data(), bytes.data(), words.size() * sizeof(uint32_t));
    return words;
}

gpu::GpuDepthRange Renderer::readDepthRange() {
    const std::vector<uint8_t> bytes = readBuffer(resources_->grid.depthRange);
    gpu::GpuDepthRange range;
    std::memcpy(&range, bytes.data(), sizeof(range));
    return range;
}

LightStatsImage Renderer::readLightStats() {
    if (!settings_.collectLightStats) throw Error("renderer", "light statistics were not requested");
    submitAndWait(resources_->lightStatsVariant.commandBuffer);
    const std::vector<uint8_t> bytes = readBuffer(resources_->lightStats);
    const size_t pixels = size_t(settings_.width) * settings_.height;
    std::vector<uint32_t> words(pixels * 4);
    std::memcpy(words.data(), bytes.data(), words.size() * sizeof(uint32_t));
    LightStatsImage stats;
    stats.width = settings_.width;
    stats.height = settings_.height;
    stats.tested.resize(pixels);
    stats.affecting.resize(pixels);
    stats.covered.resize(pixels);
    stats.methodLuminance.resize(pixels);
    stats.bruteLuminance.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        const uint32_t* w = &words[i * 4];
        stats.covered[i] = (w[1] & 0x80000000u) ? uint8_t{1} : uint8_t{0};  // the shader marks every pixel it shades
        stats.tested[i] = w[0];
        stats.affecting[i] = w[1] & 0x7FFFFFFFu;
        std::memcpy(&stats.methodLuminance[i], &w[2], sizeof(float));
        std::memcpy(&stats.bruteLuminance[i], &w[3], sizeof(float));
    }
    return stats;
}

ShadowFactorImage Renderer::readShadowFactors() {
    if (!settings_.collectShadowFactors) throw Error("renderer", "shadow factors were not requested");
    submitAndWait(resources_->shadowFactorsVariant.commandBuffer);
    const std::vector<uint8_t> bytes = readBuffer(resources_->shadowDebug);
    const size_t pixels = size_t(settings_.width) * settings_.height;
    ShadowFactorImage image;
    image.width = settings_.width;
    image.height = settings_.height;
    image.slots = shadowPlan_.shadowedSpots + shadowPlan_.shadowedPoints;
    image.positions.resize(pixels);
    image.normals.resize(pixels);
    image.covered.resize(pixels);
    image.factors.resize(pixels * image.slots);
    const auto* words = reinterpret_cast<const uint32_t*>(bytes.data());
    for (size_t i = 0; i < pixels; ++i) {
        const uint32_t* surface = words + i * PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS;
        std::memcpy(&image.positions[i], surface, sizeof(glm::vec3));
        std::memcpy(&image.normals[i], surface + 4, sizeof(glm::vec3));
        image.covered[i] = surface[3] != 0 ? uint8_t{1} : uint8_t{0};
        const auto* factors = reinterpret_cast<const uint8_t*>(words + pixels * PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS +
                                                               i * PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS);
        // Uncovered pixels were cleared to 0: report them as not reached.
        for (uint32_t slot = 0; slot < image.slots; ++slot) {
            image.factors[i * image.slots + slot] = image.covered[i] ? factors[slot] : uint8_t{255};
        }
    }
    return image;
}

uint64_t Renderer::shadowMemoryBytes() const { return resources_->shadowMaps.allocatedBytes(); }

std::vector<float> Renderer::readDepth() {
    Resources& r = *resources_;
    const VkDeviceSize bytes = VkDeviceSize(settings_.width) * settings_.height * sizeof(float);
    vk::Buffer staging(context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback, "depth readback");
    context_.submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, r.depth, DepthPrepass::kFinalLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
        copy.imageExtent = {settings_.width, settings_.height, 1};
        vkCmdCopyImageToBuffer(cmd, r.depth.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &copy);
        vk::imageBarrier(cmd, r.depth, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, DepthPrepass::kFinalLayout,
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
