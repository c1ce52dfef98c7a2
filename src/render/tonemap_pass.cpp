#include "render/tonemap_pass.h"

#include <array>

#include "shaders/compute_tonemap_comp_spv.h"
#include "vk/descriptors.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace punctual::render {
namespace {
struct ToneMapConstants {
    uint32_t width;
    uint32_t height;
    float exposure;
};
constexpr uint32_t kGroupSize = 8;  // local_size of tonemap.comp
}  // namespace

TonemapPass::TonemapPass(const vk::Context& context, const vk::Image& radiance, float exposure)
    : radiance_(radiance),
      width_(radiance.desc().width), height_(radiance.desc().height), exposure_(exposure) {
    const VkDevice device = context.device();
    output_ = vk::Buffer(context, VkDeviceSize(width_) * height_ * 4,
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                         vk::MemoryUse::DeviceLocal, "tone-mapped pixels");

    sampler_ = vk::createSampler(device, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    const std::array<VkDescriptorSetLayoutBinding, 2> bindings = {{
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    }};
    setLayout_ = context.objects().setLayout(bindings);
    pipelineLayout_ =
        context.objects().pipelineLayout({setLayout_}, {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ToneMapConstants)});
    descriptors_ = vk::allocateDescriptorSet(device, setLayout_, bindings);

    const VkDescriptorImageInfo imageInfo{sampler_, radiance.view(), kRadianceLayout};
    const VkDescriptorBufferInfo bufferInfo{output_.handle(), 0, VK_WHOLE_SIZE};
    const std::array<VkWriteDescriptorSet, 2> writes = {
        vk::imageWrite(descriptors_.set, 0, &imageInfo),
        vk::bufferWrite(descriptors_.set, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &bufferInfo),
    };
    vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);

    pipeline_ = context.objects().computePipeline(pipelineLayout_, compute_tonemap_comp_spv);
}

void TonemapPass::record(const FrameContext& frame) const {
    const VkCommandBuffer cmd = frame.cmd;
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &descriptors_.set, 0, nullptr);
    const ToneMapConstants constants{width_, height_, exposure_};
    vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
    vkCmdDispatch(cmd, (width_ + kGroupSize - 1) / kGroupSize, (height_ + kGroupSize - 1) / kGroupSize, 1);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
}

}  // namespace punctual::render
