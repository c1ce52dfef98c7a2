#pragma once
// The files of `punctual validate`: report.json, report.html, per-light mismatch maps and, on
// request, OpenEXR images of the surface positions and the GPU shadow factors.
#include <string>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "reference/shadow_validation.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace punctual::report {

// Every file validate may write into its --out-dir (report.json lists a run's files).
const OutputFolderLayout& validationFolderLayout();

// `edgeBandPixels`: the band's width in screen pixels (--edge-band-px), 0 for one shadow texel.
nlohmann::json validationJson(const reference::ShadowValidation& validation, const Scene& scene,
                              const render::Renderer& renderer, float edgeBandPixels);

// Red: false shadow, blue: false lit, greys: agreement (dark grey lit, light grey shadowed),
// black: not compared; pixels of the edge band are drawn at half brightness.
ImageRgba8 mismatchMap(const reference::LightShadowValidation& light, uint32_t width, uint32_t height);
ImageRgba8 mismatchMap(const std::vector<reference::PixelVerdict>& verdicts, const std::vector<uint8_t>& inBand,
                       uint32_t width, uint32_t height);

// The frame with each pixel tinted by the sun's cascade it read (`cascades`: cascade + 1, 0 for
// none), in the colours of Unity's cascade debug view: red, green, blue, yellow; untinted where no
// cascade was read.
ImageRgba8 cascadeOverlay(const ImageRgba8& frame, const std::vector<uint8_t>& cascades);

std::string validationHtml(const nlohmann::json& report);

// Adds positions.exr (RGB = world position, NaN where no geometry) and shadow-factor-<slot>.exr
// (the GPU factor, NaN where the light does not reach) to `outputs` under `folder`.
void addExrImages(OutputFiles& outputs, const std::string& folder, const ShadowFactorImage& factors);

}  // namespace punctual::report
