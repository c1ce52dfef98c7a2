#pragma once
// A built-in scene's path (issue 34): where its camera and some of its lights are at each time of
// a sequence, as keyframe tracks (scene/keyframes.h) the way a glTF file animates its nodes. The
// camera follows an eye and a target (LINEAR tracks, the view built with lookAt, so no
// trigonometry enters and the path is the same on every platform); a moving light follows an
// offset from where the scene put it. At time 0 every track holds the scene's own values, so a
// scene posed at 0 is the still scene, bit for bit.
#include <cstdint>
#include <optional>
#include <vector>

#include "scene/keyframes.h"
#include "scene/scene.h"

namespace punctual {

struct LightPath {
    uint32_t light = 0;     // index into Scene::lights
    KeyframeTrack offset;   // 3 numbers a keyframe: metres from the light's own position
};

struct ObjectPath {
    uint32_t object = 0;    // index into Scene::objects
    KeyframeTrack offset;   // 3 numbers a keyframe: metres the object's placement moves
};

struct ScenePath {
    KeyframeTrack eye;      // 3 numbers a keyframe, world space
    KeyframeTrack target;
    std::vector<LightPath> lights;
    std::vector<ObjectPath> objects;
    double seconds = 0.0;   // the path's length: its last keyframe's time
};

// The lights that move when a share of them does (--moving-lights F): light floor(k / F) for
// k = 0, 1, ... below `lightCount`, so F = 1/6 moves lights 0, 6, 12, ..., F = 1/4 lights 0, 4, 8,
// ..., 1 all and 0 none. (A hair added before the floor keeps F = 0.1, which a double holds a
// little above a tenth, at lights 0, 10, 20.)
std::vector<uint32_t> movingLights(uint32_t lightCount, double share);

// What moves along a built-in scene's path besides its camera: a share of its lamps (--moving-lights;
// none given: the path's own) and a share of its props (--moving-casters; none by default).
struct PathMotion {
    std::optional<double> lights;
    double casters = 0.0;
};

// The props a share of which move (--moving-casters): the objects whose world bounds fit a
// kPropSide cube (crates, blocks, bollards; not floors, walls, pillars or buildings), in scene order.
inline constexpr float kPropSide = 4.0f;
std::vector<uint32_t> sceneProps(const Scene& scene);

// Adds to `path` (its `seconds` set) the lift of movingLights(props, share) of sceneProps(scene):
// each rises 1 m and sinks back twice, keyframes at every quarter of the path, as crates on a
// hoist: casters that move under lamps that stand still (the case HDRP's mixed cached shadows
// serve, render/shadow_cache.h).
void addLiftedProps(ScenePath& path, const Scene& scene, double share);

// Adds to `path` (its `seconds` set) the sway of movingLights(lightCount, share): each 1 m to +x
// and back, then 1 m to -x and back, keyframes at every quarter of the path, as hanging lamps in
// a draught: shadows that move while the walls stand still.
void addSwayingLights(ScenePath& path, uint32_t lightCount, double share);

// A LINEAR track of 3-number keyframes.
KeyframeTrack linearTrack(std::vector<float> times, const std::vector<glm::vec3>& values);

// Poses `scene` at `time` seconds along `path`: the camera looks from eye(time) at target(time)
// (y up, its far plane refitted just past the scene's bounds, as the built-in scenes fit it), and
// each moving light stands at its own position plus its offset(time), and each moving object's
// placement moves by its offset(time) (the scene's bounds refitted before the camera's far plane).
void applyScenePath(Scene& scene, const ScenePath& path, double time);

}  // namespace punctual
