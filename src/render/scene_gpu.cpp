#include "render/scene_gpu.h"

#include <algorithm>
#include <cstddef>

#include "core/error.h"
#include "core/log.h"
#include "gpu_types.h"
#include "scene/texture_limit.h"
#include "vk/check.h"
#include "vk/descriptors.h"
#include "vk/context.h"

namespace punctual::render {
namespace {

vk::Image uploadTexture(vk::Context& context, uint32_t width, uint32_t height, const uint8_t* rgba,
                        const std::string& name) {
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_SRGB;  // glTF base-colour textures are sRGB-encoded
    desc.width = width;
    desc.height = height;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.debugName = name;
    vk::Image image(context, desc);
    const VkDeviceSize bytes = VkDeviceSize(width) * height * 4;
    vk::Buffer staging(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::Upload, "texture staging");
    staging.write(rgba, bytes);
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_ACCESS_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width, height, 1};
        vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        vk::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    });
    return image;
}

template <typename T>
vk::Buffer deviceBuffer(vk::Context& context, const std::vector<T>& data, VkBufferUsageFlags usage,
                        const std::string& name) {
    const VkDeviceSize bytes = data.size() * sizeof(T);
    vk::Buffer buffer(context, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::DeviceLocal, name);
    vk::uploadToBuffer(context, buffer, data.data(), bytes);
    return buffer;
}

}  // namespace

