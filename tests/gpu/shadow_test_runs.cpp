#include "shadow_test_runs.h"

#include "report/validation_report.h"
#include "gpu_test_support.h"
#include "reference/embree_scene.h"

namespace punctual::testing {

render::RenderSettings shadowRenderSettings(uint32_t width, uint32_t height, const ShadowSettings& shadows) {
    render::RenderSettings settings = renderSettings(width, height);
    settings.shadows = shadows;
    settings.collectShadowFactors = true;
    return settings;
}

ShadowRun renderAndValidateShadows(vk::Context& context, const Scene& scene, const render::RenderSettings& settings) {
    render::Renderer renderer(context, scene, settings);
    ShadowRun run;
    run.image = renderer.render(1, 0).image;
    run.factors = renderer.readShadowFactors();
    run.lights = renderer.lights();
    run.plan = renderer.shadowPlan();
    const reference::EmbreeScene embree(scene);
    run.validation = reference::validateShadows(embree, run.factors, run.lights, run.plan);
    return run;
}

void saveShadowRun(const std::string& name, const ShadowRun& run) {
    saveTestImage(name, run.image);
    for (const reference::LightShadowValidation& light : run.validation.lights) {
        saveTestImage(name + "-mismatch-" + std::to_string(light.slot),
                      report::mismatchMap(light, run.validation.width, run.validation.height));
    }
}

}  // namespace punctual::testing
