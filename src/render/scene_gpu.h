#pragma once
// The scene's GPU copy: one vertex and one index buffer for all meshes, the per-object and
// per-material storage buffers, and the textures (sRGB, every mip level the loader generated; any
// larger than the device's maxImageDimension2D downscaled to it, with a warning), each read
// through a sampler made from its glTF sampler. Built once per scene; every raster pass draws
// through drawObjects().
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

// How the depth-only passes draw an object. Opaque objects need no fragment shader, so their
// pipelines keep the early depth test; single-sided ones are culled by the rasteriser, whose front
// face is CCW, or CW for a mirroring transform. Masked objects test alpha in alpha_mask.frag.
// Blended (alphaMode BLEND) objects are not in the depth prepass at all: the transparent passes
// draw them, and the shadow passes as --transparent-shadows says.
enum class DepthDrawKind : uint8_t { OpaqueTwoSided, OpaqueCullBackCcw, OpaqueCullBackCw, Masked, Blended };
inline constexpr uint32_t kDepthDrawKindCount = 5;
inline constexpr uint32_t kPrepassDrawKinds = 4;  // the kinds before Blended

class SceneGpu {
public:
    // `objectLightCounts`: per object, the length of its per-object light list (empty: none).
    SceneGpu(vk::Context& context, const Scene& scene, const std::vector<uint32_t>& objectLightCounts);

    const vk::Buffer& objectBuffer() const { return objects_; }
    const vk::Buffer& materialBuffer() const { return materials_; }
    // Set 1 of the raster passes: binding 0 the material's base-colour texture, binding 1 its
    // emissive texture (fragment stage).
    VkDescriptorSetLayout materialSetLayout() const { return materialSetLayout_; }
    uint32_t objectCount() const { return uint32_t(draws_.size()); }
    DepthDrawKind depthDrawKind(uint32_t object) const { return depthKinds_[object]; }
    bool masked(uint32_t object) const { return depthKinds_[object] == DepthDrawKind::Masked; }
    bool blended(uint32_t object) const { return depthKinds_[object] == DepthDrawKind::Blended; }
    // Every object the opaque forward pass draws (all but the blended), ascending.
    std::span<const uint32_t> unblendedObjects() const { return unblended_; }
    // The objects of one kind, ascending.
    std::span<const uint32_t> objectsOfKind(DepthDrawKind kind) const { return objectsOfKind_[uint32_t(kind)]; }

    // Binds the geometry and issues one indexed draw per listed object, in list order, passing the
    // object index as a push constant at `pushOffset` for `stages`. `withTextures` also binds each
    // object's material set (set 1) for pipelines that read it.
    void drawObjects(VkCommandBuffer cmd, VkPipelineLayout layout, std::span<const uint32_t> objects,
                     uint32_t pushOffset, VkShaderStageFlags stages, bool withTextures = false) const;

    // One indexed draw of `object` with `instanceCount` instances from `firstInstance` (the shadow
    // pages' draws, one instance a page), as drawObjects otherwise; the geometry must be bound
    // (bindGeometry).
    void drawObjectInstances(VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t object, uint32_t pushOffset,
                             VkShaderStageFlags stages, bool withTextures, uint32_t instanceCount,
                             uint32_t firstInstance) const;
    void bindGeometry(VkCommandBuffer cmd) const;

    // Bytes of the scene's device buffers and textures.
    uint64_t memoryBytes() const;

    static std::vector<VkVertexInputAttributeDescription> vertexAttributes();
    // Position and the two texture coordinate sets: what shadow_masked.vert reads.
    static std::vector<VkVertexInputAttributeDescription> maskedCasterAttributes();
    static uint32_t vertexStride() { return sizeof(Vertex); }

private:
    struct Draw {
        uint32_t firstIndex;
        uint32_t indexCount;
        int32_t vertexOffset;
    };
    void createSamplers(vk::Context& context, const Scene& scene);
    VkSampler samplerFor(const TextureSampler& sampler) const;
    void createMaterialSets(vk::Context& context, const Scene& scene);

    vk::Buffer vertices_;
    vk::Buffer indices_;
    vk::Buffer objects_;
    vk::Buffer materials_;
    std::vector<vk::Image> textures_;  // the scene's, then a 1x1 white one for texture-less slots
    std::vector<TextureSampler> samplerKeys_;  // distinct samplers the materials use
    std::vector<vk::Handle<VkSampler>> samplers_;  // one per key
    VkDescriptorSetLayout materialSetLayout_ = VK_NULL_HANDLE;  // the context's object cache owns it
    vk::Handle<VkDescriptorPool> materialPool_;
    std::vector<VkDescriptorSet> materialSets_;  // one per material (freed with the pool)
    std::vector<Draw> draws_;
    std::vector<uint32_t> drawMaterial_;  // per object: its material
    std::vector<DepthDrawKind> depthKinds_;
    std::vector<uint32_t> objectsOfKind_[kDepthDrawKindCount];
    std::vector<uint32_t> unblended_;
};

}  // namespace punctual::render
