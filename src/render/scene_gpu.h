#pragma once
// The scene's GPU copy: one vertex and one index buffer for all meshes, the per-object and
// per-material storage buffers, and the base-colour textures (sRGB, one sampler; any larger than
// the device's maxImageDimension2D downscaled to it, with a warning). Built once per scene; every
// raster pass draws through drawObjects().
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "scene/scene.h"
#include "vk/buffer.h"
#include "vk/handle.h"
#include "vk/image.h"

namespace punctual::vk {
class Context;
}

namespace punctual::render {

class SceneGpu {
public:
    // `objectLightCounts`: per object, the length of its per-object light list (empty: none).
    SceneGpu(vk::Context& context, const Scene& scene, const std::vector<uint32_t>& objectLightCounts);

    const vk::Buffer& objectBuffer() const { return objects_; }
    const vk::Buffer& materialBuffer() const { return materials_; }
    // Set 1 of the forward pass: one combined image sampler, the material's base-colour texture.
    VkDescriptorSetLayout materialSetLayout() const { return materialSetLayout_; }
    uint32_t objectCount() const { return uint32_t(draws_.size()); }

    // Binds the geometry and issues one indexed draw per object, passing the object index as a
    // push constant (stage flags: vertex | fragment). `withTextures` also binds each object's
    // material texture set (set 1) for pipelines that read it.
    void drawObjects(VkCommandBuffer cmd, VkPipelineLayout layout, bool withTextures) const;
    // The listed objects only, with the index pushed at `pushOffset` for `stages`; no textures.
    void drawObjects(VkCommandBuffer cmd, VkPipelineLayout layout, std::span<const uint32_t> objects,
                     uint32_t pushOffset, VkShaderStageFlags stages) const;

    static std::vector<VkVertexInputAttributeDescription> vertexAttributes();
    static uint32_t vertexStride() { return sizeof(Vertex); }

private:
    struct Draw {
        uint32_t firstIndex;
        uint32_t indexCount;
        int32_t vertexOffset;
    };
    vk::Buffer vertices_;
    vk::Buffer indices_;
    vk::Buffer objects_;
    vk::Buffer materials_;
    std::vector<vk::Image> textures_;  // the scene's, then a 1x1 white one for untextured materials
    vk::Handle<VkSampler> sampler_;
    vk::Handle<VkDescriptorSetLayout> materialSetLayout_;
    vk::Handle<VkDescriptorPool> materialPool_;
    std::vector<VkDescriptorSet> textureSets_;  // one per texture (freed with the pool)
    std::vector<Draw> draws_;
    std::vector<uint32_t> drawTextureSet_;      // per object: index into textureSets_
};

}  // namespace punctual::render
