// Shadow caching (render/shadow_cache.h, issue 34): along the hall's walk with a quarter of its
// lamps swaying, the cache keeps exactly the views whose square, matrix and casters are last
// frame's (an oracle that compares the plans themselves, not their hashes), and its frames are
// bit for bit the uncached frames (each view drawn in its own packing's square) and those of the
// cache's squares all drawn, whatever the filter and with views drawn in tiles; a caster that
// moves redraws only the views it is or was in; mixed caching draws lifting crates over their
// views' kept static depth, bit for bit the uncached frames; and the command line refuses what it
// cannot cache, in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <optional>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/image.h"
#include "gpu_test_support.h"
#include "render/renderer.h"
#include "render/shadow_cache.h"
#include "report/sequence_report.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_path.h"

namespace punctual {
namespace {

using testing::cat;
using testing::quoted;

// What a view's depth is made of, compared whole: its square's side, its matrix's bits, its
// casters and each caster's model matrix and mesh.
struct ViewContents {
    uint32_t size = 0;
    glm::mat4 viewProjection{0.0f};
    std::vector<uint32_t> casters;
    std::vector<glm::mat4> models;
    std::vector<uint32_t> meshes;
    bool operator==(const ViewContents& o) const {
        return size == o.size && std::memcmp(&viewProjection, &o.viewProjection, sizeof(glm::mat4)) == 0 &&
               casters == o.casters && meshes == o.meshes &&
               std::memcmp(models.data(), o.models.data(), models.size() * sizeof(glm::mat4)) == 0 &&
               models.size() == o.models.size();
    }
};
using FrameContents = std::map<std::pair<uint32_t, uint32_t>, ViewContents>;  // by (scene light, face)

FrameContents contentsOf(const render::Renderer& renderer, const Scene& scene) {
    FrameContents contents;
    const ShadowPlan& plan = renderer.shadowPlan();
    for (const ShadowView& view : plan.views) {
        if (view.isCascade || !view.rendered()) continue;
        ViewContents c{view.rect.size, view.gpu.viewProjection, view.casters, {}, {}};
        for (const uint32_t object : view.casters) {
            c.models.push_back(scene.objects[object].model);
            c.meshes.push_back(scene.objects[object].mesh);
        }
        contents[{renderer.lights().sceneLightIndex[view.packedLight], view.face}] = c;
    }
    return contents;
}

// The views the oracle keeps: rendered now and last frame with the same contents, where the cache
// did not lay its atlas out afresh. Checks the cache kept exactly those, and returns how many.
size_t expectKeptAsTheOracleSays(const render::Renderer& renderer, const render::ShadowCache& cache,
                                 const FrameContents& before, const FrameContents& now) {
    size_t kept = 0;
    const ShadowPlan& plan = renderer.shadowPlan();
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        const ShadowView& view = plan.views[v];
        if (view.isCascade || !view.rendered()) continue;
        const std::pair<uint32_t, uint32_t> key{renderer.lights().sceneLightIndex[view.packedLight], view.face};
        const auto previous = before.find(key);
        const bool expected = !cache.lastFrame().laidOut && previous != before.end() && previous->second == now.at(key);
        EXPECT_EQ(cache.kept(v), expected) << "light " << key.first << " face " << key.second;
        kept += expected;
    }
    return kept;
}

Scene hallAt(double time, double movingShare, double movingCasters = 0.0) {
    return makeBuiltinScene(parseBuiltinScene("hall"), std::nullopt, time, {movingShare, movingCasters});
}

TEST(ShadowCache, TheWalkKeepsWhatTheOracleKeepsAndDrawsTheUncachedFrames) {
    auto context = testing::makeValidatedContext();
    const render::RenderSettings settings = testing::renderSettings(192, 108);
    render::ShadowCache keeping(*context, settings.shadows, render::ShadowCacheMode::On);
    render::ShadowCache redrawing(*context, settings.shadows, render::ShadowCacheMode::Redraw);
    FrameContents before;
    size_t kept = 0;
    size_t drawn = 0;
    for (const double time : {2.0, 2.25, 2.5, 2.75, 3.0}) {
        const Scene scene = hallAt(time, 0.25);
        render::Renderer cached(*context, scene, settings, &keeping);
        const ImageRgba8 image = cached.render().image;
        const FrameContents now = contentsOf(cached, scene);
        kept += expectKeptAsTheOracleSays(cached, keeping, before, now);
        drawn += keeping.lastFrame().drawnViews;
        EXPECT_EQ(keeping.lastFrame().keptViews + keeping.lastFrame().drawnViews, cached.shadowPlan().viewsRendered);
        before = now;
        render::Renderer all(*context, scene, settings, &redrawing);
        EXPECT_EQ(all.render().image.pixels, image.pixels) << "at " << time << " s";
        EXPECT_EQ(redrawing.lastFrame().keptViews, 0u);
        // Uncached: the frame's own packing, whose squares lie elsewhere (the cache's atlas keeps
        // last frame's places, and is larger).
        render::Renderer uncached(*context, scene, settings);
        EXPECT_EQ(uncached.render().image.pixels, image.pixels) << "at " << time << " s";
        EXPECT_NE(uncached.shadowPlan().atlas.texels(), cached.shadowPlan().atlas.texels());
    }
    EXPECT_GT(kept, 100u);  // most views keep their depth
    EXPECT_GT(drawn, 0u);   // and the swaying lamps' do not
    testing::expectNoValidationMessages(*context);
}

// One crate moves 0.4 m between two frames of a still camera and still lights: the views it was or
// is a caster of are drawn again, and only those.
TEST(ShadowCache, AMovingCasterRedrawsOnlyTheViewsItTouches) {
    auto context = testing::makeValidatedContext();
    const render::RenderSettings settings = testing::renderSettings(192, 108);
    render::ShadowCache cache(*context, settings.shadows);
    const Scene still = hallAt(1.0, 0.0);
    Scene moved = still;
    // The first object that some views draw and others do not.
    render::Renderer first(*context, still, settings, &cache);
    first.render();
    const FrameContents before = contentsOf(first, still);
    std::map<uint32_t, size_t> viewsOf;
    for (const auto& [key, c] : before) {
        for (const uint32_t object : c.casters) ++viewsOf[object];
    }
    uint32_t object = 0;
    for (const auto& [o, count] : viewsOf) {
        if (count >= 2 && count + 10 < before.size()) {
            object = o;
            break;
        }
    }
    ASSERT_GT(viewsOf[object], 0u);
    moved.objects[object].model = glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, 0.0f, 0.0f)) * moved.objects[object].model;
    moved.objects[object].worldBounds = moved.meshes[moved.objects[object].mesh].localBounds.transformed(moved.objects[object].model);
    render::Renderer second(*context, moved, settings, &cache);
    second.render();
    const FrameContents now = contentsOf(second, moved);
    ASSERT_FALSE(cache.lastFrame().laidOut);
    const size_t kept = expectKeptAsTheOracleSays(second, cache, before, now);
    size_t touched = 0;  // the views the crate is a caster of in either frame
    for (const auto& [key, c] : now) {
        const auto& was = before.count(key) ? before.at(key).casters : std::vector<uint32_t>{};
        touched += std::count(c.casters.begin(), c.casters.end(), object) > 0 || std::count(was.begin(), was.end(), object) > 0;
    }
    EXPECT_EQ(cache.lastFrame().drawnViews, touched);
    EXPECT_EQ(kept + touched, now.size());
    EXPECT_GE(touched, 2u);
    testing::expectNoValidationMessages(*context);
}

