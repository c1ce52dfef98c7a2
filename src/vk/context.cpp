#include "vk/context.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "vk/check.h"

namespace punctual::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasLayer(const char* name) {
    uint32_t count = 0;
    check(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
    std::vector<VkLayerProperties> layers(count);
    check(vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool hasInstanceExtension(const char* name) {
    uint32_t count = 0;
    check(vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr), "vkEnumerateInstanceExtensionProperties");
    std::vector<VkExtensionProperties> extensions(count);
    check(vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data()),
          "vkEnumerateInstanceExtensionProperties");
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

VkInstance createInstance(bool validation, bool withPortability) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "punctual";
    app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    app.pEngineName = "punctual";
    app.apiVersion = VK_API_VERSION_1_2;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (validation) {
        if (!hasLayer(kValidationLayer)) {
            throw Error("vulkan", "validation requested but VK_LAYER_KHRONOS_validation is not installed "
                                  "(apt-get install vulkan-validationlayers)");
        }
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    if (withPortability) {
        // Lets the loader list portability drivers (MoltenVK) too; harmless elsewhere.
        extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
        info.flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
    }
    info.pApplicationInfo = &app;
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
    return instance;
}

}  // namespace

const char* deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        default: return "other";
    }
}

namespace {

// Higher is better. A CPU device (lavapipe) is a valid last choice, never skipped.
int typeScore(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
        default: return 0;
    }
}

// The queue family that does graphics and compute and has timestamps; UINT32_MAX when none.
uint32_t pickQueueFamily(VkPhysicalDevice device, std::string& whyNot) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need) {
            if (families[i].timestampValidBits == 0) {
                whyNot = "its graphics queue has no timestamps";
                continue;
            }
            return i;
        }
    }
    if (whyNot.empty()) whyNot = "no queue does both graphics and compute";
    return UINT32_MAX;
}

std::vector<VkPhysicalDevice> enumerateDevices(VkInstance instance) {
    uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
    return devices;
}

DeviceInfo describe(VkPhysicalDevice device, uint32_t index) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(device, &props);
    DeviceInfo info;
    info.index = index;
    info.name = props.deviceName;
    info.type = deviceTypeName(props.deviceType);
    info.apiVersion = props.apiVersion;
    if (props.apiVersion < VK_API_VERSION_1_2) {
        info.whyNotUsable = "needs Vulkan 1.2";
    } else if (pickQueueFamily(device, info.whyNotUsable) != UINT32_MAX) {
        info.usable = true;
    }
    return info;
}

}  // namespace

std::vector<DeviceInfo> Context::listDevices() {
    VkInstance instance = createInstance(false, hasInstanceExtension(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME));
    std::vector<DeviceInfo> infos;
    const auto devices = enumerateDevices(instance);
    for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
    vkDestroyInstance(instance, nullptr);
    return infos;
}

namespace {

// The device --device N names (refused when unusable, with the reason), else the usable one of the
// best type (discrete, integrated, virtual, CPU).
size_t chooseDevice(const std::vector<VkPhysicalDevice>& devices, int deviceIndex) {
    if (deviceIndex >= 0) {
        if (deviceIndex >= int(devices.size())) {
            throw Error("--device", "no device " + std::to_string(deviceIndex) + " (found " +
                                        std::to_string(devices.size()) + ", see `punctual devices`)");
        }
        const DeviceInfo info = describe(devices[size_t(deviceIndex)], uint32_t(deviceIndex));
        if (!info.usable) throw Error("--device", "device " + std::to_string(deviceIndex) + " (" + info.name +
                                                      ") is not usable: " + info.whyNotUsable);
        return size_t(deviceIndex);
    }
    int chosen = -1;
    int bestScore = -1;
    for (uint32_t i = 0; i < devices.size(); ++i) {
        const DeviceInfo info = describe(devices[i], i);
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        const int score = typeScore(props.deviceType);
        if (info.usable && score > bestScore) {
            bestScore = score;
            chosen = int(i);
        }
    }
    if (chosen < 0) throw Error("vulkan", "no usable Vulkan 1.2 device with graphics, compute and timestamps");
    return size_t(chosen);
}

// The subgroup size, and whether compute shaders have subgroup arithmetic (the one-subgroup tile kernels).
void readSubgroupSupport(VkPhysicalDevice device, uint32_t& size, bool& computeArithmetic) {
    VkPhysicalDeviceSubgroupProperties subgroup{};
    subgroup.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES;
    VkPhysicalDeviceProperties2 properties2{};
    properties2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    properties2.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(device, &properties2);
    size = std::max(subgroup.subgroupSize, 1u);
    computeArithmetic = (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) != 0 &&
                        (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT) != 0;
}

// The bits of a timestamp the queue family's timestamps fill.
uint64_t timestampMaskOf(VkPhysicalDevice device, uint32_t family) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    const uint32_t bits = families[family].timestampValidBits;
    return bits >= 64 ? ~0ull : ((1ull << bits) - 1ull);
}

}  // namespace

