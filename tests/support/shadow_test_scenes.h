#pragma once
// Scenes built in code for the shadow tests, each aimed at one way shadow maps go wrong (acne on
// grazing receivers, cube-face seams, very wide spots, casters nearer than the near plane), and
// counting a validation's verdicts. CPU only: the CPU tests plan shadows for these scenes, the
// GPU tests (tests/gpu/shadow_test_runs.h) render them.
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "reference/shadow_validation.h"
#include "scene/scene.h"

namespace punctual::testing {

// Pixels of one light with the given verdict; `outsideBandOnly` skips the edge band.
size_t countVerdicts(const reference::LightShadowValidation& light, reference::PixelVerdict verdict,
                     bool outsideBandOnly = false);
// Pixels with `verdict` over every shadowed light of one type.
size_t countVerdicts(const reference::ShadowValidation& validation, bool points, reference::PixelVerdict verdict);

// Angle (radians) between a surface's unit normal and the direction from `position` to the light.
float angleToLight(const glm::vec3& position, const glm::vec3& normal, const glm::vec3& lightPosition);

// A 40 x 40 m floor (a 0.2 m thick box, top at y = 0) and nothing else, seen from above. Lights
// are added by the caller (call computeBounds() again after adding objects).
Scene emptyFloorScene();

// The empty floor seen straight down from 10 m with a 90-degree field of view: in a
// kFloorFrame x kFloorFrame frame every visible floor point is 10 m deep along the camera's axis,
// so one pixel there spans 10 x 2 tan 45 / 512 = 20 / 512 = 0.0390625 m (kFloorPixel), and pixel
// (x, y) sees the floor point ((x + 0.5) kFloorPixel - 10, 0, (y + 0.5) kFloorPixel - 10).
Scene floorSeenFromAbove();
constexpr uint32_t kFloorFrame = 512;
constexpr float kFloorPixel = 20.0f / 512.0f;

// Acne: the empty floor lit by one light `height` metres above it (a point at the origin's
// vertical, or a spot at the same place tilted so that its cone meets the floor at 15 to 85
// degrees from the normal). Light reaches the floor at up to atan(5.7) = 80 degrees well inside
// the frame.
Scene grazingFloorScene(bool spot);
constexpr float kGrazingLightHeight = 1.0f;

// A point light 2 m above a floor, inside a ring of posts and under a few hanging boxes, with
// two walls: the shadows fall on the floor and the walls across five cube faces, and the posts'
// shadow edges cross the face seams (the square |x| = |z| = 2 on the floor and the diagonals
// beyond it).
//
// `lampCap`: a small plate 0.28 m above the light (a lamp's cap, shadowing only the sky). Being
// the nearest caster, it keeps the plan's near plane at 0.25 m. Without it the nearest casters are
// 1.1 m away, the near plane is at 1 m along each face's axis, and the off-axis parts of posts and
// boxes nearer than that along the axis are clipped out of the shadow map (the renderer bug that
// ShadowNearPlane shows). The layout and seam tests use the cap so that they measure layouts and
// seams, not that bug.
Scene pointAmongOccludersScene(bool lampCap);
constexpr float kOccludedPointHeight = 2.0f;

// A spot 1 m above the floor pointing straight down with the given outer cone angle, a box
// under it (shadow inside 80 degrees) and a tall box beside it whose top half is seen at more
// than 80 degrees from the axis (its shadow falls in the rim the shadow map does not cover).
// `bracket`: a 4 cm cube 0.15 m below the light, on its axis (a lamp's lens holder): as the
// nearest caster, and on the axis where the straight-line distance is the depth, it keeps the near
// plane at 0.12 m, clear of the near-plane bug (see pointAmongOccludersScene). Its own shadow is
// a 0.3 m disc under the light.
Scene wideSpotScene(float outerConeAngle, bool bracket);
constexpr glm::vec3 kWideSpotPosition{0.0f, 1.0f, 0.0f};

// A spot 3 m above the floor pointing down (outer cone 70 degrees) and a 2.6 m post 1 m off its
// axis, the only caster besides the floor. The post's nearest point is 1.03 m from the light, so
// the plan puts the near plane at 0.93 m along the axis: the post above y = 2.07 m is nearer than
// that and is clipped, and its floor shadow beyond r = 3.2 m (up to 7.5 m) is lost.
Scene offAxisPostScene();

// Virtual pages' seams: the floor seen from above (floorSeenFromAbove, every pixel 0.039 m) under a
// spot 3 m up at x = -4 tilted 45 degrees towards +x (outer cone 45 degrees), among a grid of thin
// posts whose shadows run across the lit floor. The floor's depth along the spot's axis runs from
// about 2 to 7 m, so at one texel per pixel its receivers ask for 110 to 360 texels across the
// view: three levels of the virtual map (128, 256, 512), with level changes and page borders
// everywhere under the shadows.
Scene tiltedSpotOverPostsSeenFromAbove();

}  // namespace punctual::testing
