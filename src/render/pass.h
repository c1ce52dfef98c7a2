#pragma once
// The one interface every pass of a frame implements. The renderer keeps its passes in a list in
// frame order (pass_list.h), builds descriptor set 0 from the bindings they declare, and records
// and times each under its own name, so adding a pass is: its class, its binding numbers in
// gpu_types.h, and one line in the renderer's list (docs/EXTENDING.md). Each pass declares the
// images it touches and the layouts it finds and leaves them in, and the list checks that
// neighbours agree, so a pass is read from its own declaration alone.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace punctual::vk {
class Context;
class Image;
}

namespace punctual::render {

class BindingTable;
class FrameBindings;
class SceneGpu;

// One image a pass touches in a frame: the layout it needs the image in when it starts
// (VK_IMAGE_LAYOUT_UNDEFINED: any, as it discards the contents) and the layout it leaves it in.
struct ImageUse {
    const vk::Image* image;
    VkImageLayout expects;
    VkImageLayout leaves;
};

// An image of set 0, in the layout its binding reads it in, and the stages that may sample it.
struct BoundImage {
    ImageUse use;  // expects and leaves that layout
    VkShaderStageFlags stages;
};

// Where the statistics count a pass's device memory (DeviceMemory in renderer.h).
enum class MemoryKind { Frame, LightGrid, Shadows };

// What a pass records into: the frame's command buffer, its geometry and set 0.
struct FrameContext {
    VkCommandBuffer cmd;
    const SceneGpu& scene;
    const FrameBindings& bindings;
};

class Pass {
public:
    Pass() = default;
    virtual ~Pass() = default;
    Pass(const Pass&) = delete;
    Pass& operator=(const Pass&) = delete;

    // The name of the pass in timings, the stats JSON (gpu_ms.<name>), `punctual compare` and the
    // bench's <name>_ms columns.
    virtual const char* name() const = 0;

    // Adds the set-0 bindings of the resources this pass owns (called once, before the set is
    // built; the resources must exist by then, so passes create them in their constructors).
    virtual void addBindings(BindingTable& /*table*/) const {}

    // Creates the pipelines, which need set 0's layout (called once, after the set is built).
    virtual void createPipelines(const vk::Context& /*context*/, const FrameBindings& /*bindings*/) {}

    // Whether the pass has work this frame. A pass without (light culling under brute force, the
    // shadow stage with no shadowed light) is still recorded, since it may move its resources into
    // the layouts later passes expect, but it is not timed and reports 0 ms.
    virtual bool timed() const { return true; }

    // Records the pass, including the barriers that make its writes visible to the passes after
    // it.
    virtual void record(const FrameContext& frame) const = 0;

    // Device memory the pass owns (images and buffers), for the statistics, and where they count it.
    virtual uint64_t memoryBytes() const { return 0; }
    virtual MemoryKind memoryKind() const { return MemoryKind::Frame; }

    // The images the pass renders to, transitions or reads outside set 0 this frame, with the
    // layouts it finds and leaves them in (none for a pass without work that records nothing).
    virtual std::vector<ImageUse> imageUses() const { return {}; }
    // The stages of its shaders that sample set 0's images this frame (0: none): those images
    // that these stages may read must then be in the layouts their bindings name
    // (BindingTable::addImage).
    virtual VkShaderStageFlags boundImageStages() const { return 0; }
};

}  // namespace punctual::render
