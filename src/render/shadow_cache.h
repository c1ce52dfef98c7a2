#pragma once
// Shadow caching (--shadow-cache on, issue 34): the shadow maps of a sequence, kept from frame to
// frame, and which views keep last frame's depth. Each frame's renderer is made anew (punctual
// play), so the cache outlives them: the renderer hands it its plan (prepare), the shadow pass
// draws only the views it does not keep, into the cache's maps.
//
// A view keeps its depth when its square did not move and its signature (lights/
// shadow_view_signature.h: its matrix, so its light's position and direction, its side, and its
// casters, each with its transform, geometry and alpha test) is last frame's: a light that moved
// redraws its own views only, a caster that moved or changed the views it was or is in. That is
// HDRP's "update on demand" decided per view, and Unreal's page invalidation per view.
//
// What is cached: the spot views and point slices in the atlas, and the sun's cascades while the
// camera and the casters stand still (their matrices follow the camera). Not the cube layout's
// faces (redrawn every frame), nor virtual pages (refused: their pool is allocated afresh from
// each frame's marks).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/variant_table.h"
#include "lights/light_setup.h"
#include "lights/shadow_atlas_cache.h"
#include "lights/shadow_setup.h"
#include "render/shadow_maps.h"
#include "scene/scene.h"

namespace punctual::vk {
class Context;
}

namespace punctual::render {

// --shadow-cache (punctual play): a table, so parsing, --help and the tests derive from it.
enum class ShadowCacheMode : uint32_t { Off, On, Redraw };
struct ShadowCacheModeInfo {
    ShadowCacheMode value;
    const char* name;
    const char* description;
};
inline constexpr std::array<ShadowCacheModeInfo, 3> kShadowCacheModes = {{
    {ShadowCacheMode::Off, "off", "every frame packs its atlas afresh and draws every view"},
    {ShadowCacheMode::On, "on", "views keep their squares, and their depth while nothing in them moved"},
    // Where a square lies does not change its depth (each view is drawn at the drawing square's
    // origin and copied, render/shadow_pass.h) nor its lookups (in the view's own texels), so on
    // equals off and redraw bit for bit; redraw tells the cache's keeping from its placing.
    {ShadowCacheMode::Redraw, "redraw", "the squares of on, every view drawn (on, off and redraw give the same frames)"},
}};
static_assert(valuesAreIndices(kShadowCacheModes) && namesAreUnique(kShadowCacheModes));

// What the cache did for the last frame.
struct ShadowCacheFrame {
    uint32_t keptViews = 0;     // rendered views whose depth was kept
    uint32_t drawnViews = 0;    // rendered views drawn
    uint32_t keepableViews = 0; // rendered views whose depth could have been kept (redraw: drawn anyway)
    bool laidOut = false;       // every view placed afresh (first frame, maps made anew, no block left)
    uint32_t movedViews = 0;    // views moved out of a block another needed (drawn, not kept)
    uint64_t atlasTexels = 0;   // the cache's atlas
    uint64_t packedTexels = 0;  // the frame's own packing (--shadow-cache off)
    double checkMs = 0.0;       // CPU: fingerprints, signatures and placement
};

class ShadowCache {
public:
    // For a sequence rendered with `settings` (the same every frame), in mode On or Redraw. Throws
    // Error for virtual pages.
    ShadowCache(const vk::Context& context, const ShadowSettings& settings, ShadowCacheMode mode = ShadowCacheMode::On);
    ShadowCache(const ShadowCache&) = delete;
    ShadowCache& operator=(const ShadowCache&) = delete;

    // Moves the plan's atlas views into the cache's atlas (plan.atlas, each view's rect and atlas
    // UV) and decides which keep their depth; makes the maps anew when their shape changed. One
    // renderer at a time: the last one given the cache must be gone (its frames done) first.
    void prepare(ShadowPlan& plan, const Scene& scene, const FrameLights& lights);

    const ShadowMaps& maps() const { return *maps_; }
    // Whether plan view `view` keeps last frame's depth (not cleared, not drawn).
    bool kept(uint32_t view) const { return view < kept_.size() && kept_[view]; }
    // The atlas's layout when this frame's shadow pass begins: UNDEFINED for maps made this frame,
    // else the one every frame leaves it in (ShadowPass::kReadLayout).
    VkImageLayout atlasLayoutBefore() const { return atlasLayoutBefore_; }
    const ShadowCacheFrame& lastFrame() const { return frame_; }

private:
    // What the maps' images are sized by: each made anew when its own changes (the atlas's
    // squares are kept only while the atlas is).
    struct MapsShape {
        uint32_t atlasWidth = 0;
        uint32_t atlasHeight = 0;
        uint32_t cubeResolution = 0;
        uint32_t shadowedPoints = 0;
        bool sameAtlas(const MapsShape& o) const { return atlasWidth == o.atlasWidth && atlasHeight == o.atlasHeight; }
        bool sameCubes(const MapsShape& o) const {
            return cubeResolution == o.cubeResolution && shadowedPoints == o.shadowedPoints;
        }
    };
    const vk::Context& context_;
    ShadowSettings settings_;
    bool keep_;  // On; Redraw places as On but keeps nothing
    ShadowAtlasCache atlas_;
    std::optional<ShadowMaps> maps_;
    MapsShape shape_;
    std::vector<bool> kept_;
    VkImageLayout atlasLayoutBefore_ = VK_IMAGE_LAYOUT_UNDEFINED;
    ShadowCacheFrame frame_;
};

}  // namespace punctual::render
