#include "render/scene_gpu.h"

#include <algorithm>
#include <array>
#include <cstddef>

#include "core/error.h"
#include "core/log.h"
#include "gpu_types.h"
#include "materials.h"
#include "scene/texture_limit.h"
#include "scene/texture_mips.h"
#include "vk/check.h"
#include "vk/descriptors.h"
#include "vk/context.h"

namespace punctual::render {
namespace {

// Every level of `texture` into a new sampled image, left in SHADER_READ_ONLY_OPTIMAL.
vk::Image uploadTexture(vk::Context& context, const Texture& texture) {
    vk::ImageDesc desc;
    desc.format = VK_FORMAT_R8G8B8A8_SRGB;  // glTF colour textures are sRGB-encoded
    desc.width = texture.width;
    desc.height = texture.height;
    desc.mipLevels = texture.levelCount();
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.debugName = texture.name;
    vk::Image image(context, desc);

    std::vector<VkBufferImageCopy> copies;
    VkDeviceSize bytes = 0;
    const auto addLevel = [&](uint32_t level, uint32_t width, uint32_t height) {
        VkBufferImageCopy copy{};
        copy.bufferOffset = bytes;
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
        copy.imageExtent = {width, height, 1};
        copies.push_back(copy);
        bytes += VkDeviceSize(width) * height * 4;
    };
    addLevel(0, texture.width, texture.height);
    for (uint32_t level = 1; level < texture.levelCount(); ++level)
        addLevel(level, texture.mipLevels[level - 1].width, texture.mipLevels[level - 1].height);
    vk::Buffer staging(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::Upload, "texture staging");
    staging.write(texture.rgba.data(), VkDeviceSize(texture.rgba.size()));
    for (uint32_t level = 1; level < texture.levelCount(); ++level) {
        const std::vector<uint8_t>& rgba = texture.mipLevels[level - 1].rgba;
        staging.write(rgba.data(), VkDeviceSize(rgba.size()), copies[level].bufferOffset);
    }
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_ACCESS_TRANSFER_WRITE_BIT);
        vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(copies.size()), copies.data());
        vk::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    });
    return image;
}

VkFilter vulkanFilter(TextureFilter filter) { return filter == TextureFilter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }

VkSamplerAddressMode vulkanWrap(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
        case TextureWrap::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case TextureWrap::Repeat: break;
    }
    return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

// A glTF sampler as Vulkan's. No anisotropy: the CPU reference filters as Vulkan's isotropic
// trilinear rule says (reference/texture_sampler.h), and anisotropic footprints are left to each
// driver. Without mipmaps maxLod 0 keeps level 0, while the minification filter still applies.
vk::Handle<VkSampler> createTextureSampler(VkDevice device, const TextureSampler& sampler) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = vulkanFilter(sampler.magFilter);
    info.minFilter = vulkanFilter(sampler.minFilter);
    info.mipmapMode = sampler.mipFilter == TextureFilter::Nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST
                                                                  : VK_SAMPLER_MIPMAP_MODE_LINEAR;
    info.addressModeU = vulkanWrap(sampler.wrapU);
    info.addressModeV = vulkanWrap(sampler.wrapV);
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.minLod = 0.0f;
    info.maxLod = sampler.mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
    VkSampler handle = VK_NULL_HANDLE;
    vk::check(vkCreateSampler(device, &info, nullptr, &handle), "vkCreateSampler");
    return {device, handle, vkDestroySampler};
}

// KHR_texture_transform's rows (materials.h) with the texture coordinate set in row U's w.
void packTextureRef(const TextureRef& ref, glm::vec4 rows[2]) {
    const TextureTransform& t = ref.transform;
    rows[0] = glm::vec4(gpu::textureTransformRowU(t.offset, t.rotation, t.scale), float(ref.texCoord));
    rows[1] = glm::vec4(gpu::textureTransformRowV(t.offset, t.rotation, t.scale), 0.0f);
}

