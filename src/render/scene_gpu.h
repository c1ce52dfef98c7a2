#pragma once
// The scene's GPU copy: one vertex and one index buffer for all meshes, the per-object and
// per-material storage buffers, and the base-colour textures (sRGB, one sampler). Built once per
// scene; every raster pass draws through drawObjects().
#include <cstdint>
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
    // At least one texture: a 1x1 white placeholder when the scene has none, so the texture
    // array binding is never empty.
    const std::vector<vk::Image>& textures() const { return textures_; }
    VkSampler sampler() const { return sampler_; }
    uint32_t objectCount() const { return uint32_t(draws_.size()); }

    // Binds the geometry and issues one indexed draw per object, passing the object index as a
    // push constant (stage flags: vertex | fragment).
    void drawObjects(VkCommandBuffer cmd, VkPipelineLayout layout) const;

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
    std::vector<vk::Image> textures_;
    vk::Handle<VkSampler> sampler_;
    std::vector<Draw> draws_;
};

}  // namespace punctual::render
