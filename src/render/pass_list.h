#pragma once
// The frame's passes in order (pass.h), owned here: the renderer adds them, and the list records a
// frame, times it, totals their memory and checks that neighbours agree on image layouts.
//
// Layouts: each pass declares the images it touches, the layout it needs each in when it starts
// and the one it leaves it in (Pass::imageUses; set 0's images, in their bindings' layouts, for a
// pass whose shaders sample them). checkImageLayouts walks a frame and fails, naming both passes,
// where a pass would find an image in another layout than it declared. A pass that expects a
// layout must find an earlier pass of the same frame leaving the image so (images start
// UNDEFINED, and a frame is submitted again and again, so it cannot lean on the last frame's
// end), and every frame recorded from the same passes (the debug variants) must leave each image
// in the layout the main frame leaves it in (its resting layout), so any frame may follow any.
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "render/pass.h"

namespace punctual::vk {
class GpuTimer;
class Image;
}  // namespace punctual::vk

namespace punctual::render {

// Where each image rests between frames: the layout the last pass to touch it leaves it in.
using ImageLayouts = std::map<const vk::Image*, VkImageLayout>;

class PassList {
public:
    // Adds a pass at the end of the frame and returns it.
    template <typename P, typename... Args>
    P* add(Args&&... args) {
        passes_.push_back(std::make_unique<P>(std::forward<Args>(args)...));
        return static_cast<P*>(passes_.back().get());
    }

    const std::vector<std::unique_ptr<Pass>>& passes() const { return passes_; }
    // Every pass, in frame order.
    std::vector<const Pass*> frame() const;
    // A debug frame: the passes before `replaced` (a pass of this list), then `variants` in its
    // place and nothing after it.
    std::vector<const Pass*> frameReplacing(const Pass& replaced, std::span<const Pass* const> variants) const;
    std::vector<std::string> names() const;
    // The device memory of the passes that report it as `kind`.
    uint64_t memoryBytes(MemoryKind kind) const;

    // Records `passes` in order into `frame.cmd`; with a timer, each timed pass in a scope under
    // its name, all of them in a scope named "total".
    static void record(const FrameContext& frame, std::span<const Pass* const> passes, vk::GpuTimer* timer);

private:
    std::vector<std::unique_ptr<Pass>> passes_;
};

// The images `pass` uses this frame: its own declaration, and those of set 0's images (`bound`)
// that the stages sampling them (Pass::boundImageStages) may read.
std::vector<ImageUse> imageUsesOf(const Pass& pass, std::span<const BoundImage> bound);

// The layouts `passes` leave the images they touch in.
ImageLayouts restingLayouts(std::span<const Pass* const> passes, std::span<const BoundImage> bound);

// Throws InternalError where a pass of `passes` would find an image in another layout than it
// expects, or where the frame leaves an image in another layout than `resting` (the main frame's
// restingLayouts) says.
void checkImageLayouts(std::span<const Pass* const> passes, std::span<const BoundImage> bound, const ImageLayouts& resting);

}  // namespace punctual::render