gpu::GpuMaterial packMaterial(const Material& material) {
    gpu::GpuMaterial packed{};
    packed.baseColorFactor = material.baseColorFactor;
    packed.emission = glm::vec4(material.emission(), material.alphaCutoff);
    packTextureRef(material.baseColorTexture, packed.baseColorUv);
    packTextureRef(material.emissiveTexture, packed.emissiveUv);
    packed.metallicRoughness = glm::vec2(material.metallic, material.roughness);
    packed.baseColorTexture = material.baseColorTexture.image;
    packed.emissiveTexture = material.emissiveTexture.image;
    if (material.alphaMode == AlphaMode::Mask) packed.flags |= PUNCTUAL_MATERIAL_ALPHA_MASK;
    if (material.alphaMode == AlphaMode::Blend) packed.flags |= PUNCTUAL_MATERIAL_ALPHA_BLEND;
    if (!material.doubleSided) packed.flags |= PUNCTUAL_MATERIAL_SINGLE_SIDED;
    return packed;
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
    for (const Material& material : scene.materials) materials.push_back(packMaterial(material));
    if (materials.empty()) throw Error(scene.source, "scene has no materials");
    materials_ = deviceBuffer(context, materials, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "materials");

    for (uint32_t index = 0; index < scene.objects.size(); ++index) {
        const uint32_t materialIndex = scene.meshes.at(scene.objects[index].mesh).material;
        const Material& material = scene.materials.at(materialIndex);
        drawMaterial_.push_back(materialIndex);
        DepthDrawKind kind = DepthDrawKind::OpaqueTwoSided;
        if (material.alphaMode == AlphaMode::Blend) {
            kind = DepthDrawKind::Blended;
        } else if (material.alphaMode == AlphaMode::Mask) {
            kind = DepthDrawKind::Masked;
        } else if (!material.doubleSided) {
            const bool mirrored = objects[index].material.y != 0u;
            kind = mirrored ? DepthDrawKind::OpaqueCullBackCw : DepthDrawKind::OpaqueCullBackCcw;
        }
        depthKinds_.push_back(kind);
        objectsOfKind_[uint32_t(kind)].push_back(index);
        if (kind != DepthDrawKind::Blended) unblended_.push_back(index);
    }

    // Textures are already fitted to the frame when loaded (scene/texture_limit.h); the device
    // may allow less (maxImageDimension2D is only guaranteed to be 4096). Beyond it image
    // creation is invalid, so fit those here, once per texture, with a new mip chain.
    const uint32_t deviceMaxSide = context.properties().limits.maxImageDimension2D;
    for (const Texture& texture : scene.textures) {
        if (std::max(texture.width, texture.height) <= deviceMaxSide) {
            textures_.push_back(uploadTexture(context, texture));
            continue;
        }
        Texture fitted = fittedTexture(texture, deviceMaxSide);
        generateMipmaps(fitted);
        log::warn(scene.source + ": " +
                  downscaleWarning("texture '" + texture.name + "'", {texture.width, texture.height},
                                   {fitted.width, fitted.height},
                                   "the device's limit, maxImageDimension2D = " + std::to_string(deviceMaxSide)));
        textures_.push_back(uploadTexture(context, fitted));
    }
    Texture white;
    white.name = "no texture";
    white.width = 1;
    white.height = 1;
    white.rgba = {255, 255, 255, 255};
    textures_.push_back(uploadTexture(context, white));

    createSamplers(context, scene);
    createMaterialSets(context, scene);
}

void SceneGpu::createSamplers(vk::Context& context, const Scene& scene) {
    samplerKeys_.push_back(TextureSampler{});  // the white texel's, and the first of the list
    for (const Material& material : scene.materials)
        for (const TextureRef* ref : {&material.baseColorTexture, &material.emissiveTexture})
            if (ref->present() && std::find(samplerKeys_.begin(), samplerKeys_.end(), ref->sampler) == samplerKeys_.end())
                samplerKeys_.push_back(ref->sampler);
    for (const TextureSampler& key : samplerKeys_) samplers_.push_back(createTextureSampler(context.device(), key));
}

VkSampler SceneGpu::samplerFor(const TextureSampler& sampler) const {
    const auto found = std::find(samplerKeys_.begin(), samplerKeys_.end(), sampler);
    return samplers_.at(size_t(found - samplerKeys_.begin())).get();
}

