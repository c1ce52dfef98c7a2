// Fuzz target: the glTF loader (loadGltf) on arbitrary bytes, .gltf and .glb alike.
//
// The loader reads a path, so each input is written to one file in a private temporary folder
// (a write of a few kilobytes, small next to parsing). The file is called input.gltf; the loader
// picks GLB by the "glTF" magic before it looks at the extension, so an input starting with the
// magic exercises the binary container and any other the JSON one. Relative URIs resolve inside
// that folder, where nothing else exists.
//
// The contract under test: loadGltf either returns a scene or throws punctual::Error, and a scene
// it returns goes through the renderer's CPU-side frame setup (light culling and caps, shadow
// plan, per-object lists), with its own lights and with generated ones (--lights), as the
// commands would. Anything else (a crash, a sanitizer report, another exception, a hang) is a bug.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "core/error.h"
#include "core/log.h"
#include "fuzz_target.h"
#include "lights/light_setup.h"
#include "lights/per_object_lights.h"
#include "lights/shadow_setup.h"
#include "scene/gltf_loader.h"
#include "scene/light_generator.h"

namespace {

std::string gFolder;
std::string gInputPath;

// What Renderer's constructor computes on the CPU before it touches the GPU (render/renderer.cpp).
void setUpFrame(const punctual::Scene& scene) {
    const glm::mat4 projection = scene.camera.projection(16.0f / 9.0f);
    punctual::FrameLights lights = punctual::setupFrameLights(scene, scene.camera.view, projection);
    (void)punctual::planShadows(scene, lights, scene.camera.position(), punctual::ShadowSettings{});
    (void)punctual::buildPerObjectLightLists(scene, lights);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
    gFolder = punctual::fuzzing::makeInputFolder("gltf");
    gInputPath = gFolder + "/input.gltf";
    // Warnings (an undecodable texture, a skipped primitive) are part of the contract, not news.
    punctual::log::setSink([](const std::string&, const std::string&) {});
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::FILE* file = std::fopen(gInputPath.c_str(), "wb");
    if (file == nullptr || std::fwrite(data, 1, size, file) != size || std::fclose(file) != 0) {
        std::perror("fuzz_gltf: cannot write the input file");
        std::abort();
    }
    try {
        punctual::Scene scene = punctual::loadGltf(gInputPath);
        setUpFrame(scene);
        punctual::replaceLights(scene, 8, 4, size);
        setUpFrame(scene);
    } catch (const punctual::Error&) {
        // A clean, named error: what bad input must give.
    }
    return 0;
}
