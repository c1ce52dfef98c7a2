#pragma once
// Small scenes built in code, each provoking one known failure of a light-culling or shadow
// method (the bench's failure study). All share a 20 x 20 m grey floor at y = 0 seen from
// (0, 3, 10) looking at the origin, unless a scene says otherwise.
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual::study {

Scene floorScene(const std::string& name);
// A box of `size` centred at `center` (mesh + object); call scene.computeBounds() when done.
void addBox(Scene& scene, const glm::vec3& center, const glm::vec3& size, uint32_t material = 0);
// A rectangle centred on `center` spanning +-halfU along `u` and +-halfV along `v` (unit axes),
// facing cross(u, v) (counter-clockwise seen from there), with texture coordinates 0..uvScale
// from the corner at -u -v, and TEXCOORD_1 = TEXCOORD_0 / 2. One object drawn with `material`.
void addQuad(Scene& scene, const std::string& name, glm::vec3 center, glm::vec3 u, glm::vec3 v, float halfU,
             float halfV, uint32_t material, float uvScale = 1.0f, const glm::mat4& model = glm::mat4(1.0f));
Light pointLight(const glm::vec3& position, float range, float intensity);
Light spotLight(const glm::vec3& position, const glm::vec3& direction, float range, float intensity, float innerAngle,
                float outerAngle);

// A spot and a point light low over an empty floor: light arrives at up to ~85 degrees from the
// normal (acne).
Scene grazingLightScene();
// Thin slabs lying just above the floor and a box standing on it, lit from above at an angle:
// the shadows start at the contact (peter-panning).
Scene contactCasterScene();
// A point light in a ring of pillars whose shadows cross its cube's face edges (seams).
Scene seamScene();
// A spot light above a long wall that crosses the light's near plane when it is pushed out
// (pancaking).
Scene pancakingScene();
// A spot above a floor with a box under it, cone half-angle `outerAngle` (towards 90 degrees).
Scene wideSpotScene(float outerAngle);
// A row of thin posts near the camera in front of a far floor, small lights on the posts and on
// the floor (tile depth discontinuities).
Scene postsScene();
// A large floor under `lightCount` overlapping point lights (per-object lists).
Scene largeFloorScene(int lightCount);
// The floor under `spotCount` spots and `pointCount` points, all in view (beyond the caps).
Scene manyLightsScene(int spotCount, int pointCount);
// A spot and a point light, both of range `range`, over a box, a post and a hanging slab. Every
// object lies within 18 m of both lights, so any range from 20 m up reaches the same geometry
// (shadow near and far planes fitted to the range rather than to the casters fail at long ones).
Scene longRangeScene(float range);
// longRangeScene(1e4) with far geometry in both lights' reach, none of it in the camera's view: a
// wall 3 km from the point light along +X, and a box 5 km down the spot's cone (under the floor).
// A shadow view whose near plane follows its far plane clips the near casters (issue 30).
Scene distantGeometryScene();

// The sun's cascades: a 400 m x 320 m field seen from 8 m up along it (looking 11 degrees down, so
// every cascade's range fills rows of the frame), posts of several heights from 1 m to 160 m away
// (each of four cascades over 160 m holds casters, and some straddle their splits), a wall and
// boxes, under a sun 35 degrees high shining across the view and towards the camera (shadows fall
// towards it, where the far cascades can see them). No other light.
Scene cascadeFieldScene();
// The sun's pancaking: a deck (85 m x 3 m, 0.5 m thick) `deckHeight` metres above the ground,
// across the view 5-8 m ahead of a camera at eye height, whose shadow falls on the ground under
// it, inside the first cascade. From about 4 m up the deck lies between the sun and the first
// cascade's sphere, in front of its near plane: pancaking keeps its shadow, clipping loses it.
Scene cascadePancakingScene(float deckHeight);
// The sun's cascade seams: rows of posts from 3 m to 180 m under a low sun behind the camera, whose
// long shadows fall away from it, across every split of the view. The seed's culling bias leaves the
// posts deep inside a cascade out of the next one, though their shadows reach into it.
Scene cascadeSeamScene();
// Transparency with tiled depth bounds: two glass panes (alphaMode BLEND, alpha 0.5 and 0.35,
// overlapping) 3 and 4.5 m from the camera, in front of a wall `wallDistance` metres behind the
// nearer pane, with small point lights (range 1.2 m) just in front of the panes. From about 2 m
// on those lights reach the glass but not the wall, so tiles bounded by the opaque depth alone
// lose them; one more light lights the wall.
Scene glassPanesScene(float wallDistance);
// The sun's light: travelling along `direction` (need not be unit), `lux` bright.
Light sunLight(const glm::vec3& direction, float lux);

}  // namespace punctual::study
