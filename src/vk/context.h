#pragma once
// The headless Vulkan device: no window, no surface. Picks the best device present (discrete GPU,
// then integrated, virtual, CPU: lavapipe reports itself as a CPU device and is accepted), or
// the one `--device N` names. With validation on, every validation message is printed and
// counted; tests fail on any.
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/command_buffer.h"
#include "vk/handle.h"
#include "vk/object_cache.h"

namespace punctual::vk {

struct ContextOptions {
    bool validation = false;
    int deviceIndex = -1;  // -1: pick the best
    bool printValidationMessages = true;
};

// "discrete", "integrated", "virtual", "cpu" or "other".
const char* deviceTypeName(VkPhysicalDeviceType type);

struct DeviceInfo {
    uint32_t index = 0;
    std::string name;
    std::string type;  // "discrete", "integrated", "virtual", "cpu", "other"
    uint32_t apiVersion = 0;
    bool usable = false;
    std::string whyNotUsable;
};

class Context {
public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    VkCommandPool commandPool() const { return commandPool_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    const VkPhysicalDeviceFeatures& enabledFeatures() const { return enabledFeatures_; }
    // Vulkan 1.2's shaderOutputLayer (gl_Layer written by a vertex shader), enabled where present.
    bool shaderOutputLayer() const { return shaderOutputLayer_; }
    // The device's subgroup size, and whether compute shaders have the subgroup arithmetic
    // operations (subgroupMin, subgroupOr, ...: Vulkan 1.1 core, optional but near universal).
    uint32_t subgroupSize() const { return subgroupSize_; }
    bool computeSubgroupArithmetic() const { return computeSubgroupArithmetic_; }
    std::string deviceName() const { return properties_.deviceName; }
    // Nanoseconds per timestamp tick, and the mask of valid timestamp bits on our queue.
    double timestampPeriodNs() const { return double(properties_.limits.timestampPeriod); }
    uint64_t timestampMask() const { return timestampMask_; }

    uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const;

    // The device's render passes, layouts and pipelines, one per definition (vk/object_cache.h).
    // A cache: asking it for an object changes nothing any other caller sees, hence const.
    ObjectCache& objects() const { return *objects_; }

    // Allocates a primary command buffer, lets `record` fill it, submits and waits.
    template <typename Record>
    void submitAndWait(Record&& record) {
        const CommandBuffer cmd = beginOneShot();
        record(cmd.get());
        endOneShot(cmd);
    }

    // Validation messages seen so far (warnings and errors).
    size_t validationMessageCount() const;
    std::vector<std::string> validationMessages() const;
    bool validationEnabled() const { return validation_; }

    static std::vector<DeviceInfo> listDevices();

private:
    void release();
    CommandBuffer beginOneShot();
    void endOneShot(const CommandBuffer& cmd);
    static VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

    bool validation_ = false;
    bool printValidation_ = true;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    Handle<VkCommandPool> commandPool_;
    std::unique_ptr<ObjectCache> objects_;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceFeatures enabledFeatures_{};
    bool shaderOutputLayer_ = false;
    uint32_t subgroupSize_ = 1;
    bool computeSubgroupArithmetic_ = false;
    uint64_t timestampMask_ = ~0ull;

    mutable std::mutex messagesMutex_;
    std::vector<std::string> messages_;
};

}  // namespace punctual::vk
