#pragma once
// A primary command buffer that frees itself: allocated from a pool, returned to it on
// destruction (move-only, like vk::Handle), so a thrown error never leaks one.
#include <utility>

#include <vulkan/vulkan.h>

namespace punctual::vk {

class CommandBuffer {
public:
    CommandBuffer() = default;
    CommandBuffer(VkDevice device, VkCommandPool pool);  // allocates
    ~CommandBuffer() { reset(); }
    CommandBuffer(const CommandBuffer&) = delete;
    CommandBuffer& operator=(const CommandBuffer&) = delete;
    CommandBuffer(CommandBuffer&& other) noexcept { *this = std::move(other); }
    CommandBuffer& operator=(CommandBuffer&& other) noexcept {
        if (this != &other) {
            reset();
            device_ = std::exchange(other.device_, VK_NULL_HANDLE);
            pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
            cmd_ = std::exchange(other.cmd_, VK_NULL_HANDLE);
        }
        return *this;
    }
    void reset();

    VkCommandBuffer get() const { return cmd_; }
    operator VkCommandBuffer() const { return cmd_; }  // NOLINT: implicit use in vkCmd* calls is the point
    explicit operator bool() const { return cmd_ != VK_NULL_HANDLE; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

// Submits `cmd` alone, signalling `fence` (reset first), and waits for it. A generous timeout
// turns a hung GPU into an error instead of a hung process.
void submitAndWait(VkDevice device, VkQueue queue, VkCommandBuffer cmd, VkFence fence);

}  // namespace punctual::vk
