#pragma once
// Fitting the shadow views' demanded tiers into a memory budget (--shadow-budget) and into the
// largest atlas the device can make.
//
// Each view asks for a power-of-two tier (shadow_resolution.h). While the atlas those tiers pack
// into (shadow_atlas.h) is larger than the budget or than the device's largest 2D image, the
// lights give up resolution in rounds: each round halves the views of one light at a time, from
// the least important light (light_setup.h's ranking) to the most important, checking after each
// light whether the atlas now fits. A view never goes below the smallest tier. The least important
// lights thus lose detail first, and no light loses more than one halving more than a more
// important one. Every view that got less than it asked for is listed: nothing is reduced
// silently.
#include <cstdint>
#include <string>
#include <vector>

#include "lights/shadow_atlas.h"

namespace punctual {

struct ShadowReduction {
    uint32_t view = 0;       // index in the plan's views
    uint32_t demanded = 0;   // tier asked for
    uint32_t granted = 0;    // tier given
};

struct ShadowAllocation {
    std::vector<uint32_t> resolutions;  // per view: texels a side, 0 for none
    AtlasLayout atlas;
    uint64_t bytes = 0;                 // the atlas's bytes
    std::vector<ShadowReduction> reductions;
    std::string limitName;              // what forced the reductions ("the budget of 64 MiB", ...)
};

struct ShadowBudgetLimits {
    uint64_t bytes = 0;          // the atlas may take at most this much
    std::string bytesName;       // e.g. "--shadow-budget 64", "the device's largest heap"
    uint32_t maxSide = 16384;    // the device's largest 2D image side (maxImageDimension2D)
    uint32_t texelBytes = 2;     // bytes per texel of the shadow format
    uint32_t minTier = 16;
};

// `demanded`: each view's tier (0 = nothing). `lightRank`: for each view, its light's rank, 0 the
// most important. Throws Error naming limits.bytesName when even the smallest tiers do not fit.
ShadowAllocation fitShadowBudget(const std::vector<uint32_t>& demanded, const std::vector<uint32_t>& lightRank,
                                 const ShadowBudgetLimits& limits);

// "20.0 GiB", "1.2 MiB", "80.0 KiB": the largest unit that shows the size as at least 0.1.
std::string describeBytes(uint64_t bytes);

}  // namespace punctual
