#include "render/pass_list.h"

#include <string_view>

#include "core/check.h"
#include "vk/gpu_timer.h"
#include "vk/image.h"

namespace punctual::render {
namespace {

std::string layoutName(VkImageLayout layout) {
    switch (layout) {
        case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
        case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
        case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "COLOR_ATTACHMENT_OPTIMAL";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return "DEPTH_STENCIL_ATTACHMENT_OPTIMAL";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return "DEPTH_STENCIL_READ_ONLY_OPTIMAL";
        case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY_OPTIMAL";
        case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC_OPTIMAL";
        case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST_OPTIMAL";
        default: return "layout " + std::to_string(int(layout));
    }
}

std::string imageName(const vk::Image* image) {
    const std::string& name = image->desc().debugName;
    return name.empty() ? "an unnamed image" : "the " + name + " image";
}

// Walks `passes` from new (UNDEFINED) images and fails at the first pass that finds an image in
// another layout than it expects; returns where the frame leaves each image.
ImageLayouts walkFrame(std::span<const Pass* const> passes, std::span<const BoundImage> bound) {
    ImageLayouts layouts;
    std::map<const vk::Image*, std::string> lastPass;
    for (const Pass* pass : passes) {
        for (const ImageUse& use : imageUsesOf(*pass, bound)) {
            const auto it = layouts.find(use.image);
            const VkImageLayout found = it == layouts.end() ? VK_IMAGE_LAYOUT_UNDEFINED : it->second;
            if (use.expects != VK_IMAGE_LAYOUT_UNDEFINED && found != use.expects) {
                const auto before = lastPass.find(use.image);
                const std::string source =
                    before == lastPass.end() ? "no pass (a new image is UNDEFINED)" : "pass '" + before->second + "'";
                throw InternalError(std::string("pass '") + pass->name() + "' expects " + imageName(use.image) + " in " +
                                    layoutName(use.expects) + ", but " + source + " leaves it in " + layoutName(found));
            }
            layouts[use.image] = use.leaves;
            lastPass[use.image] = pass->name();
        }
    }
    return layouts;
}

}  // namespace

std::vector<const Pass*> PassList::frame() const {
    std::vector<const Pass*> frame;
    for (const auto& pass : passes_) frame.push_back(pass.get());
    return frame;
}

std::vector<const Pass*> PassList::frameReplacing(const Pass& replaced, std::span<const Pass* const> variants) const {
    std::vector<const Pass*> frame;
    bool found = false;
    for (const auto& pass : passes_) {
        if (pass.get() == &replaced) {
            found = true;
            break;
        }
        frame.push_back(pass.get());
    }
    PUNCTUAL_CHECK(found, "a debug frame replaces a pass of the list");
    frame.insert(frame.end(), variants.begin(), variants.end());
    return frame;
}

std::vector<std::string> PassList::names() const {
    std::vector<std::string> names;
    for (const auto& pass : passes_) names.emplace_back(pass->name());
    return names;
}

uint64_t PassList::memoryBytes(MemoryKind kind) const {
    uint64_t bytes = 0;
    for (const auto& pass : passes_) {
        if (pass->memoryKind() == kind) bytes += pass->memoryBytes();
    }
    return bytes;
}

void PassList::record(const FrameContext& frame, std::span<const Pass* const> passes, vk::GpuTimer* timer) {
    if (timer) timer->reset(frame.cmd);
    const uint32_t total = timer ? timer->begin(frame.cmd, "total") : 0;
    for (const Pass* pass : passes) {
        if (timer && pass->timed()) {
            const uint32_t scope = timer->begin(frame.cmd, pass->name());
            pass->record(frame);
            timer->end(frame.cmd, scope);
        } else {
            pass->record(frame);
        }
    }
    if (timer) timer->end(frame.cmd, total);
}

std::vector<ImageUse> imageUsesOf(const Pass& pass, std::span<const BoundImage> bound) {
    std::vector<ImageUse> uses = pass.imageUses();
    for (const BoundImage& image : bound) {
        if ((image.stages & pass.boundImageStages()) != 0) uses.push_back(image.use);
    }
    return uses;
}

ImageLayouts restingLayouts(std::span<const Pass* const> passes, std::span<const BoundImage> bound) {
    ImageLayouts resting;
    for (const Pass* pass : passes) {
        for (const ImageUse& use : imageUsesOf(*pass, bound)) resting[use.image] = use.leaves;
    }
    return resting;
}

void checkImageLayouts(std::span<const Pass* const> passes, std::span<const BoundImage> bound, const ImageLayouts& resting) {
    // From new images: a pass that expects a layout must find a pass before it in the frame that
    // leaves the image so. (Walking from the resting layouts would add nothing: only an image's
    // first use sees where the walk started, and a first use that expects a layout already fails
    // here.)
    const ImageLayouts ends = walkFrame(passes, bound);
    for (const auto& [image, layout] : ends) {
        const auto it = resting.find(image);
        if (it != resting.end() && it->second != layout) {
            throw InternalError("a frame leaves " + imageName(image) + " in " + layoutName(layout) +
                                ", but the frame submitted after it starts from " + layoutName(it->second));
        }
    }
}

}  // namespace punctual::render
