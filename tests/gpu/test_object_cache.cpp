// The context's object cache (vk/object_cache.h): a key changes with every field of a definition,
// equal definitions share one object, and renderers that share pipelines draw what renderers that
// built their own drew.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gpu_test_support.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "vk/object_cache.h"

namespace punctual {
namespace {

// Stand-ins for handles: the key functions never call Vulkan.
template <typename T>
T fakeHandle(uintptr_t value) {
    if constexpr (std::is_pointer_v<T>) {
        return reinterpret_cast<T>(value);
    } else {
        return T(value);
    }
}

TEST(ObjectCache, EveryFieldOfAGraphicsPipelineJoinsItsKey) {
    static const std::array<uint32_t, 5> vertexWords = {0x07230203u, 1u, 2u, 3u, 4u};
    static const std::array<uint32_t, 5> otherWords = {0x07230203u, 1u, 2u, 3u, 5u};  // same size, one word apart
    static const std::array<uint32_t, 6> fragmentWords = {0x07230203u, 9u, 8u, 7u, 6u, 5u};
    const uint32_t constant = 7;
    const uint32_t otherConstant = 8;
    const VkSpecializationMapEntry entry{3, 0, sizeof(uint32_t)};
    const VkSpecializationMapEntry otherEntry{4, 0, sizeof(uint32_t)};
    const VkSpecializationInfo specialization{1, &entry, sizeof(uint32_t), &constant};
    const VkSpecializationInfo otherValue{1, &entry, sizeof(uint32_t), &otherConstant};
    const VkSpecializationInfo otherId{1, &otherEntry, sizeof(uint32_t), &constant};

    vk::GraphicsPipelineDesc base;
    base.layout = fakeHandle<VkPipelineLayout>(0x1000);
    base.renderPass = fakeHandle<VkRenderPass>(0x2000);
    base.vertexSpirv = vertexWords;
    base.fragmentSpirv = fragmentWords;
    base.fragmentSpecialization = &specialization;
    base.vertexSpecialization = nullptr;
    base.vertexStride = 32;
    base.vertexAttributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}, {1, 0, VK_FORMAT_R32G32_SFLOAT, 12}};

    // One change per field of GraphicsPipelineDesc (a new field needs a line here and in
    // graphicsPipelineKey; object_cache.cpp's size check is the reminder).
    const std::vector<std::pair<std::string, std::function<void(vk::GraphicsPipelineDesc&)>>> changes = {
        {"layout", [](auto& d) { d.layout = fakeHandle<VkPipelineLayout>(0x1001); }},
        {"renderPass", [](auto& d) { d.renderPass = fakeHandle<VkRenderPass>(0x2001); }},
        {"vertexSpirv", [&](auto& d) { d.vertexSpirv = otherWords; }},
        {"fragmentSpirv", [&](auto& d) { d.fragmentSpirv = {}; }},
        {"fragmentSpecialization value", [&](auto& d) { d.fragmentSpecialization = &otherValue; }},
        {"fragmentSpecialization id", [&](auto& d) { d.fragmentSpecialization = &otherId; }},
        {"fragmentSpecialization none", [&](auto& d) { d.fragmentSpecialization = nullptr; }},
        {"vertexSpecialization", [&](auto& d) { d.vertexSpecialization = &specialization; }},
        {"vertexStride", [](auto& d) { d.vertexStride = 48; }},
        {"vertexAttributes count", [](auto& d) { d.vertexAttributes.pop_back(); }},
        {"vertexAttributes format", [](auto& d) { d.vertexAttributes[1].format = VK_FORMAT_R32G32B32A32_SFLOAT; }},
        {"vertexAttributes offset", [](auto& d) { d.vertexAttributes[1].offset = 16; }},
        {"vertexAttributes location", [](auto& d) { d.vertexAttributes[1].location = 2; }},
        {"hasColorAttachment", [](auto& d) { d.hasColorAttachment = !d.hasColorAttachment; }},
        {"alphaBlend", [](auto& d) { d.alphaBlend = !d.alphaBlend; }},
        {"depthTest", [](auto& d) { d.depthTest = !d.depthTest; }},
        {"depthWrite", [](auto& d) { d.depthWrite = !d.depthWrite; }},
        {"depthCompare", [](auto& d) { d.depthCompare = VK_COMPARE_OP_GREATER; }},
        {"cullMode", [](auto& d) { d.cullMode = VK_CULL_MODE_BACK_BIT; }},
        {"frontFace", [](auto& d) { d.frontFace = VK_FRONT_FACE_CLOCKWISE; }},
        {"depthBias", [](auto& d) { d.depthBias = !d.depthBias; }},
        {"depthClamp", [](auto& d) { d.depthClamp = !d.depthClamp; }},
    };
    const vk::ObjectKey baseKey = vk::graphicsPipelineKey(base);
    vk::GraphicsPipelineDesc copy = base;
    EXPECT_EQ(vk::graphicsPipelineKey(copy), baseKey);  // equal definitions, equal keys
    for (const auto& [field, change] : changes) {
        vk::GraphicsPipelineDesc changed = base;
        change(changed);
        EXPECT_NE(vk::graphicsPipelineKey(changed), baseKey) << field;
    }
    // A compute pipeline never takes a graphics pipeline's key.
    EXPECT_NE(vk::computePipelineKey(base.layout, vertexWords, &specialization), baseKey);
}

