#include "render/render_settings.h"

#include <cmath>
#include <sstream>
#include <string>

#include "core/error.h"
#include "gpu_types.h"

namespace punctual::render {
namespace {

std::string shortNumber(float value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

}  // namespace

void validateRenderSettings(const RenderSettings& settings) {
    if (settings.width == 0 || settings.height == 0 || settings.width > kMaxImageSide ||
        settings.height > kMaxImageSide) {
        throw Error("--size", "width and height must be from 1 to " + std::to_string(kMaxImageSide) + ", got " +
                                  std::to_string(settings.width) + "x" + std::to_string(settings.height));
    }
    if (!(settings.exposure > 0.0f) || !std::isfinite(settings.exposure)) {
        throw Error("--exposure", "must be a finite number > 0, got " + shortNumber(settings.exposure));
    }
    if (settings.tileSize < kMinTileSize || settings.tileSize > kMaxTileSize) {
        throw Error("--tile-size",
                    "must be from " + std::to_string(kMinTileSize) + " to " + std::to_string(kMaxTileSize) +
                                     " pixels, got " + std::to_string(settings.tileSize));
    }
    if (settings.clusterSlices < 1 || settings.clusterSlices > PUNCTUAL_MAX_CLUSTER_SLICES) {
        throw Error("--slices", "must be from 1 to " + std::to_string(PUNCTUAL_MAX_CLUSTER_SLICES) + ", got " +
                                    std::to_string(settings.clusterSlices));
    }
    if (settings.maxLights.spots > PUNCTUAL_MAX_LIGHT_CAPACITY || settings.maxLights.points > PUNCTUAL_MAX_LIGHT_CAPACITY) {
        throw Error("--max-lights", "at most " + std::to_string(PUNCTUAL_MAX_LIGHT_CAPACITY) + " of each kind, got " +
                                        std::to_string(settings.maxLights.spots) + "," +
                                        std::to_string(settings.maxLights.points));
    }
    validateShadowSettings(settings.shadows);
}

}  // namespace punctual::render
