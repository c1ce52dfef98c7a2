#pragma once
// Per-pass GPU times from timestamp queries. Scopes are named and get their query slots in the
// order they are opened, so no pass owns a hard-coded slot.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/handle.h"

namespace punctual::vk {

class Context;

class GpuTimer {
public:
    GpuTimer(const Context& context, uint32_t maxScopes);

    // Resets the pool; call once per recorded frame before any scope.
    void reset(VkCommandBuffer cmd);
    // Opens a scope (timestamp after all earlier work) and returns its id.
    uint32_t begin(VkCommandBuffer cmd, const std::string& name);
    void end(VkCommandBuffer cmd, uint32_t scope);
    // Reads back after the frame's fence: milliseconds per scope name (scopes of the same name add).
    std::map<std::string, double> resolveMilliseconds() const;

private:
    const Context& context_;
    Handle<VkQueryPool> pool_;
    uint32_t maxScopes_ = 0;
    std::vector<std::string> names_;
};

}  // namespace punctual::vk
