#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "gpu_types.h"
#include "render/depth_prepass.h"
#include "render/forward_pass.h"
#include "render/frame_bindings.h"
#include "render/scene_gpu.h"
#include "render/tonemap_pass.h"
#include "vk/buffer.h"
#include "vk/check.h"
#include "vk/context.h"
#include "vk/gpu_timer.h"
#include "vk/image.h"

namespace punctual::render {

struct Renderer::Resources {
    SceneGpu scene;
    vk::Buffer frameUniform;
    vk::Buffer lights;
    vk::Image depth;
    vk::Image radiance;
    FrameBindings bindings;
    DepthPrepass depthPrepass;
    ForwardPass forwardPass;
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

    Resources(vk::Context& context, const Scene& sceneData, const RenderSettings& settings, const FrameLights& frameLights)
        : scene(context, sceneData),
          frameUniform(context, sizeof(gpu::GpuFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload,
                       "frame"),
          // Sized to the lights this frame really uses; one slot when there are none, because a
          // Vulkan buffer cannot be empty.
          lights(context, std::max<size_t>(frameLights.packed.size(), 1) * sizeof(gpu::GpuPunctualLight),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "lights"),
          depth(makeImage(context, DepthPrepass::kDepthFormat,
                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                          settings, "depth")),
          radiance(makeImage(context, ForwardPass::kRadianceFormat,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, settings, "radiance")),
          bindings(context, scene, frameUniform, lights),
          depthPrepass(context, bindings, depth),
          forwardPass(context, bindings, radiance, depth),
          tonemapPass(context, radiance, settings.exposure),
          readback(context, VkDeviceSize(settings.width) * settings.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                   vk::MemoryUse::Readback, "readback"),
          timer(context, 16) {}
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
}

gpu::GpuFrame packFrame(const Scene& scene, const RenderSettings& settings, const glm::mat4& view,
                        const glm::mat4& projection, const FrameLights& lights) {
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
    view_ = scene.camera.view;
    projection_ = scene.camera.projection(float(settings.width) / float(settings.height));
    lights_ = setupFrameLights(scene, view_, projection_);
    resources_ = std::make_unique<Resources>(context, scene, settings, lights_);

    const gpu::GpuFrame frame = packFrame(scene, settings, view_, projection_, lights_);
    resources_->frameUniform.write(&frame, sizeof(frame));
    if (!lights_.packed.empty()) {
        resources_->lights.write(lights_.packed.data(), lights_.packed.size() * sizeof(gpu::GpuPunctualLight));
    }

    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = context.commandPool();
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocInfo.commandBufferCount = 1;
    vk::check(vkAllocateCommandBuffers(context.device(), &allocInfo, &resources_->commandBuffer),
              "vkAllocateCommandBuffers");
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    vk::check(vkCreateFence(context.device(), &fenceInfo, nullptr, &fence), "vkCreateFence");
    resources_->fence = vk::Handle<VkFence>(context.device(), fence, vkDestroyFence);
    recordFrame();
}

Renderer::~Renderer() {
    if (resources_) {
        vkDeviceWaitIdle(context_.device());
        vkFreeCommandBuffers(context_.device(), context_.commandPool(), 1, &resources_->commandBuffer);
    }
}

void Renderer::recordFrame() {
    Resources& r = *resources_;
    VkCommandBuffer cmd = r.commandBuffer;
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vk::check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    r.timer.reset(cmd);
    const uint32_t total = r.timer.begin(cmd, "total");

    uint32_t scope = r.timer.begin(cmd, "depth");
    r.depthPrepass.record(cmd, r.scene, r.bindings);
    r.timer.end(cmd, scope);
    // Depth writes of the prepass must land before the forward pass's EQUAL test reads them.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT);

    scope = r.timer.begin(cmd, "forward");
    r.forwardPass.record(cmd, r.scene, r.bindings);
    r.timer.end(cmd, scope);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);

    scope = r.timer.begin(cmd, "tonemap");
    r.tonemapPass.record(cmd);
    r.timer.end(cmd, scope);
    r.timer.end(cmd, total);

    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferCopy copy{0, 0, r.readback.size()};
    vkCmdCopyBuffer(cmd, r.tonemapPass.output().handle(), r.readback.handle(), 1, &copy);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
    vk::check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
}

FrameResult Renderer::render(uint32_t frames) {
    if (frames == 0) throw Error("--frames", "must be at least 1");
    Resources& r = *resources_;
    FrameResult result;
    for (uint32_t i = 0; i < frames; ++i) {
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &r.commandBuffer;
        VkFence fence = r.fence;
        vk::check(vkResetFences(context_.device(), 1, &fence), "vkResetFences");
        vk::check(vkQueueSubmit(context_.queue(), 1, &submit, fence), "vkQueueSubmit");
        constexpr uint64_t kTimeoutNs = 600ull * 1000 * 1000 * 1000;
        vk::check(vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, kTimeoutNs), "vkWaitForFences");
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