Context::Context(const ContextOptions& options)
    : validation_(options.validation), printValidation_(options.printValidationMessages) {
    instance_ = createInstance(validation_, hasInstanceExtension(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME));
    try {
        if (validation_) {
            VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
            info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
            info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
            info.pfnUserCallback = &Context::onValidationMessage;
            info.pUserData = this;
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
            if (!create) throw Error("vulkan", "VK_EXT_debug_utils is not available");
            check(create(instance_, &info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
        }

        const auto devices = enumerateDevices(instance_);
        if (devices.empty()) throw Error("vulkan", "no Vulkan device found (apt-get install mesa-vulkan-drivers)");
        physicalDevice_ = devices[chooseDevice(devices, options.deviceIndex)];
        vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
        readSubgroupSupport(physicalDevice_, subgroupSize_, computeSubgroupArithmetic_);
        std::string ignored;
        queueFamily_ = pickQueueFamily(physicalDevice_, ignored);
        timestampMask_ = timestampMaskOf(physicalDevice_, queueFamily_);

        // Enable only the optional features the passes use, where present.
        VkPhysicalDeviceFeatures supported;
        vkGetPhysicalDeviceFeatures(physicalDevice_, &supported);
        enabledFeatures_.imageCubeArray = supported.imageCubeArray;
        enabledFeatures_.shaderSampledImageArrayDynamicIndexing = supported.shaderSampledImageArrayDynamicIndexing;
        enabledFeatures_.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
        enabledFeatures_.depthClamp = supported.depthClamp;
        enabledFeatures_.depthBiasClamp = supported.depthBiasClamp;
        // Virtual shadow pages draw each page into its own layer of an array (gl_Layer from the
        // vertex shader: Vulkan 1.2's shaderOutputLayer), so that every page is rasterized at the
        // same origin wherever its slot lies (render/shadow_page_layers.h).
        VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        VkPhysicalDeviceFeatures2 supported2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        supported2.pNext = &supported12;
        vkGetPhysicalDeviceFeatures2(physicalDevice_, &supported2);
        VkPhysicalDeviceVulkan12Features enabled12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        enabled12.shaderOutputLayer = supported12.shaderOutputLayer;
        shaderOutputLayer_ = supported12.shaderOutputLayer == VK_TRUE;

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queueInfo.queueFamilyIndex = queueFamily_;
        queueInfo.queueCount = 1;
        queueInfo.pQueuePriorities = &priority;
        VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        deviceInfo.queueCreateInfoCount = 1;
        deviceInfo.pQueueCreateInfos = &queueInfo;
        deviceInfo.pEnabledFeatures = &enabledFeatures_;
        deviceInfo.pNext = &enabled12;
        check(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_), "vkCreateDevice");
        vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        poolInfo.queueFamilyIndex = queueFamily_;
        VkCommandPool pool = VK_NULL_HANDLE;
        check(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool), "vkCreateCommandPool");
        commandPool_ = Handle<VkCommandPool>(device_, pool, vkDestroyCommandPool);
        objects_ = std::make_unique<ObjectCache>(device_);
    } catch (...) {
        release();
        throw;
    }
}

Context::~Context() { release(); }

void Context::release() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        objects_.reset();
        commandPool_.reset();
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    device_ = VK_NULL_HANDLE;
    messenger_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
}

uint32_t Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const {
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memory);
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & required) == required) return i;
    }
    throw Error("vulkan", "no memory type with the required properties");
}

CommandBuffer Context::beginOneShot() {
    CommandBuffer cmd(device_, commandPool_);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    return cmd;
}

void Context::endOneShot(const CommandBuffer& cmd) {
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence rawFence = VK_NULL_HANDLE;
    check(vkCreateFence(device_, &fenceInfo, nullptr, &rawFence), "vkCreateFence");
    const Handle<VkFence> fence(device_, rawFence, vkDestroyFence);
    try {
        vk::submitAndWait(device_, queue_, cmd, fence);
    } catch (...) {
        vkDeviceWaitIdle(device_);  // the command buffer and fence are freed on the way out
        throw;
    }
}

size_t Context::validationMessageCount() const {
    std::lock_guard lock(messagesMutex_);
    return messages_.size();
}

std::vector<std::string> Context::validationMessages() const {
    std::lock_guard lock(messagesMutex_);
    return messages_;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                             VkDebugUtilsMessageTypeFlagsEXT,
                                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                             void* user) {
    auto* self = static_cast<Context*>(user);
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    const std::string message = std::string(level) + ": " + (data && data->pMessage ? data->pMessage : "");
    {
        std::lock_guard lock(self->messagesMutex_);
        self->messages_.push_back(message);
    }
    if (self->printValidation_) std::fprintf(stderr, "punctual: validation %s\n", message.c_str());
    return VK_FALSE;
}

}  // namespace punctual::vk