// Mixed caching along the walk with half the hall's props lifting and the lamps still: each frame
// equals the uncached frame bit for bit; the objects learned dynamic are moving props; and a view
// drawn over its kept static depth is one whose static part (its square's side, its matrix, its
// static casters and their placements) is last frame's, drawing its dynamic casters alone.
TEST(ShadowCache, MixedDrawsTheMovingCastersOverTheKeptStaticDepth) {
    auto context = testing::makeValidatedContext();
    const render::RenderSettings settings = testing::renderSettings(192, 108);
    render::ShadowCache mixed(*context, settings.shadows, render::ShadowCacheMode::Mixed);
    render::ShadowCache on(*context, settings.shadows, render::ShadowCacheMode::On);
    const Scene still = hallAt(0.0, 0.0);
    std::vector<uint32_t> movingProps;
    for (const uint32_t k : movingLights(uint32_t(sceneProps(still).size()), 0.5)) movingProps.push_back(sceneProps(still)[k]);
    FrameContents before;  // the static part of each view, last frame
    size_t overStatic = 0;
    uint64_t mixedDraws = 0;
    uint64_t onDraws = 0;
    for (const double time : {2.0, 2.25, 2.5, 2.75, 3.25}) {
        const Scene scene = hallAt(time, 0.0, 0.5);
        render::Renderer cached(*context, scene, settings, &mixed);
        const ImageRgba8 image = cached.render().image;
        render::Renderer uncached(*context, scene, settings);
        EXPECT_EQ(uncached.render().image.pixels, image.pixels) << "at " << time << " s";
        render::Renderer keeping(*context, scene, settings, &on);
        EXPECT_EQ(keeping.render().image.pixels, image.pixels) << "at " << time << " s";
        mixedDraws += cached.shadowDraws().total;
        onDraws += keeping.shadowDraws().total;
        for (uint32_t object = 0; object < scene.objects.size(); ++object) {
            if (mixed.dynamic(object)) {
                EXPECT_NE(std::find(movingProps.begin(), movingProps.end(), object), movingProps.end()) << object;
            }
        }
        // Each view's static part now, and the oracle for the views drawn over their static depth.
        FrameContents now;
        const ShadowPlan& plan = cached.shadowPlan();
        for (uint32_t v = 0; v < plan.views.size(); ++v) {
            const ShadowView& view = plan.views[v];
            if (view.isCascade || !view.rendered()) continue;
            ViewContents c{view.rect.size, view.gpu.viewProjection, {}, {}, {}};
            bool hasDynamic = false;
            for (const uint32_t object : view.casters) {
                hasDynamic = hasDynamic || mixed.dynamic(object);
                if (mixed.dynamic(object)) continue;
                c.casters.push_back(object);
                c.models.push_back(scene.objects[object].model);
                c.meshes.push_back(scene.objects[object].mesh);
            }
            const std::pair<uint32_t, uint32_t> key{cached.lights().sceneLightIndex[view.packedLight], view.face};
            now[key] = c;
            if (mixed.kept(v)) continue;
            const render::ViewDrawing drawing = mixed.drawing(v);
            EXPECT_EQ(drawing != render::ViewDrawing::Whole, hasDynamic) << "light " << key.first;
            if (drawing != render::ViewDrawing::OverStatic) continue;
            ++overStatic;
            EXPECT_TRUE(before.count(key) && before.at(key) == c) << "light " << key.first << " face " << key.second;
            for (const uint32_t object : view.casters) EXPECT_EQ(mixed.draws(v, object), mixed.dynamic(object));
        }
        before = now;
    }
    EXPECT_GT(mixed.lastFrame().dynamicCasters, 0u);
    EXPECT_GT(mixed.lastFrame().staticTexels, 0u);
    EXPECT_GT(overStatic, 50u);       // not vacuous: most views with a lifting crate keep their static depth
    EXPECT_LT(mixedDraws, onDraws);  // and draw fewer casters than whole views
    testing::expectNoValidationMessages(*context);
}

