#pragma once
// Loads a glTF 2.0 scene (.gltf with external or data: URI buffers, or .glb) into a Scene.
#include <optional>
#include <string>

#include "scene/scene.h"
#include "scene/texture_limit.h"

namespace punctual {

// Reads `path` (format chosen by the "glTF" magic, or else the .glb extension) and returns the
// scene of its default scene: triangle meshes, metallic-roughness materials with decoded
// base-colour textures, the first perspective camera and the KHR_lights_punctual lights.
//
// Every problem with the file (missing, unparsable, out-of-bounds accessors, non-finite
// vertices, invalid lights, nothing to draw) throws punctual::Error(path, one-line problem).
// Problems we can render around (an undecodable texture, non-triangle primitives, an
// orthographic camera) log one warning each instead.
//
// Base-colour textures larger than options.textureLimit are downscaled as they are decoded, with
// one warning each (scene/texture_limit.h).
//
// With options.time the scene is posed at that many seconds of its animations (translation,
// rotation, scale and morph weights of nodes, scene/gltf_animation.h), cameras, lights and meshes
// alike; without it, at the nodes' stored values (the rest pose), as before animation existed.
struct GltfLoadOptions {
    TextureLimit textureLimit;  // none by default
    std::optional<double> time;  // seconds into the animations (--time T)
};
Scene loadGltf(const std::string& path, const GltfLoadOptions& options = {});

}  // namespace punctual
