#pragma once
// The scenes punctual builds itself, chosen with `--scene NAME` (the first entry when neither a
// scene file nor --scene is given). One entry each: its name, its maker and the one line --help
// prints. Adding a scene is an entry here plus its maker and its test (docs/EXTENDING.md);
// parsing, the error that lists the names and --help all read this table (core/variant_table.h).
#include <array>
#include <string>

#include "core/variant_table.h"
#include "scene/default_scene.h"
#include "scene/outdoor_scene.h"
#include "scene/scene.h"

namespace punctual {

struct BuiltinScene {
    Scene (*value)();  // the maker (named `value` as in every variant table)
    const char* name;
    const char* description;
};

inline constexpr std::array<BuiltinScene, 2> kBuiltinScenes = {{
    {makeDefaultScene, "hall", "a 40 m x 30 m hall of walls, pillars and crates, 96 lamps"},
    {makeOutdoorScene, "outdoor", "a street in low sun, casters 0.9 to 300 m away, 32 lamps"},
}};
static_assert(namesAreUnique(kBuiltinScenes));

// The scene used when neither a scene file nor --scene is given.
inline constexpr const BuiltinScene& kDefaultBuiltinScene = kBuiltinScenes[0];

// The entry named `name`. Throws Error("--scene", "expected hall or outdoor, got 'x'").
inline const BuiltinScene& parseBuiltinScene(const std::string& name) {
    return parseVariant(kBuiltinScenes, name, "--scene");
}

// Builds the scene named `name` (see parseBuiltinScene for an unknown name).
inline Scene makeBuiltinScene(const std::string& name) { return parseBuiltinScene(name).value(); }

}  // namespace punctual
