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
// faces (redrawn every frame).
//
// Virtual pages (--shadow-res virtual): each marked page keeps its slot of a pool that outlives the
// frames (lights/shadow_page_pool_cache.h), and its depth while its signature holds
// (shadowPageSignature: its view's matrix, its level and place, and the casters that meet it). A
// light that moved redraws its pages; a caster that moved, the pages it met or meets. With pages
// the cascades are drawn every frame.
//
// Mixed (HDRP's mixed cached shadows; Unreal keeps static casters' pages apart too): a view with
// a moving caster inside it is drawn every frame that caster moves, but its static casters' depth
// is kept apart, in a second atlas of the views that have dynamic casters (its own buddy
// allocator, lights/shadow_atlas_cache.h), and copied into the drawing square before the dynamic
// casters are drawn over it. That equals drawing every caster, bit for bit: depth-only drawing
// keeps the nearest fragment whatever the order (the depth test is LESS and every caster writes
// depth alone, so each texel ends at the minimum of its fragments' depths, rounded to the format
// by a monotonic conversion). Which casters are dynamic is learned, not declared (glTF has no
// static flag): an object whose caster fingerprint (lights/shadow_view_signature.h) changed since
// it was last seen is dynamic from then on. Learning one costs its views' static depth once (it
// leaves their static set); a wrong guess costs time, never a texel, as the static signature
// covers exactly the casters kept apart.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/variant_table.h"
#include "lights/light_setup.h"
#include "lights/shadow_atlas_cache.h"
#include "lights/shadow_page_allocation.h"
#include "lights/shadow_page_pool_cache.h"
#include "lights/shadow_setup.h"
#include "render/shadow_maps.h"
#include "scene/scene.h"
#include "vk/image.h"

namespace punctual::vk {
class Context;
}