TEST(ObjectCache, EveryFieldOfTheOtherDefinitionsJoinsTheirKeys) {
    vk::RenderPassDesc pass;
    const vk::ObjectKey passKey = vk::renderPassKey(pass);
    vk::RenderPassDesc otherPass = pass;
    otherPass.colorLoad = VK_ATTACHMENT_LOAD_OP_LOAD;
    EXPECT_NE(vk::renderPassKey(otherPass), passKey);
    otherPass = pass;
    otherPass.depthFinalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    EXPECT_NE(vk::renderPassKey(otherPass), passKey);

    std::vector<VkDescriptorSetLayoutBinding> bindings = {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
    const vk::ObjectKey setKey = vk::setLayoutKey(bindings);
    for (int field = 0; field < 4; ++field) {
        std::vector<VkDescriptorSetLayoutBinding> changed = bindings;
        if (field == 0) changed[1].binding = 3;
        if (field == 1) changed[1].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        if (field == 2) changed[1].descriptorCount = 2;
        if (field == 3) changed[1].stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
        EXPECT_NE(vk::setLayoutKey(changed), setKey) << field;
    }

    const std::array<VkDescriptorSetLayout, 2> sets = {fakeHandle<VkDescriptorSetLayout>(1),
                                                       fakeHandle<VkDescriptorSetLayout>(2)};
    const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, 4};
    const vk::ObjectKey layoutKey = vk::pipelineLayoutKey(sets, push);
    EXPECT_NE(vk::pipelineLayoutKey(std::span(sets).first(1), push), layoutKey);
    EXPECT_NE(vk::pipelineLayoutKey(sets, {VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4}), layoutKey);
    EXPECT_NE(vk::pipelineLayoutKey(sets, {VK_SHADER_STAGE_VERTEX_BIT, 0, 8}), layoutKey);
}

TEST(ObjectCache, RenderersShareTheirPipelinesAndDrawTheSameImages) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    render::RenderSettings settings = testing::renderSettings(256, 144);
    settings.method = render::LightListMethod::Clustered;

    // Equal definitions give the same object.
    vk::RenderPassDesc pass;
    EXPECT_EQ(context->objects().renderPass(pass), context->objects().renderPass(pass));

    const uint64_t before = context->objects().pipelinesBuilt();
    ImageRgba8 first;
    {
        render::Renderer renderer(*context, scene, settings);
        first = renderer.render(1, 0).image;
    }
    const uint64_t builtByFirst = context->objects().pipelinesBuilt() - before;
    EXPECT_GT(builtByFirst, 3u);  // prepass, culling, forward, tone map at least

    // The same settings again: no pipeline is built, the image is the same to the bit.
    render::Renderer again(*context, scene, settings);
    EXPECT_EQ(context->objects().pipelinesBuilt() - before, builtByFirst);
    EXPECT_TRUE(again.render(1, 0).image.pixels == first.pixels);

    // Another method builds its own culling and forward pipelines, and draws the same image (the
    // culled methods are lossless) while the first renderer's objects stay in use.
    render::RenderSettings brute = settings;
    brute.method = render::LightListMethod::Brute;
    render::Renderer other(*context, scene, brute);
    EXPECT_GT(context->objects().pipelinesBuilt() - before, builtByFirst);
    EXPECT_TRUE(other.render(1, 0).image.pixels == first.pixels);
    EXPECT_TRUE(again.render(1, 0).image.pixels == first.pixels);
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