// play with the cache on, off and redrawn gives the same frames bit for bit: with the default
// filter (gathers of raw depths), with bilinear compares (receiver-plane compares off), with
// views of 2048 texels, drawn in 2 x 2 tiles of the drawing square, and with virtual pages. (At this size, views drawn in
// their squares and bilinear taps through the atlas's UV, as before the drawing square, differed
// in 4 and 5 of the 5 frames.)
TEST(ShadowCache, PlayCachedIsPlayUncachedBitForBit) {
    testing::TempFolder folder;
    const std::string common = " --scene hall --moving-lights 0.25 --fps 4 --seconds 1 --size 320x180 --save-frames --out-dir ";
    // The last also lifts half the props and caches their views mixed, those larger than the
    // drawing square included.
    const std::vector<std::string> configurations = {"", " --shadow-receiver-plane off", " --shadow-res 2048 --shadowed 2,1",
                                                     " --moving-casters 0.5 --shadow-res 2048 --shadowed 4,2",
                                                     " --shadow-res virtual"};
    for (size_t c = 0; c < configurations.size(); ++c) {
        const std::string& options = configurations[c];
        const bool lifting = options.find("--moving-casters") != std::string::npos;
        std::map<std::string, std::string> dirs;
        for (const char* mode : {"on", "off", "redraw", "mixed"}) {
            if (std::string(mode) == "mixed" && !lifting) continue;  // no dynamic caster: on's frames
            dirs[mode] = folder.file(cat(mode, "-", c));
            ASSERT_EQ(testing::runPunctual(folder, cat("play --shadow-cache ", mode, options, common, quoted(dirs[mode])))
                          .exitCode,
                      0)
                << options;
        }
        for (uint32_t i = 0; i < 5; ++i) {
            const std::string frame = report::frameImageName(i);
            const std::vector<uint8_t> on = readPng(dirs["on"] + "/" + frame).pixels;
            EXPECT_EQ(on, readPng(dirs["off"] + "/" + frame).pixels) << frame << options;
            EXPECT_EQ(on, readPng(dirs["redraw"] + "/" + frame).pixels) << frame << options;
            if (lifting) {
                EXPECT_EQ(on, readPng(dirs["mixed"] + "/" + frame).pixels) << frame << options;
            }
        }
        if (lifting) {  // not vacuous: views drew their lifting crates over their static depth
            const nlohmann::json mixed = nlohmann::json::parse(testing::readText(dirs["mixed"] + "/frames.json"));
            int overStatic = 0;
            for (const nlohmann::json& f : mixed["frames"]) overStatic += f["stats"]["shadows"]["cache"]["over_static_views"].get<int>();
            EXPECT_GT(overStatic, 0);
        }
        const nlohmann::json document = nlohmann::json::parse(testing::readText(dirs["on"] + "/frames.json"));
        EXPECT_EQ(document["settings"]["shadow_cache"], "on");
        EXPECT_EQ(document["frames"][0]["stats"]["shadows"]["cache"]["laid_out"], 1);
        // (With lifting crates, each of the 12 views has one in it, or a swaying lamp.)
        const bool paged = options.find("virtual") != std::string::npos;
        if (!lifting) {  // (virtual pages: no view is kept, pages are)
            EXPECT_GT(document["frames"][4]["stats"]["shadows"]["cache"][paged ? "kept_pages" : "kept_views"].get<int>(), 0)
                << options;
        }
        EXPECT_NE(testing::readText(dirs["on"] + "/frames.csv").find("shadow_cache_kept_views"), std::string::npos);
        if (options.find("2048") != std::string::npos) {
            // Not vacuous: the views are larger than the drawing square.
            const nlohmann::json& tiers = document["frames"][0]["stats"]["shadows"]["tiers"];
            EXPECT_GT(tiers["2048"].get<int>(), 0);
        }
    }
}