SceneGpu::SceneGpu(vk::Context& context, const Scene& scene, const std::vector<uint32_t>& objectLightCounts) {
    if (scene.vertices.empty() || scene.indices.empty() || scene.objects.empty()) {
        throw Error(scene.source, "no triangle meshes to draw");
    }
    vertices_ = deviceBuffer(context, scene.vertices, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertices");
    indices_ = deviceBuffer(context, scene.indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "indices");

    std::vector<gpu::GpuObject> objects;
    objects.reserve(scene.objects.size());
    for (size_t index = 0; index < scene.objects.size(); ++index) {
        const Object& object = scene.objects[index];
        const Mesh& mesh = scene.meshes.at(object.mesh);
        gpu::GpuObject packed{};
        packed.model = object.model;
        packed.normalMatrix = glm::transpose(glm::inverse(object.model));
        const bool mirrored = glm::determinant(glm::mat3(object.model)) < 0.0f;
        const uint32_t lightCount = index < objectLightCounts.size() ? objectLightCounts[index] : 0u;
        packed.material = glm::uvec4(mesh.material, mirrored ? 1u : 0u, lightCount, 0u);
        objects.push_back(packed);
        draws_.push_back({mesh.firstIndex, mesh.indexCount, int32_t(mesh.vertexOffset)});
    }
    objects_ = deviceBuffer(context, objects, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "objects");

    std::vector<gpu::GpuMaterial> materials;
    for (const Material& material : scene.materials) {
        gpu::GpuMaterial packed{};
        packed.baseColorFactor = material.baseColorFactor;
        packed.metallicRoughness = glm::vec2(material.metallic, material.roughness);
        packed.baseColorTexture = material.baseColorTexture;
        materials.push_back(packed);
    }
    if (materials.empty()) throw Error(scene.source, "scene has no materials");
    materials_ = deviceBuffer(context, materials, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "materials");

    // Textures are already fitted to the frame when loaded (scene/texture_limit.h); the device
    // may allow less (maxImageDimension2D is only guaranteed to be 4096). Beyond it image
    // creation is invalid, so fit those here, once per texture.
    const uint32_t deviceMaxSide = context.properties().limits.maxImageDimension2D;
    for (const Texture& texture : scene.textures) {
        if (std::max(texture.width, texture.height) <= deviceMaxSide) {
            textures_.push_back(uploadTexture(context, texture.width, texture.height, texture.rgba.data(), texture.name));
            continue;
        }
        const Texture fitted = fittedTexture(texture, deviceMaxSide);
        log::warn(scene.source + ": " +
                  downscaleWarning("texture '" + texture.name + "'", {texture.width, texture.height},
                                   {fitted.width, fitted.height},
                                   "the device's limit, maxImageDimension2D = " + std::to_string(deviceMaxSide)));
        textures_.push_back(uploadTexture(context, fitted.width, fitted.height, fitted.rgba.data(), fitted.name));
    }
    const uint8_t white[4] = {255, 255, 255, 255};
    textures_.push_back(uploadTexture(context, 1, 1, white, "untextured"));

    // glTF samplers are not read: every texture is filtered bilinearly and repeats (README).
    sampler_ = vk::createSampler(context.device(), VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT);

    // One descriptor set per texture; each object binds the set of its material's texture.
    const VkDevice device = context.device();
    const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                               VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    materialSetLayout_ = vk::createDescriptorSetLayout(device, {&binding, 1});
    const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, uint32_t(textures_.size())};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = uint32_t(textures_.size());
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &poolSize;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    vk::check(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
    materialPool_ = vk::Handle<VkDescriptorPool>(device, pool, vkDestroyDescriptorPool);
    const std::vector<VkDescriptorSetLayout> layouts(textures_.size(), materialSetLayout_.get());
    VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocInfo.descriptorPool = pool;
    allocInfo.descriptorSetCount = uint32_t(layouts.size());
    allocInfo.pSetLayouts = layouts.data();
    textureSets_.resize(textures_.size());
    vk::check(vkAllocateDescriptorSets(device, &allocInfo, textureSets_.data()), "vkAllocateDescriptorSets");
    for (size_t i = 0; i < textures_.size(); ++i) {
        const VkDescriptorImageInfo imageInfo{sampler_, textures_[i].view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        const VkWriteDescriptorSet write = vk::imageWrite(textureSets_[i], 0, &imageInfo);
        vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
    }
    const uint32_t untextured = uint32_t(textures_.size() - 1);
    for (const Object& object : scene.objects) {
        const int texture = scene.materials.at(scene.meshes.at(object.mesh).material).baseColorTexture;
        drawTextureSet_.push_back(texture >= 0 ? uint32_t(texture) : untextured);
    }
}

void SceneGpu::drawObjects(VkCommandBuffer cmd, VkPipelineLayout layout, bool withTextures) const {
    const VkBuffer vertexBuffer = vertices_.handle();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
    vkCmdBindIndexBuffer(cmd, indices_.handle(), 0, VK_INDEX_TYPE_UINT32);
    uint32_t boundSet = UINT32_MAX;
    for (uint32_t i = 0; i < draws_.size(); ++i) {
        if (withTextures && drawTextureSet_[i] != boundSet) {
            boundSet = drawTextureSet_[i];
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &textureSets_[boundSet], 0,
                                    nullptr);
        }
        vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(uint32_t), &i);
        vkCmdDrawIndexed(cmd, draws_[i].indexCount, 1, draws_[i].firstIndex, draws_[i].vertexOffset, 0);
    }
}

void SceneGpu::drawObjects(VkCommandBuffer cmd, VkPipelineLayout layout, std::span<const uint32_t> objects,
                           uint32_t pushOffset, VkShaderStageFlags stages) const {
    const VkBuffer vertexBuffer = vertices_.handle();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
    vkCmdBindIndexBuffer(cmd, indices_.handle(), 0, VK_INDEX_TYPE_UINT32);
    for (const uint32_t i : objects) {
        vkCmdPushConstants(cmd, layout, stages, pushOffset, sizeof(uint32_t), &i);
        vkCmdDrawIndexed(cmd, draws_[i].indexCount, 1, draws_[i].firstIndex, draws_[i].vertexOffset, 0);
    }
}

std::vector<VkVertexInputAttributeDescription> SceneGpu::vertexAttributes() {
    return {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(Vertex, position))},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(Vertex, normal))},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, uint32_t(offsetof(Vertex, uv))},
    };
}

}  // namespace punctual::render
