#include "render/render_settings.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "gpu_types.h"

namespace punctual::render {

void validateRenderSettings(const RenderSettings& settings) {
    if (settings.width == 0 || settings.height == 0 || settings.width > kMaxImageSide ||
        settings.height > kMaxImageSide) {
        throw Error("--size", "width and height must be between 1 and " + std::to_string(kMaxImageSide));
    }
    if (!(settings.exposure > 0.0f) || !std::isfinite(settings.exposure)) {
        throw Error("--exposure", "must be a finite number > 0");
    }
    if (settings.tileSize < kMinTileSize || settings.tileSize > kMaxTileSize) {
        throw Error("--tile-size",
                    "must be from " + std::to_string(kMinTileSize) + " to " + std::to_string(kMaxTileSize) + " pixels");
    }
    if (settings.clusterSlices < 1 || settings.clusterSlices > PUNCTUAL_MAX_CLUSTER_SLICES) {
        throw Error("--slices", "must be from 1 to " + std::to_string(PUNCTUAL_MAX_CLUSTER_SLICES));
    }
    validateShadowSettings(settings.shadows);
}

}  // namespace punctual::render
