#include "app/scene_source.h"

#include "scene/default_scene.h"
#include "scene/gltf_loader.h"
#include "scene/light_generator.h"

namespace punctual::app {

Scene loadSceneForOptions(const RenderOptions& options) {
    Scene scene = options.scenePath ? loadGltf(*options.scenePath) : makeDefaultScene();
    if (options.lights) {
        replaceLights(scene, options.lights->spot, options.lights->point, options.lights->seed);
    }
    validateLights(scene.lights, scene.source);
    return scene;
}

}  // namespace punctual::app