void SceneGpu::createMaterialSets(vk::Context& context, const Scene& scene) {
    const VkDevice device = context.device();
    const std::array<VkDescriptorSetLayoutBinding, 2> bindings = {{
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
    }};
    materialSetLayout_ = context.objects().setLayout(bindings);
    const uint32_t setCount = uint32_t(scene.materials.size());
    const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * setCount};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = setCount;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &poolSize;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    vk::check(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
    materialPool_ = vk::Handle<VkDescriptorPool>(device, pool, vkDestroyDescriptorPool);
    const std::vector<VkDescriptorSetLayout> layouts(setCount, materialSetLayout_);
    VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocInfo.descriptorPool = pool;
    allocInfo.descriptorSetCount = setCount;
    allocInfo.pSetLayouts = layouts.data();
    materialSets_.resize(setCount);
    vk::check(vkAllocateDescriptorSets(device, &allocInfo, materialSets_.data()), "vkAllocateDescriptorSets");

    const size_t white = textures_.size() - 1;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        std::array<VkDescriptorImageInfo, 2> images{};
        const std::array<const TextureRef*, 2> refs = {&material.baseColorTexture, &material.emissiveTexture};
        for (size_t slot = 0; slot < refs.size(); ++slot) {
            const TextureRef& ref = *refs[slot];
            const size_t image = ref.present() ? size_t(ref.image) : white;
            images[slot] = {ref.present() ? samplerFor(ref.sampler) : samplers_.front().get(),
                            textures_.at(image).view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        }
        const std::array<VkWriteDescriptorSet, 2> writes = {vk::imageWrite(materialSets_[m], 0, &images[0]),
                                                            vk::imageWrite(materialSets_[m], 1, &images[1])};
        vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);
    }
}

uint64_t SceneGpu::memoryBytes() const {
    uint64_t bytes = vertices_.size() + indices_.size() + objects_.size() + materials_.size();
    for (const vk::Image& texture : textures_) bytes += texture.allocatedBytes();
    return bytes;
}

void SceneGpu::bindGeometry(VkCommandBuffer cmd) const {
    const VkBuffer vertexBuffer = vertices_.handle();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
    vkCmdBindIndexBuffer(cmd, indices_.handle(), 0, VK_INDEX_TYPE_UINT32);
}

void SceneGpu::drawObjectInstances(VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t object, uint32_t pushOffset,
                                   VkShaderStageFlags stages, bool withTextures, uint32_t instanceCount,
                                   uint32_t firstInstance) const {
    if (withTextures) {
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &materialSets_[drawMaterial_[object]], 0,
                                nullptr);
    }
    vkCmdPushConstants(cmd, layout, stages, pushOffset, sizeof(uint32_t), &object);
    vkCmdDrawIndexed(cmd, draws_[object].indexCount, instanceCount, draws_[object].firstIndex, draws_[object].vertexOffset,
                     firstInstance);
}

void SceneGpu::drawObjects(VkCommandBuffer cmd, VkPipelineLayout layout, std::span<const uint32_t> objects,
                           uint32_t pushOffset, VkShaderStageFlags stages, bool withTextures) const {
    bindGeometry(cmd);
    uint32_t boundMaterial = UINT32_MAX;
    for (const uint32_t i : objects) {
        if (withTextures && drawMaterial_[i] != boundMaterial) {
            boundMaterial = drawMaterial_[i];
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &materialSets_[boundMaterial],
                                    0, nullptr);
        }
        vkCmdPushConstants(cmd, layout, stages, pushOffset, sizeof(uint32_t), &i);
        vkCmdDrawIndexed(cmd, draws_[i].indexCount, 1, draws_[i].firstIndex, draws_[i].vertexOffset, 0);
    }
}

std::vector<VkVertexInputAttributeDescription> SceneGpu::vertexAttributes() {
    return {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(Vertex, position))},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(Vertex, normal))},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, uint32_t(offsetof(Vertex, uv))},
        {3, 0, VK_FORMAT_R32G32_SFLOAT, uint32_t(offsetof(Vertex, uv1))},
    };
}

std::vector<VkVertexInputAttributeDescription> SceneGpu::maskedCasterAttributes() {
    std::vector<VkVertexInputAttributeDescription> attributes = vertexAttributes();
    attributes.erase(attributes.begin() + 1);  // no normal
    return attributes;
}

}  // namespace punctual::render
