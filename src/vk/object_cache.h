#pragma once
// Render passes, descriptor-set layouts, pipeline layouts and pipelines, one per definition, kept
// for the life of the device (vk::Context owns the cache).
//
// Why: every Renderer made on a Context asks for the same few objects, and building a pipeline is
// the costliest step of setting a frame up. lavapipe (Mesa 22.3) takes 0.1-0.3 s for each forward
// pipeline and keeps nothing in a VkPipelineCache; a bench or a test suite that makes a renderer
// per configuration built the same forward shader hundreds of times (bench/RESULTS.md, CI time).
// A real GPU driver compiles less slowly, but the same objects are still built once, not once per
// renderer.
//
// Identical definitions give the same handle, so a pipeline's key can name its layout and render
// pass by handle. Sharing is what Vulkan allows: a pipeline is used with any compatible render
// pass and with descriptor sets bound through any identically defined pipeline layout, and the
// cache outlives every renderer that uses its objects. A shader's SPIR-V enters a key as its size
// and a 64-bit FNV-1a hash of its words (two shaders colliding would need the same size and hash).
#include <cstdint>
#include <initializer_list>
#include <map>
#include <mutex>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/handle.h"
#include "vk/pipeline.h"

namespace punctual::vk {

// What identifies each kind of object: every field of its definition, in order (exposed for the
// tests that check no field is left out).
using ObjectKey = std::vector<uint64_t>;
ObjectKey renderPassKey(const RenderPassDesc& desc);
ObjectKey setLayoutKey(std::span<const VkDescriptorSetLayoutBinding> bindings);
ObjectKey pipelineLayoutKey(std::span<const VkDescriptorSetLayout> setLayouts, VkPushConstantRange pushConstants);
ObjectKey graphicsPipelineKey(const GraphicsPipelineDesc& desc);
ObjectKey computePipelineKey(VkPipelineLayout layout, std::span<const uint32_t> spirv,
                             const VkSpecializationInfo* specialization);

class ObjectCache {
public:
    explicit ObjectCache(VkDevice device) : device_(device) {}
    ObjectCache(const ObjectCache&) = delete;
    ObjectCache& operator=(const ObjectCache&) = delete;

    // Each returns the cache's object for the definition, built on first use; the handles stay
    // valid until the cache is destroyed (callers never destroy them).
    VkRenderPass renderPass(const RenderPassDesc& desc);
    // Bindings without immutable samplers (an internal error otherwise: their handles would have to
    // join the key).
    VkDescriptorSetLayout setLayout(std::span<const VkDescriptorSetLayoutBinding> bindings);
    // Set layouts 0, 1, ... (from setLayout) and at most one push-constant range (size 0: none).
    VkPipelineLayout pipelineLayout(std::initializer_list<VkDescriptorSetLayout> setLayouts,
                                    VkPushConstantRange pushConstants);
    // desc.layout and desc.renderPass from this cache.
    VkPipeline graphicsPipeline(const GraphicsPipelineDesc& desc);
    VkPipeline computePipeline(VkPipelineLayout layout, std::span<const uint32_t> spirv,
                               const VkSpecializationInfo* specialization = nullptr);

    // How many pipelines were built (not found), for the tests.
    uint64_t pipelinesBuilt() const;

private:
    VkDevice device_;
    mutable std::mutex mutex_;
    std::map<ObjectKey, Handle<VkRenderPass>> renderPasses_;
    std::map<ObjectKey, Handle<VkDescriptorSetLayout>> setLayouts_;
    std::map<ObjectKey, Handle<VkPipelineLayout>> pipelineLayouts_;
    // Declared last: destroyed first, before the layouts and render passes they were built from.
    std::map<ObjectKey, Handle<VkPipeline>> pipelines_;
    uint64_t pipelinesBuilt_ = 0;
};

}  // namespace punctual::vk
