#include "cli/scene_source.h"

#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/light_generator.h"
#include "scene/texture_limit.h"

namespace punctual::cli {

Scene loadSceneForOptions(const RenderOptions& options) {
    // Textures are fitted to the frame when decoded, so every command (GPU and CPU reference
    // alike) samples the same texels.
    GltfLoadOptions load;
    load.textureLimit = textureLimitForFrame(options.width, options.height);
    load.time = options.time;
    Scene scene = options.scenePath ? loadGltf(*options.scenePath, load)
                                    : makeBuiltinScene(options.sceneName ? parseBuiltinScene(*options.sceneName)
                                                                                         : kDefaultBuiltinScene,
                                                       options.sceneTriangles, options.time,
                                                       PathMotion{options.movingLights, options.movingCasters.value_or(0.0)});
    if (options.lights) {
        replaceLights(scene, options.lights->spot, options.lights->point, options.lights->seed,
                      options.lightRange.value_or(LightRange{}));
    }
    validateLights(scene.lights, scene.source);
    return scene;
}

}  // namespace punctual::cli
