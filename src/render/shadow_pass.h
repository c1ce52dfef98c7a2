#pragma once
// The raster shadow stage: spot lights into a 2D depth array (one layer each), point lights into
// a cube depth array (six faces each) or six slices of a 2D array. Arrays are sized to the
// shadowed lights present (a 1x1 placeholder when there are none); a view without casters draws
// nothing (spot layers are not even cleared: the shader never reads them).
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "lights/shadow_setup.h"
#include "vk/handle.h"
#include "vk/image.h"

namespace punctual::vk {
class Context;
}

namespace punctual::render {

class FrameBindings;
class SceneGpu;

// The depth arrays and their compare sampler; built before the frame's descriptor set.
class ShadowMaps {
public:
    ShadowMaps(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings);

    const vk::Image& spots() const { return spots_; }
    const vk::Image& pointCubes() const { return pointCubes_; }
    const vk::Image& pointSlices() const { return pointSlices_; }
    VkSampler sampler() const { return sampler_; }
    // Device memory of the three arrays, placeholders included.
    uint64_t allocatedBytes() const;

    static constexpr VkFormat kFormat = VK_FORMAT_D32_SFLOAT;

private:
    vk::Image spots_;
    vk::Image pointCubes_;
    vk::Image pointSlices_;
    vk::Handle<VkSampler> sampler_;
};

class ShadowPass {
public:
    ShadowPass(const vk::Context& context, const FrameBindings& bindings, const ShadowMaps& maps,
               const ShadowPlan& plan, const ShadowSettings& settings);
    // Renders every view with casters, clears point faces without, and leaves all three arrays
    // in SHADER_READ_ONLY_OPTIMAL for the forward pass.
    void record(VkCommandBuffer cmd, const SceneGpu& scene, const FrameBindings& bindings) const;

private:
    struct Target {
        vk::Handle<VkImageView> view;
        vk::Handle<VkFramebuffer> framebuffer;
        uint32_t planView = 0;  // index into plan_.views
    };
    const ShadowMaps& maps_;
    const ShadowPlan& plan_;
    uint32_t resolution_ = 0;
    vk::Handle<VkRenderPass> renderPass_;
    vk::Handle<VkPipelineLayout> pipelineLayout_;
    vk::Handle<VkPipeline> pipeline_;
    std::vector<Target> targets_;
};

}  // namespace punctual::render
