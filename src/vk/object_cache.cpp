#include "vk/object_cache.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>

#include "core/byte_words.h"
#include "core/check.h"
#include "vk/descriptors.h"

namespace punctual::vk {

namespace {

// Appends a definition's fields to a key, each as one or more 64-bit words.
class KeyWriter {
public:
    void add(uint64_t value) { key_.push_back(value); }
    template <typename T>
    void addHandle(T handle) {
        if constexpr (std::is_pointer_v<T>) {
            add(uint64_t(reinterpret_cast<uintptr_t>(handle)));
        } else {
            add(uint64_t(handle));  // 32-bit builds: non-dispatchable handles are 64-bit integers
        }
    }
    void addBytes(const void* data, size_t size) {
        addBytesAsWords(data, size, [&](uint64_t word) { add(word); });
    }
    // SPIR-V as its size and a 64-bit FNV-1a hash of its words: the whole module would make each
    // key about 100 KiB (the forward shader).
    void addSpirv(std::span<const uint32_t> words) {
        uint64_t hash = 0xcbf29ce484222325ull;
        for (uint32_t word : words) {
            hash ^= word;
            hash *= 0x100000001b3ull;
        }
        add(words.size());
        add(hash);
    }
    void addSpecialization(const VkSpecializationInfo* info) {
        if (!info) {
            add(0);
            return;
        }
        add(1);
        add(info->mapEntryCount);
        for (uint32_t i = 0; i < info->mapEntryCount; ++i) {
            const VkSpecializationMapEntry& entry = info->pMapEntries[i];
            add(entry.constantID);
            add(entry.offset);
            add(entry.size);
        }
        addBytes(info->pData, info->dataSize);
    }
    ObjectKey take() { return std::move(key_); }

private:
    ObjectKey key_;
};

// A render pass description is enums alone: its bytes are its definition, and a field added to it
// joins the key by itself (no padding can hide one).
static_assert(std::has_unique_object_representations_v<RenderPassDesc>,
              "RenderPassDesc gained a field with padding or a pointer: key it field by field");

// The graphics description's fields are keyed one by one (graphicsPipelineKey). A field added to
// GraphicsPipelineDesc must join that key and tests/gpu/test_object_cache.cpp's list of fields;
// this size (LP64) is the reminder.
static_assert(sizeof(void*) != 8 || sizeof(GraphicsPipelineDesc) == 120,
              "GraphicsPipelineDesc changed: add the new field to graphicsPipelineKey and its test");

// Graphics and compute pipelines share one map; their keys start apart.
constexpr uint64_t kGraphicsPipeline = 1;
constexpr uint64_t kComputePipeline = 2;

template <typename Map, typename Build>
auto findOrBuild(Map& map, ObjectKey key, Build&& build) {
    auto found = map.find(key);
    if (found == map.end()) found = map.emplace(std::move(key), build()).first;
    return found->second.get();
}

}  // namespace

ObjectKey renderPassKey(const RenderPassDesc& desc) {
    KeyWriter key;
    key.addBytes(&desc, sizeof(desc));
    return key.take();
}

ObjectKey setLayoutKey(std::span<const VkDescriptorSetLayoutBinding> bindings) {
    KeyWriter key;
    key.add(bindings.size());
    for (const VkDescriptorSetLayoutBinding& binding : bindings) {
        PUNCTUAL_CHECK(binding.pImmutableSamplers == nullptr, "a cached set layout with immutable samplers");
        key.add(binding.binding);
        key.add(uint64_t(binding.descriptorType));
        key.add(binding.descriptorCount);
        key.add(binding.stageFlags);
    }
    return key.take();
}

ObjectKey pipelineLayoutKey(std::span<const VkDescriptorSetLayout> setLayouts, VkPushConstantRange pushConstants) {
    KeyWriter key;
    key.add(setLayouts.size());
    for (VkDescriptorSetLayout layout : setLayouts) key.addHandle(layout);
    key.add(pushConstants.stageFlags);
    key.add(pushConstants.offset);
    key.add(pushConstants.size);
    return key.take();
}

ObjectKey graphicsPipelineKey(const GraphicsPipelineDesc& desc) {
    KeyWriter key;
    key.add(kGraphicsPipeline);
    key.addHandle(desc.layout);
    key.addHandle(desc.renderPass);
    key.addSpirv(desc.vertexSpirv);
    key.addSpirv(desc.fragmentSpirv);
    key.addSpecialization(desc.fragmentSpecialization);
    key.addSpecialization(desc.vertexSpecialization);
    key.add(desc.vertexStride);
    key.add(desc.vertexAttributes.size());
    for (const VkVertexInputAttributeDescription& attribute : desc.vertexAttributes) {
        key.add(attribute.location);
        key.add(attribute.binding);
        key.add(uint64_t(attribute.format));
        key.add(attribute.offset);
    }
    key.add(desc.hasColorAttachment);
    key.add(desc.alphaBlend);
    key.add(desc.depthTest);
    key.add(desc.depthWrite);
    key.add(uint64_t(desc.depthCompare));
    key.add(desc.cullMode);
    key.add(uint64_t(desc.frontFace));
    key.add(desc.depthBias);
    key.add(desc.depthClamp);
    return key.take();
}

ObjectKey computePipelineKey(VkPipelineLayout layout, std::span<const uint32_t> spirv,
                             const VkSpecializationInfo* specialization) {
    KeyWriter key;
    key.add(kComputePipeline);
    key.addHandle(layout);
    key.addSpirv(spirv);
    key.addSpecialization(specialization);
    return key.take();
}

VkRenderPass ObjectCache::renderPass(const RenderPassDesc& desc) {
    const std::lock_guard lock(mutex_);
    return findOrBuild(renderPasses_, renderPassKey(desc), [&] { return createRenderPass(device_, desc); });
}

VkDescriptorSetLayout ObjectCache::setLayout(std::span<const VkDescriptorSetLayoutBinding> bindings) {
    const std::lock_guard lock(mutex_);
    return findOrBuild(setLayouts_, setLayoutKey(bindings), [&] { return createDescriptorSetLayout(device_, bindings); });
}

VkPipelineLayout ObjectCache::pipelineLayout(std::initializer_list<VkDescriptorSetLayout> setLayouts,
                                             VkPushConstantRange pushConstants) {
    const std::lock_guard lock(mutex_);
    return findOrBuild(pipelineLayouts_, pipelineLayoutKey({setLayouts.begin(), setLayouts.size()}, pushConstants),
                       [&] { return createPipelineLayout(device_, setLayouts, pushConstants); });
}

VkPipeline ObjectCache::graphicsPipeline(const GraphicsPipelineDesc& desc) {
    const std::lock_guard lock(mutex_);
    return findOrBuild(pipelines_, graphicsPipelineKey(desc), [&] {
        ++pipelinesBuilt_;
        return createGraphicsPipeline(device_, desc);
    });
}

VkPipeline ObjectCache::computePipeline(VkPipelineLayout layout, std::span<const uint32_t> spirv,
                                        const VkSpecializationInfo* specialization) {
    const std::lock_guard lock(mutex_);
    return findOrBuild(pipelines_, computePipelineKey(layout, spirv, specialization), [&] {
        ++pipelinesBuilt_;
        return createComputePipeline(device_, layout, spirv, specialization);
    });
}

uint64_t ObjectCache::pipelinesBuilt() const {
    const std::lock_guard lock(mutex_);
    return pipelinesBuilt_;
}

}  // namespace punctual::vk
