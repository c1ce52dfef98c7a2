#include "vk/command_buffer.h"

#include <cstdint>

#include "vk/check.h"

namespace punctual::vk {

CommandBuffer::CommandBuffer(VkDevice device, VkCommandPool pool) : device_(device), pool_(pool) {
    VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    info.commandPool = pool;
    info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    info.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(device, &info, &cmd_), "vkAllocateCommandBuffers");
}

void CommandBuffer::reset() {
    if (cmd_ != VK_NULL_HANDLE) vkFreeCommandBuffers(device_, pool_, 1, &cmd_);
    cmd_ = VK_NULL_HANDLE;
}

void submitAndWait(VkDevice device, VkQueue queue, VkCommandBuffer cmd, VkFence fence) {
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    check(vkResetFences(device, 1, &fence), "vkResetFences");
    check(vkQueueSubmit(queue, 1, &submit, fence), "vkQueueSubmit");
    constexpr uint64_t kTimeoutNs = 600ull * 1000 * 1000 * 1000;
    check(vkWaitForFences(device, 1, &fence, VK_TRUE, kTimeoutNs), "vkWaitForFences");
}

}  // namespace punctual::vk
