#include "render/frame_bindings.h"

#include <set>

#include "core/check.h"
#include "render/scene_gpu.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/image.h"

namespace punctual::render {

void BindingTable::addBuffer(uint32_t binding, VkDescriptorType type, VkShaderStageFlags stages,
                             const vk::Buffer& buffer) {
    rows_.push_back({{binding, type, 1, stages, nullptr}, {buffer.handle(), 0, VK_WHOLE_SIZE}, {}});
}

void BindingTable::addImage(uint32_t binding, VkShaderStageFlags stages, VkSampler sampler, const vk::Image& image,
                            VkImageLayout layout) {
    rows_.push_back({{binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr},
                     {},
                     {sampler, image.view(), layout},
                     &image});
}

std::vector<BoundImage> BindingTable::boundImages() const {
    std::vector<BoundImage> images;
    for (const Row& row : rows_) {
        if (row.source) images.push_back({{row.source, row.image.imageLayout, row.image.imageLayout}, row.layout.stageFlags});
    }
    return images;
}

FrameBindings::FrameBindings(const vk::Context& context, const SceneGpu& scene, const BindingTable& table) {
    const VkDevice device = context.device();
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    std::set<uint32_t> seen;
    for (const BindingTable::Row& row : table.rows_) {
        PUNCTUAL_CHECK(seen.insert(row.layout.binding).second, "set 0 binding declared twice");
        bindings.push_back(row.layout);
    }
    setLayout_ = context.objects().setLayout(bindings);
    materialSetLayout_ = scene.materialSetLayout();
    pipelineLayout_ = context.objects().pipelineLayout({setLayout_, scene.materialSetLayout()},
                                               {kRasterStages, 0, sizeof(uint32_t)});
    descriptors_ = vk::allocateDescriptorSet(device, setLayout_, bindings);

    std::vector<VkWriteDescriptorSet> writes;
    for (const BindingTable::Row& row : table.rows_) {
        writes.push_back(row.layout.descriptorType == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                             ? vk::imageWrite(descriptors_.set, row.layout.binding, &row.image)
                             : vk::bufferWrite(descriptors_.set, row.layout.binding, row.layout.descriptorType,
                                               &row.buffer));
    }
    vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void FrameBindings::bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint) const {
    bind(cmd, bindPoint, pipelineLayout_);
}

void FrameBindings::bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout) const {
    vkCmdBindDescriptorSets(cmd, bindPoint, layout, 0, 1, &descriptors_.set, 0, nullptr);
}

}  // namespace punctual::render
