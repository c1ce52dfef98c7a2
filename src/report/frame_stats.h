#pragma once
// The stats JSON of a rendered frame and the timing table printed to stdout.
#include <string>

#include <nlohmann/json.hpp>

#include "lights/virtual_pages.h"
#include "render/renderer.h"

namespace punctual::report {

// {"gpu_ms": {<every pass by name, in frame order: depth, culling, shadows, forward, tonemap>, total}, "lights": {spot, point,
//  directional, culled_by_frustum, dropped_by_cap, in_scene}, "frames", "size", "device", "scene",
//  "triangles", "objects", "geometry": geometryStatsJson, "memory": {"peak_rss_bytes", "device_bytes"}}
nlohmann::json frameStatsJson(const render::FrameResult& result, const render::Renderer& renderer,
                              const Scene& scene, const std::string& deviceName, uint32_t frames);

// {"method", "tile_size", "slices", "tested_per_pixel", "affecting_per_pixel", "efficiency",
//  "max_tested", "max_affecting", "missed_energy", "pixels_missing_light", "covered_pixels",
//  "per_object": {"objects_over_cap", "max_candidates"}}
// The light lists' floor: the (cell, light) entries the grid holds (its set bits), times a 16-bit
// light index (every capacity's index fits 16 bits, PUNCTUAL_MAX_LIGHT_CAPACITY): what lists
// storing exactly their lights would take. Reads the grid back; 0 for the methods without one.
uint64_t lightGridFloorBytes(render::Renderer& renderer);
inline constexpr uint64_t kLightIndexBytes = 2;

nlohmann::json cullingStatsJson(const CullingStats& stats, const render::Renderer& renderer);

// {"enabled", "resolution", "filter", "samples", "penumbra", "bias", "strength", "point_layout",
//  "shadowed_spots", "shadowed_points", "dropped_by_cap", "views_rendered", "views_skipped",
//  "faces_rendered", "faces_skipped" (the same counts), "memory_bytes"}
nlohmann::json shadowStatsJson(const render::Renderer& renderer);

// What virtual shadow pages would cost on this frame (lights/virtual_pages.h), at the texel format's
// bytes: {"shaded_pairs", "floor_bytes", "atlas_bytes" (this frame's whole views: spots and point
// slices), "layouts": [{"virtual_size", "page_size", "levels", "pages_marked" (with the filter's
// reach), "pages_under_receivers" (without it), "pages_per_level",
// "views_with_pages", "physical_bytes", "page_table_bytes" (every level's, per view with pages),
// "used_levels_page_table_bytes" (the levels with pages only), "over_floor" ((physical + the used
// levels' table) / floor), "over_atlas", "pairs_coarser_than_asked"}]}
// Virtual shadow pages (--shadow-res virtual): pages marked, allocated, coarsened and drawn (per
// level where it says so), the draws, the pool's and the table's bytes, and the floor of
// `shadedPairs` (the frame's shaded (pixel, shadowed view) pairs) beside them.
nlohmann::json virtualPagesJson(const render::Renderer& renderer, uint64_t shadedPairs);

nlohmann::json virtualPageEstimateJson(const VirtualPageEstimate& estimate, const render::Renderer& renderer);

// {"triangles" (in the scene's buffers), "triangles_instanced" (each object's mesh once), "objects",
//  "objects_in_view", "camera_triangles", "camera_draws": {"depth", "forward", "transparent"},
//  "shadow_draws": {"total", "max_per_view"}, "shadow_triangles"}
nlohmann::json geometryStatsJson(const render::Renderer& renderer, const Scene& scene);

std::string timingTable(const render::PassTimings& ms);

// "lights: 64 spot, 32 point, 1 directional (12 outside the view, 3988 over the capacity,
// --max-lights 64,32)": the frame's lights, and the ones it dropped. Printed by render and
// reference.
std::string frameLightsLine(const FrameLights& lights, const LightCapacity& capacity);

// "lights over the capacity: 4000 dropped, 96 kept, the most important (--max-lights 64,32)",
// or "" when the frame kept every spot and point light in view. Printed by compare and validate
// (render and reference print frameLightsLine).
std::string droppedLightsLine(const render::Renderer& renderer);

// "lights without a shadow: 84 of 96 (84 over --shadowed 8,4, 0 cast none); the shadow figures
// count the shadowed only", or "" when every spot and point light of the frame has a shadow or
// shadows are off. Printed by render, compare and validate.
std::string unshadowedLightsLine(const render::Renderer& renderer);

}  // namespace punctual::report
