#pragma once
// Every VkResult is checked: a failure becomes punctual::Error("vulkan", "<call>: <result>").
#include <string>

#include <vulkan/vulkan.h>

namespace punctual::vk {

const char* resultName(VkResult result);
void check(VkResult result, const char* call);

}  // namespace punctual::vk