namespace punctual::render {

// --shadow-cache (punctual play): a table, so parsing, --help and the tests derive from it.
enum class ShadowCacheMode : uint32_t { Off, On, Redraw, Mixed };
struct ShadowCacheModeInfo {
    ShadowCacheMode value;
    const char* name;
    const char* description;
};
inline constexpr std::array<ShadowCacheModeInfo, 4> kShadowCacheModes = {{
    {ShadowCacheMode::Off, "off", "every frame packs its atlas afresh and draws every view"},
    {ShadowCacheMode::On, "on", "views keep their squares, and their depth while nothing in them moved"},
    // Where a square lies does not change its depth (each view is drawn at the drawing square's
    // origin and copied, render/shadow_pass.h) nor its lookups (in the view's own texels), so on
    // equals off and redraw bit for bit; redraw tells the cache's keeping from its placing.
    {ShadowCacheMode::Redraw, "redraw", "the squares of on, every view drawn (on, off and redraw give the same frames)"},
    {ShadowCacheMode::Mixed, "mixed",
     "as on, and views keep static casters' depth apart, drawing moving ones over it"},
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
    // Mixed: drawn views that drew their dynamic casters over their kept static depth (a subset of
    // drawnViews), those that drew and stored their static casters' depth first, the objects
    // learned dynamic so far, and the static atlas's texels.
    uint32_t overStaticViews = 0;
    uint32_t staticStoredViews = 0;
    uint32_t dynamicCasters = 0;
    uint64_t staticTexels = 0;
    // Virtual pages: the frame's pages kept and drawn, those that could have been kept (redraw:
    // drawn anyway), and the pool's slots for pages.
    uint32_t keptPages = 0;
    uint32_t drawnPages = 0;
    uint32_t keepablePages = 0;
    uint32_t pageSlots = 0;
    double checkMs = 0.0;       // CPU: fingerprints, signatures and placement
};

// How the shadow pass draws a view the cache does not keep.
enum class ViewDrawing : uint8_t {
    Whole,         // every caster over the far plane
    StoreStatic,   // mixed: the static casters, stored in the static atlas, then the dynamic ones
    OverStatic,    // mixed: the stored static depth, then the dynamic casters over it
};

class ShadowCache {
public:
    // For a sequence rendered with `settings` (the same every frame), in mode On, Redraw or Mixed.
    // Throws Error for Mixed with virtual pages.
    ShadowCache(const vk::Context& context, const ShadowSettings& settings, ShadowCacheMode mode = ShadowCacheMode::On);
    ShadowCache(const ShadowCache&) = delete;
    ShadowCache& operator=(const ShadowCache&) = delete;

    // Moves the plan's atlas views into the cache's atlas (plan.atlas, each view's rect and atlas
    // UV) and decides which keep their depth; makes the maps anew when their shape changed. One
    // renderer at a time: the last one given the cache must be gone (its frames done) first.
    void prepare(ShadowPlan& plan, const Scene& scene, const FrameLights& lights);

    // Virtual pages, once the marking frame has marked them: puts `allocation`'s pages in the pool
    // (their slots, the pool's place in plan.atlas: assignPageSlots, placeShadowPagePool), makes the
    // maps anew where the pool's shape changed, and returns per page whether it is drawn (false: it
    // keeps last frame's depth). `pageCasters` as shadowPageCasters gives them.
    std::vector<bool> placePages(ShadowPlan& plan, ShadowPageAllocation& allocation,
                                 const std::vector<std::vector<uint32_t>>& pageCasters, const Scene& scene,
                                 const FrameLights& lights);

    // Virtual pages: whether page `page` (of the allocation placePages last placed) kept its depth.
    bool keptPage(size_t page) const { return page < keptPages_.size() && keptPages_[page]; }

    const ShadowMaps& maps() const { return *maps_; }
    // Whether plan view `view` keeps last frame's depth (not cleared, not drawn).
    bool kept(uint32_t view) const { return view < kept_.size() && kept_[view]; }
    // The atlas's layout when this frame's shadow pass begins: UNDEFINED for maps made this frame,
    // else the one every frame leaves it in (ShadowPass::kReadLayout).
    VkImageLayout atlasLayoutBefore() const { return atlasLayoutBefore_; }
    // Mixed: how plan view `view` is drawn when not kept, its square in the static atlas (for
    // StoreStatic and OverStatic), and whether `object` is drawn as a dynamic caster.
    ViewDrawing drawing(uint32_t view) const { return view < drawing_.size() ? drawing_[view] : ViewDrawing::Whole; }
    const AtlasRect& staticRect(uint32_t view) const { return staticRects_.at(view); }
    bool dynamic(uint32_t object) const { return object < dynamic_.size() && dynamic_[object]; }
    // Mixed: the static atlas (none while no view has a dynamic caster), and its layout as the
    // frame begins: UNDEFINED when made this frame, else TRANSFER_SRC_OPTIMAL, where it rests
    // (ShadowPass reads it there and moves it to TRANSFER_DST_OPTIMAL only for each copy into it).
    const vk::Image* staticDepth() const { return staticDepth_ ? &*staticDepth_ : nullptr; }
    VkImageLayout staticLayoutBefore() const { return staticLayoutBefore_; }
    // Whether plan view `view` draws `object` this frame (not kept; over its static depth, only
    // the dynamic casters).
    bool draws(uint32_t view, uint32_t object) const {
        return !kept(view) && (drawing(view) != ViewDrawing::OverStatic || dynamic(object));
    }
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
    // Mixed: learns the dynamic casters from this frame's fingerprints, places the views with
    // dynamic casters in the static atlas and decides how each view is drawn.
    void prepareMixed(const ShadowPlan& plan, const std::vector<ShadowViewKey>& keys,
                      const std::vector<uint64_t>& fingerprints);
    void learnDynamicCasters(const std::vector<uint64_t>& fingerprints);
    // Makes the maps for `plan` where their shape changed (mapsMadeAnew_ says whether).
    void makeMapsFor(const ShadowPlan& plan);
    // Virtual pages, before the marking frame: the atlas grown to last frame's pool where it stands.
    void preparePagedFrame(ShadowPlan& plan);
    const vk::Context& context_;
    ShadowSettings settings_;
    bool keep_;  // On; Redraw places as On but keeps nothing
    bool mixed_;
    ShadowAtlasCache atlas_;
    std::optional<ShadowMaps> maps_;
    MapsShape shape_;
    std::vector<bool> kept_;
    VkImageLayout atlasLayoutBefore_ = VK_IMAGE_LAYOUT_UNDEFINED;
    ShadowCacheFrame frame_;
    ShadowAtlasCache staticAtlas_;
    std::optional<vk::Image> staticDepth_;
    VkImageLayout staticLayoutBefore_ = VK_IMAGE_LAYOUT_UNDEFINED;
    std::vector<uint64_t> knownFingerprints_;  // per object: its fingerprint when last drawn (0: never)
    std::vector<bool> dynamic_;                // per object: learned dynamic
    std::vector<ViewDrawing> drawing_;
    std::vector<AtlasRect> staticRects_;
    bool mapsMadeAnew_ = false;
    ShadowPagePoolCache pagePool_;
    std::vector<bool> keptPages_;  // per page of the last placePages
    glm::uvec2 pageSquares_{0u};  // this frame's cascades' squares, beside which the pool lies
};

}  // namespace punctual::render
