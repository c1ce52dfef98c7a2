// The table of built-in scenes (--scene NAME): the hall is the default, every entry builds a
// valid scene of its own, and an unknown name fails with one line listing every name.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace punctual {
namespace {

TEST(BuiltinScenes, HallIsTheDefaultAndTheOthersAreListed) {
    EXPECT_STREQ(kDefaultBuiltinScene.name, "hall");
    EXPECT_EQ(variantNames(kBuiltinScenes), (std::vector<std::string>{"hall", "outdoor", "rooms", "warehouse", "engine"}));
    EXPECT_EQ(makeBuiltinScene(kDefaultBuiltinScene).source, default_scene::kSource);
    EXPECT_EQ(makeBuiltinScene("outdoor").source, outdoor_scene::kSource);
    EXPECT_EQ(makeBuiltinScene("rooms").source, rooms_scene::kSource);
    EXPECT_EQ(makeBuiltinScene("warehouse").source, warehouse_scene::kSource);
    EXPECT_EQ(makeBuiltinScene("engine").source, engine_scene::kSource);
    // Only the rooms are built to a size; the others ignore one.
    EXPECT_FALSE(kDefaultBuiltinScene.sized());
    EXPECT_FALSE(parseBuiltinScene("outdoor").sized());
    EXPECT_EQ(parseBuiltinScene("rooms").defaultTriangles, rooms_scene::kDefaultTriangles);
    EXPECT_EQ(makeBuiltinScene("hall", 20'000).triangleCount(), makeDefaultScene().triangleCount());
}

TEST(BuiltinScenes, EveryEntryBuildsAValidSceneOfItsOwn) {
    std::set<std::string> sources;
    for (const BuiltinScene& entry : kBuiltinScenes) {
        EXPECT_EQ(&parseBuiltinScene(entry.name), &entry);
        EXPECT_NE(std::string(entry.description), "") << entry.name;
        EXPECT_EQ(std::string(entry.description).find('\n'), std::string::npos) << entry.name;
        const Scene scene = makeBuiltinScene(entry.name);
        EXPECT_FALSE(scene.objects.empty()) << entry.name;
        EXPECT_FALSE(scene.lights.empty()) << entry.name;
        EXPECT_FALSE(scene.bounds.empty()) << entry.name;  // computeBounds() was called
        EXPECT_TRUE(scene.cameraFromFile) << entry.name;
        EXPECT_NO_THROW(validateLights(scene.lights, scene.source)) << entry.name;
        sources.insert(scene.source);  // names the scene in stats and messages
    }
    EXPECT_EQ(sources.size(), kBuiltinScenes.size());
}

TEST(BuiltinScenes, UnknownNameFailsWithOneLineListingTheNames) {
    for (const std::string name : {"nosuch", "", "Hall", "outdoor "}) {
        try {
            parseBuiltinScene(name);
            ADD_FAILURE() << "no error for '" << name << "'";
        } catch (const Error& error) {
            EXPECT_EQ(std::string(error.what()), "--scene: expected hall, outdoor, rooms, warehouse or engine, got '" + name + "'");
        }
    }
}

}  // namespace
}  // namespace punctual
