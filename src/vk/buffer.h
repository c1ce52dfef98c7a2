#pragma once
// A VkBuffer with its own memory. Sized by the caller to what the frame really holds.
#include <cstddef>
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

namespace punctual::vk {

class Context;

enum class MemoryUse {
    DeviceLocal,  // filled by transfers (upload through a staging buffer)
    Upload,       // host-visible, coherent: written by the CPU every frame
    Readback,     // host-visible, cached if possible: read by the CPU
};

class Buffer {
public:
    Buffer() = default;
    Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse memoryUse,
           const std::string& debugName);
    ~Buffer();
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    Buffer(Buffer&& other) noexcept;
    Buffer& operator=(Buffer&& other) noexcept;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }  // non-null for Upload and Readback
    // Writes `bytes` at `offset` into a mapped buffer; invalidates/flushes are not needed because
    // Upload memory is coherent.
    void write(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
    // Makes device writes visible to the host for Readback memory that is not coherent.
    void invalidate();

private:
    void release();

    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
    bool coherent_ = true;
};

// Copies `bytes` into a DeviceLocal buffer through a temporary staging buffer and waits.
void uploadToBuffer(Context& context, const Buffer& destination, const void* data, VkDeviceSize bytes);

}  // namespace punctual::vk
