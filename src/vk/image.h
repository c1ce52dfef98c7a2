#pragma once
// A VkImage with its own memory and one view covering all its layers and mip levels (none for an
// image whose usage is transfers alone: view() is then VK_NULL_HANDLE).
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

namespace punctual::vk {

class Context;

struct ImageDesc {
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t layers = 1;
    uint32_t mipLevels = 1;
    VkImageUsageFlags usage = 0;
    VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;
    VkImageCreateFlags flags = 0;  // e.g. VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT
    std::string debugName;
};

class Image {
public:
    Image() = default;
    Image(const Context& context, const ImageDesc& desc);
    ~Image();
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;
    Image(Image&& other) noexcept;
    Image& operator=(Image&& other) noexcept;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    const ImageDesc& desc() const { return desc_; }
    VkImageAspectFlags aspect() const;
    VkDeviceSize allocatedBytes() const { return allocatedBytes_; }

private:
    void release();

    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkDeviceSize allocatedBytes_ = 0;
    ImageDesc desc_;
};

bool isDepthFormat(VkFormat format);

// One image layout transition with explicit stages and accesses (synchronization2-free so it runs
// on every Vulkan 1.2 driver). Covers all mips and layers of `image`.
void imageBarrier(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess);

// An execution + memory dependency for buffers and images already in the right layout.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

}  // namespace punctual::vk
