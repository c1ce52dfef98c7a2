#include "vk/gpu_timer.h"

#include "core/error.h"
#include "vk/check.h"
#include "vk/context.h"

namespace punctual::vk {

GpuTimer::GpuTimer(const Context& context, uint32_t maxScopes) : context_(context), maxScopes_(maxScopes) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = maxScopes * 2;
    VkQueryPool pool = VK_NULL_HANDLE;
    check(vkCreateQueryPool(context.device(), &info, nullptr, &pool), "vkCreateQueryPool");
    pool_ = Handle<VkQueryPool>(context.device(), pool, vkDestroyQueryPool);
}

void GpuTimer::reset(VkCommandBuffer cmd) {
    names_.clear();
    vkCmdResetQueryPool(cmd, pool_, 0, maxScopes_ * 2);
}

uint32_t GpuTimer::begin(VkCommandBuffer cmd, const std::string& name) {
    if (names_.size() >= maxScopes_) throw Error("vulkan", "too many GPU timer scopes (raise maxScopes)");
    const auto scope = uint32_t(names_.size());
    names_.push_back(name);
    // BOTTOM_OF_PIPE for the start too: the timestamp is written once all earlier commands are
    // done, so a scope measures its own work and not the tail of the previous pass.
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, scope * 2);
    return scope;
}

void GpuTimer::end(VkCommandBuffer cmd, uint32_t scope) {
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, scope * 2 + 1);
}

std::map<std::string, double> GpuTimer::resolveMilliseconds() const {
    std::map<std::string, double> result;
    if (names_.empty()) return result;
    std::vector<uint64_t> ticks(names_.size() * 2);
    check(vkGetQueryPoolResults(context_.device(), pool_, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
                                ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
    const uint64_t mask = context_.timestampMask();
    for (size_t i = 0; i < names_.size(); ++i) {
        const uint64_t start = ticks[i * 2] & mask;
        const uint64_t end = ticks[i * 2 + 1] & mask;
        const uint64_t elapsed = (end - start) & mask;  // wraps correctly within the valid bits
        result[names_[i]] += double(elapsed) * context_.timestampPeriodNs() * 1e-6;
    }
    return result;
}

}  // namespace punctual::vk
