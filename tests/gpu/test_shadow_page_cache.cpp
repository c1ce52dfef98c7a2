// Virtual pages cached (--shadow-cache on with --shadow-res virtual, render/shadow_cache.h): along
// the hall's walk with a quarter of its lamps swaying and a quarter of its props lifting, the cache
// keeps exactly the pages whose view matrix and casters (each caster's model matrix and mesh) are
// last frame's, an oracle that compares the plans themselves, not their hashes; and its frames are
// bit for bit the uncached frames (every page drawn, in the frame's own slots) and those of the
// cache's slots all drawn. Not vacuous: pages are kept, pages are drawn, and kept pages lie in
// other slots than the frame's own allocation gives them.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <tuple>
#include <vector>

#include "gpu_test_support.h"
#include "lights/shadow_page_allocation.h"
#include "render/renderer.h"
#include "render/shadow_cache.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_path.h"

namespace punctual {
namespace {

// What a page's depth is made of, compared whole: its view's matrix's bits, its casters and each
// caster's model matrix and mesh.
struct PageContents {
    glm::mat4 viewProjection{0.0f};
    std::vector<uint32_t> casters;
    std::vector<glm::mat4> models;
    std::vector<uint32_t> meshes;
    bool operator==(const PageContents& o) const {
        return std::memcmp(&viewProjection, &o.viewProjection, sizeof(glm::mat4)) == 0 && casters == o.casters &&
               meshes == o.meshes && models.size() == o.models.size() &&
               std::memcmp(models.data(), o.models.data(), models.size() * sizeof(glm::mat4)) == 0;
    }
};
using PageKey = std::tuple<uint32_t, uint32_t, uint32_t, uint32_t, uint32_t>;  // light, face, level, column, row

// Per page of the renderer's allocation, in its order: its key and contents.
std::vector<std::pair<PageKey, PageContents>> pagesOf(const render::Renderer& renderer, const Scene& scene) {
    const ShadowPlan& plan = renderer.shadowPlan();
    const ShadowPageAllocation& allocation = renderer.shadowPages();
    const std::vector<std::vector<uint32_t>> casters = shadowPageCasters(scene, plan, allocation);
    std::vector<std::pair<PageKey, PageContents>> pages;
    for (size_t i = 0; i < allocation.pages.size(); ++i) {
        const ShadowPage& page = allocation.pages[i];
        const ShadowView& view = plan.views[page.view];
        PageContents contents{view.gpu.viewProjection, casters[i], {}, {}};
        for (const uint32_t object : casters[i]) {
            contents.models.push_back(scene.objects[object].model);
            contents.meshes.push_back(scene.objects[object].mesh);
        }
        const PageKey key{renderer.lights().sceneLightIndex[view.packedLight], view.face, page.level, page.column, page.row};
        pages.emplace_back(key, std::move(contents));
    }
    return pages;
}

TEST(ShadowPageCache, TheWalkKeepsThePagesTheOracleKeepsAndDrawsTheUncachedFrames) {
    auto context = testing::makeValidatedContext();
    render::RenderSettings settings = testing::renderSettings(192, 108);
    settings.shadows.resolution = ShadowSettings::kVirtualResolution;
    render::ShadowCache keeping(*context, settings.shadows, render::ShadowCacheMode::On);
    render::ShadowCache redrawing(*context, settings.shadows, render::ShadowCacheMode::Redraw);
    std::map<PageKey, PageContents> before;
    size_t kept = 0;
    size_t drawn = 0;
    size_t keptElsewhere = 0;  // kept pages whose slot is not the one the frame's own allocation gives
    for (const double time : {2.0, 2.25, 2.5, 2.75, 3.0}) {
        const Scene scene = makeBuiltinScene(parseBuiltinScene("hall"), std::nullopt, time, {0.25, 0.25});
        render::Renderer cached(*context, scene, settings, &keeping);
        const ImageRgba8 image = cached.render().image;
        const std::vector<std::pair<PageKey, PageContents>> now = pagesOf(cached, scene);
        const render::ShadowCacheFrame& frame = keeping.lastFrame();
        for (size_t i = 0; i < now.size(); ++i) {
            const auto previous = before.find(now[i].first);
            const bool expected = !frame.laidOut && previous != before.end() && previous->second == now[i].second;
            EXPECT_EQ(keeping.keptPage(i), expected) << "page " << i << " at " << time << " s";
            kept += expected;
            keptElsewhere += expected && cached.shadowPages().slotOfPage[i] != i;
        }
        drawn += frame.drawnPages;
        EXPECT_EQ(frame.keptPages + frame.drawnPages, now.size());
        before.clear();
        for (const auto& [key, contents] : now) before[key] = contents;

        render::Renderer all(*context, scene, settings, &redrawing);
        EXPECT_EQ(all.render().image.pixels, image.pixels) << "at " << time << " s";
        EXPECT_EQ(redrawing.lastFrame().keptPages, 0u);
        render::Renderer uncached(*context, scene, settings);
        EXPECT_EQ(uncached.render().image.pixels, image.pixels) << "at " << time << " s";
    }
    EXPECT_GT(kept, 1000u);         // most pages keep their depth
    EXPECT_GT(drawn, kept / 100);   // the swaying lamps' and the lifting crates' do not
    EXPECT_GT(keptElsewhere, 0u);   // and the slots are the pool's, not the frame's
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