// The cube layout: its faces are drawn every frame, its spots kept. Where the shadowed points'
// count changes, the cube array alone is made anew (the shadow memory changes), the atlas and its
// kept squares stay, and the frames are still redraw's.
TEST(ShadowCache, ANewCubeArrayKeepsTheAtlas) {
    testing::TempFolder folder;
    const std::string common =
        " --scene hall --shadow-res 256 --point-shadow-layout cube --fps 2 --seconds 2 --size 96x54 --save-frames --out-dir ";
    const std::string on = folder.file("on");
    const std::string redraw = folder.file("redraw");
    ASSERT_EQ(testing::runPunctual(folder, cat("play --validate --shadow-cache on", common, quoted(on))).exitCode, 0);
    ASSERT_EQ(testing::runPunctual(folder, cat("play --shadow-cache redraw", common, quoted(redraw))).exitCode, 0);
    const nlohmann::json document = nlohmann::json::parse(testing::readText(on + "/frames.json"));
    size_t cubeArraysRemade = 0;
    for (size_t i = 0; i < document["frames"].size(); ++i) {
        const nlohmann::json& shadows = document["frames"][i]["stats"]["shadows"];
        EXPECT_EQ(shadows["cache"]["laid_out"], i == 0 ? 1 : 0) << "frame " << i;
        if (i > 0) {
            EXPECT_GT(shadows["cache"]["kept_views"].get<int>(), 0) << "frame " << i;
            const nlohmann::json& before = document["frames"][i - 1]["stats"]["shadows"];
            cubeArraysRemade += shadows["memory_bytes"] != before["memory_bytes"];
        }
        const std::string frame = report::frameImageName(uint32_t(i));
        EXPECT_EQ(readPng(on + "/" + frame).pixels, readPng(redraw + "/" + frame).pixels) << frame;
    }
    EXPECT_GT(cubeArraysRemade, 0u);  // the walk changes the shadowed points' count
}

TEST(ShadowCache, WhatCannotBeCachedIsRefusedInOneLine) {
    testing::TempFolder folder;
    const std::string dir = quoted(folder.file("out"));
    testing::expectOneClearError(testing::runPunctual(folder, "play --shadow-cache sometimes --out-dir " + dir),
                                 "play --shadow-cache sometimes", "--shadow-cache: expected off, on, redraw or mixed, got 'sometimes'");
    testing::expectOneClearError(
        testing::runPunctual(folder, "play --shadow-res virtual --shadow-cache mixed --seconds 1 --size 64x36 --out-dir " + dir),
        "play --shadow-res virtual --shadow-cache mixed", "--shadow-cache: mixed keeps whole views' static depth apart");
    testing::expectNothingLeftBehind(folder, "refused caches");
}

}  // namespace
}  // namespace punctual
