#include "bench/failure_study.h"

namespace punctual::bench {

ValidatedFrame renderAndValidate(vk::Context& context, const Scene& scene, const reference::EmbreeScene& embree,
                                 render::RenderSettings settings, const reference::EdgeBand& band) {
    settings.collectShadowFactors = true;
    render::Renderer renderer(context, scene, settings);
    ValidatedFrame frame;
    frame.result = renderer.render(1, 1);
    frame.factors = renderer.readShadowFactors();
    frame.plan = renderer.shadowPlan();
    frame.validation = reference::validateShadows(embree, frame.factors, renderer.lights(), renderer.shadowPlan(), band);
    return frame;
}

ValidatedFrame renderAndValidate(vk::Context& context, const Scene& scene, const render::RenderSettings& settings,
                                 const reference::EdgeBand& band) {
    const reference::EmbreeScene embree(scene);
    return renderAndValidate(context, scene, embree, settings, band);
}

}  // namespace punctual::bench
