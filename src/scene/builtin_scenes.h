#pragma once
// The scenes punctual builds itself, chosen with `--scene NAME` (the first entry when neither a
// scene file nor --scene is given). One entry each: its name, its maker, the one line --help
// prints and, for a scene built to a size, its default size. Adding a scene is an entry here plus
// its maker and its test (docs/EXTENDING.md); parsing, the error that lists the names and --help
// all read this table (core/variant_table.h).
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/variant_table.h"
#include "scene/default_scene.h"
#include "scene/engine_scene.h"
#include "scene/outdoor_scene.h"
#include "scene/rooms_scene.h"
#include "scene/scene.h"
#include "scene/warehouse_scene.h"

namespace punctual {

struct BuiltinScene {
    // The maker (named `value` as in every variant table), given the triangle count to aim at:
    // --scene-triangles, else defaultTriangles. A scene of fixed size ignores it.
    Scene (*value)(uint64_t triangles);
    const char* name;
    const char* description;
    uint64_t defaultTriangles = 0;  // 0: a scene of fixed size, which --scene-triangles cannot size
    // A scene with a path (issue 34; scene/scene_path.h): poses it at a time, with a share of its
    // lights and of its props moving (--moving-lights, --moving-casters), and the path's length in
    // seconds. nullptr: a still scene, which --time cannot pose.
    void (*pose)(Scene& scene, double time, const PathMotion& motion) = nullptr;
    float pathSeconds = 0.0f;

    bool sized() const { return defaultTriangles != 0; }
    bool hasPath() const { return pose != nullptr; }
};

inline constexpr std::array<BuiltinScene, 5> kBuiltinScenes = {{
    {[](uint64_t) { return makeDefaultScene(); }, "hall",
     "a 40 m x 30 m hall of walls, pillars and crates, 96 lamps; a 12 s walk", 0, poseDefaultScene,
     default_scene::kWalkSeconds},
    {[](uint64_t) { return makeOutdoorScene(); }, "outdoor",
     "a street in low sun, casters 0.9 to 300 m away, 32 lamps; a 10 s drive", 0, poseOutdoorScene,
     outdoor_scene::kDriveSeconds},
    {makeRoomsScene, "rooms",
     "furnished rooms, 10^4 to 10^7 triangles (--scene-triangles), 96 lamps, a sun",
     rooms_scene::kDefaultTriangles},
    {[](uint64_t) { return makeWarehouseScene(); }, "warehouse",
     "8 x 8 rooms of racks behind doorways, seen from above, 4,096 lamps"},
    {[](uint64_t) { return makeEngineScene(); }, "engine",
     "an air-cooled engine of 6 mm fins, grille bars and pipes, 64 + 32 generated lamps"},
}};
static_assert(namesAreUnique(kBuiltinScenes));

// The scene used when neither a scene file nor --scene is given.
inline constexpr const BuiltinScene& kDefaultBuiltinScene = kBuiltinScenes[0];

// The entry named `name`. Throws Error("--scene", "expected hall, outdoor or rooms, got 'x'").
inline const BuiltinScene& parseBuiltinScene(const std::string& name) {
    return parseVariant(kBuiltinScenes, name, "--scene");
}

// Builds `scene` with `triangles` (a sized scene; none: its default size), posed at `time` seconds
// of its path where one is given, with `motion`'s shares of its lights and props moving (a scene
// without a path: an internal error, the command line refuses --time, --moving-lights and
// --moving-casters for it).
inline Scene makeBuiltinScene(const BuiltinScene& scene, std::optional<uint64_t> triangles = std::nullopt,
                              std::optional<double> time = std::nullopt,
                              const PathMotion& motion = {}) {
    Scene made = scene.value(triangles.value_or(scene.defaultTriangles));
    made.animationSeconds = double(scene.pathSeconds);
    if (time) {
        if (!scene.hasPath()) throw std::logic_error(std::string("built-in scene ") + scene.name + " has no path");
        scene.pose(made, *time, motion);
    }
    return made;
}

// Builds the scene named `name` (see parseBuiltinScene for an unknown name).
inline Scene makeBuiltinScene(const std::string& name, std::optional<uint64_t> triangles = std::nullopt) {
    return makeBuiltinScene(parseBuiltinScene(name), triangles);
}

}  // namespace punctual
