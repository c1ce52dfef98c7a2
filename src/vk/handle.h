#pragma once
// RAII ownership of a Vulkan handle created from a device: move-only, destroyed with the
// matching vkDestroy* call. Handle<VkPipeline> and friends keep every object's lifetime in one
// place, so a thrown error anywhere in a pass's setup never leaks.
#include <utility>

#include <vulkan/vulkan.h>

namespace punctual::vk {

template <typename T>
using DestroyFn = void (*)(VkDevice, T, const VkAllocationCallbacks*);

template <typename T>
class Handle {
public:
    Handle() = default;
    Handle(VkDevice device, T handle, DestroyFn<T> destroy) : device_(device), handle_(handle), destroy_(destroy) {}
    ~Handle() { reset(); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& other) noexcept { *this = std::move(other); }
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            device_ = std::exchange(other.device_, VK_NULL_HANDLE);
            handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
            destroy_ = std::exchange(other.destroy_, nullptr);
        }
        return *this;
    }
    void reset() {
        if (handle_ != VK_NULL_HANDLE && destroy_) destroy_(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }
    T get() const { return handle_; }
    operator T() const { return handle_; }  // NOLINT: implicit use in vkCmd* calls is the point
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    T handle_ = VK_NULL_HANDLE;
    DestroyFn<T> destroy_ = nullptr;
};

}  // namespace punctual::vk
