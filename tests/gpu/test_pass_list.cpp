// The pass list (src/render/pass_list.h): frames check that each pass finds every image in the
// layout it declares, debug frames replace a pass by identity, memory is totalled by the kind each
// pass reports, and timings' medians. No device needed: the passes here record nothing and the
// images are only identities.
#include <gtest/gtest.h>

#include <array>

#include <string>
#include <vector>

#include "core/check.h"
#include "render/pass_list.h"
#include "render/pass_timings.h"
#include "vk/image.h"

namespace punctual::render {
namespace {

// A pass that only declares: its image uses, the set-0 stages it samples, its memory.
class DeclaringPass final : public Pass {
public:
    DeclaringPass(const char* name, std::vector<ImageUse> uses, VkShaderStageFlags boundStages = 0,
                  uint64_t bytes = 0, MemoryKind kind = MemoryKind::Frame)
        : name_(name), uses_(std::move(uses)), boundStages_(boundStages), bytes_(bytes), kind_(kind) {}
    const char* name() const override { return name_; }
    void record(const FrameContext&) const override {}
    std::vector<ImageUse> imageUses() const override { return uses_; }
    VkShaderStageFlags boundImageStages() const override { return boundStages_; }
    uint64_t memoryBytes() const override { return bytes_; }
    MemoryKind memoryKind() const override { return kind_; }

private:
    const char* name_;
    std::vector<ImageUse> uses_;
    VkShaderStageFlags boundStages_;
    uint64_t bytes_;
    MemoryKind kind_;
};

constexpr VkImageLayout kUndefined = VK_IMAGE_LAYOUT_UNDEFINED;
constexpr VkImageLayout kAttachment = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
constexpr VkImageLayout kReadOnly = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
constexpr VkImageLayout kShaderRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// The message of the InternalError the check throws, or "" when it passes.
std::string layoutProblem(const std::vector<const Pass*>& frame, const std::vector<BoundImage>& bound,
                          const ImageLayouts& resting) {
    try {
        checkImageLayouts(frame, bound, resting);
    } catch (const InternalError& error) {
        return error.what();
    }
    return "";
}

TEST(PassList, NeighboursThatAgreePass) {
    const vk::Image depth;
    const DeclaringPass writer("prepass", {{&depth, kUndefined, kReadOnly}});
    const DeclaringPass reader("forward", {{&depth, kReadOnly, kReadOnly}});
    const std::vector<const Pass*> frame = {&writer, &reader};
    const ImageLayouts resting = restingLayouts(frame, {});
    EXPECT_EQ(resting.at(&depth), kReadOnly);
    EXPECT_EQ(layoutProblem(frame, {}, resting), "");
}

TEST(PassList, APassFindingAnImageInAnotherLayoutFailsNamingBothPasses) {
    const vk::Image depth;
    const DeclaringPass writer("prepass", {{&depth, kUndefined, kAttachment}});
    const DeclaringPass reader("forward", {{&depth, kReadOnly, kReadOnly}});
    const std::vector<const Pass*> frame = {&writer, &reader};
    const std::string problem = layoutProblem(frame, {}, restingLayouts(frame, {}));
    EXPECT_NE(problem.find("pass 'forward' expects an unnamed image in DEPTH_STENCIL_READ_ONLY_OPTIMAL"), std::string::npos)
        << problem;
    EXPECT_NE(problem.find("pass 'prepass' leaves it in DEPTH_STENCIL_ATTACHMENT_OPTIMAL"), std::string::npos) << problem;
}

TEST(PassList, AReaderBeforeAnyWriterFailsOnAFreshImage) {
    // The frame's end would leave the image as the reader wants it, but the first frame starts
    // from a new, UNDEFINED image.
    const vk::Image radiance;
    const DeclaringPass reader("tonemap", {{&radiance, kShaderRead, kShaderRead}});
    const DeclaringPass writer("forward", {{&radiance, kUndefined, kShaderRead}});
    const std::vector<const Pass*> frame = {&reader, &writer};
    const std::string problem = layoutProblem(frame, {}, restingLayouts(frame, {}));
    EXPECT_NE(problem.find("pass 'tonemap' expects"), std::string::npos) << problem;
    EXPECT_NE(problem.find("no pass"), std::string::npos) << problem;
}

TEST(PassList, ADebugFrameMustLeaveItsImagesAsTheFrameDoes) {
    const vk::Image radiance;
    const DeclaringPass forward("forward", {{&radiance, kUndefined, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}});
    const DeclaringPass tonemap("tonemap", {{&radiance, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kShaderRead}});
    const std::vector<const Pass*> frame = {&forward, &tonemap};
    const ImageLayouts resting = restingLayouts(frame, {});
    const std::vector<const Pass*> debug = {&forward};
    const std::string problem = layoutProblem(debug, {}, resting);
    EXPECT_NE(problem.find("a frame leaves an unnamed image in COLOR_ATTACHMENT_OPTIMAL"), std::string::npos) << problem;
}

TEST(PassList, SetZerosImagesAreCheckedForTheStagesThatSampleThem) {
    const vk::Image depth;
    const vk::Image atlas;
    const std::vector<BoundImage> bound = {{{&depth, kReadOnly, kReadOnly}, VK_SHADER_STAGE_COMPUTE_BIT},
                                           {{&atlas, kShaderRead, kShaderRead}, VK_SHADER_STAGE_FRAGMENT_BIT}};
    const DeclaringPass prepass("depth", {{&depth, kUndefined, kReadOnly}});
    const DeclaringPass culling("culling", {}, VK_SHADER_STAGE_COMPUTE_BIT);
    const DeclaringPass shadows("shadows", {{&atlas, kUndefined, kShaderRead}});
    const DeclaringPass forward("forward", {}, VK_SHADER_STAGE_FRAGMENT_BIT);
    // Culling samples the depth only (the atlas is a fragment binding), before the shadow stage.
    const std::vector<const Pass*> frame = {&prepass, &culling, &shadows, &forward};
    EXPECT_EQ(imageUsesOf(culling, bound).size(), 1u);
    EXPECT_EQ(layoutProblem(frame, bound, restingLayouts(frame, bound)), "");
    // The forward pass before the shadow stage would sample a map no pass has made readable.
    const std::vector<const Pass*> early = {&prepass, &culling, &forward, &shadows};
    const std::string problem = layoutProblem(early, bound, restingLayouts(early, bound));
    EXPECT_NE(problem.find("pass 'forward' expects"), std::string::npos) << problem;
}

TEST(PassList, DebugFramesReplaceAPassByIdentityAndMemoryIsTotalledByKind) {
    PassList list;
    const Pass* depth = list.add<DeclaringPass>("depth", std::vector<ImageUse>{}, 0, 100);
    list.add<DeclaringPass>("culling", std::vector<ImageUse>{}, 0, 20, MemoryKind::LightGrid);
    const Pass* forward = list.add<DeclaringPass>("forward", std::vector<ImageUse>{}, 0, 0);
    list.add<DeclaringPass>("forward", std::vector<ImageUse>{}, 0, 0);  // a second pass of the same name
    list.add<DeclaringPass>("shadows", std::vector<ImageUse>{}, 0, 3000, MemoryKind::Shadows);
    EXPECT_EQ(list.names(), (std::vector<std::string>{"depth", "culling", "forward", "forward", "shadows"}));
    const DeclaringPass variant("forward", {});
    const std::array<const Pass*, 1> variants = {&variant};
    const std::vector<const Pass*> debug = list.frameReplacing(*forward, variants);
    ASSERT_EQ(debug.size(), 3u);
    EXPECT_EQ(debug[0], depth);
    EXPECT_EQ(debug[2], &variant);
    EXPECT_THROW(list.frameReplacing(variant, variants), InternalError);  // not a pass of the list
    EXPECT_EQ(list.memoryBytes(MemoryKind::Frame), 100u);
    EXPECT_EQ(list.memoryBytes(MemoryKind::LightGrid), 20u);
    EXPECT_EQ(list.memoryBytes(MemoryKind::Shadows), 3000u);
}

TEST(PassTimings, MediansPerPassAndTotal) {
    std::vector<PassTimings> frames;
    for (double ms : {3.0, 1.0, 2.0}) frames.push_back({{{"depth", ms}, {"forward", 10.0 * ms}}, 11.0 * ms});
    const PassTimings median = medianTimings(frames);
    EXPECT_EQ(median.of("depth"), 2.0);
    EXPECT_EQ(median.of("forward"), 20.0);
    EXPECT_EQ(median.of("tonemap"), 0.0);  // not in the frame
    EXPECT_EQ(median.total, 22.0);
    frames.pop_back();  // an even count: the mean of the middle two
    EXPECT_EQ(medianTimings(frames).of("depth"), 2.0);
    EXPECT_TRUE(medianTimings({}).passes.empty());
}

}  // namespace
}  // namespace punctual::render
