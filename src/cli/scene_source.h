#pragma once
// Where a command's scene comes from: a glTF file or a built-in scene (--scene NAME; by default
// the first of scene/builtin_scenes.h), with the lights optionally replaced by generated ones
// (--lights).
#include "cli/options.h"
#include "scene/scene.h"

namespace punctual::cli {

Scene loadSceneForOptions(const RenderOptions& options);

}  // namespace punctual::cli
