#pragma once
// The stats JSON of a rendered frame and the timing table printed to stdout.
#include <string>

#include <nlohmann/json.hpp>

#include "render/renderer.h"

namespace punctual::app {

// {"gpu_ms": {depth, culling, shadows, forward, tonemap, total}, "lights": {spot, point,
//  directional, culled_by_frustum, dropped_by_cap, in_scene}, "frames", "size", "device", "scene"}
nlohmann::json frameStatsJson(const render::FrameResult& result, const render::Renderer& renderer,
                              const Scene& scene, const std::string& deviceName, uint32_t frames);

std::string timingTable(const render::PassTimings& ms);

}  // namespace punctual::app
