#include "app/validate_command.h"

#include <optional>

#include <charconv>
#include <cstdio>
#include <system_error>

#include "cli/option_values.h"
#include "cli/options.h"
#include "cli/output_paths.h"
#include "app/reference_command.h"
#include "cli/scene_source.h"
#include "report/frame_stats.h"
#include "metrics/shadow_page_overlay.h"
#include "report/validation_report.h"
#include "core/error.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "lights/shadow_sizing.h"
#include "reference/reference_renderer.h"
#include "reference/shadow_validation.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace punctual::app {

using namespace cli;
using namespace report;  // the command line (src/cli) and the files the commands write (src/report)
namespace {

constexpr const char* kUsage = R"(usage: punctual validate [SCENE] [render options] --out-dir DIR [--export-exr]
                         [--edge-band-px N]

Compares the GPU's shadow factor at every pixel, for every shadowed light, with Embree's ray-cast
visibility from the same surface point, and writes:
  DIR/report.json   per light and overall: pixels compared, false_shadow (GPU dark, ray lit),
                    false_lit (GPU lit, ray blocked), misclassified_fraction over every
                    compared pixel, and each also outside the edge band (ray visibility
                    changes within one shadow texel, or --edge-band-px N screen pixels)
  DIR/report.html   the GPU image, the reference and per-light mismatch maps
  DIR/*.exr         with --export-exr: world positions (NaN for background) and each light's
                    GPU shadow factor (NaN where the light does not reach)
DIR is created if missing (its parent must exist). report.json lists the files written under
"files"; a later run into DIR removes the listed files it does not write again (and nothing
else). All render options apply (see
`punctual render --help`): --shadow-filter, --shadow-res, --shadow-bias, --point-shadow-layout...
)";

// --edge-band-px N: a number of screen pixels, 0 to 64.
float parseEdgeBandPixels(const std::string& text) {
    float value = 0.0f;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || !(value >= 0.0f && value <= 64.0f)) {
        throw Error("--edge-band-px", "expected a number of screen pixels from 0 to 64, got '" + text + "'");
    }
    return value;
}

// validate's own options; the rest are render options.
struct ValidateArgs {
    std::vector<std::string> renderArgs;
    std::optional<std::string> outDir;
    bool exportExr = false;
    float edgeBandPixels = 0.0f;  // one shadow texel
    bool help = false;
};

ValidateArgs parseValidateArgs(const std::vector<std::string>& args) {
    ValidateArgs parsed;
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--help" || args[i] == "-h") {
            parsed.help = true;
            return parsed;
        } else if (args[i] == "--out-dir") {
            parsed.outDir = optionValue(args, i);
        } else if (args[i] == "--export-exr") {
            parsed.exportExr = true;
        } else if (args[i] == "--edge-band-px") {
            parsed.edgeBandPixels = parseEdgeBandPixels(optionValue(args, i));
        } else if (args[i] == "--out" || args[i] == "--stats" || args[i] == "--heatmap") {
            throw Error(args[i], "not an option of validate (it writes into --out-dir)");
        } else {
            parsed.renderArgs.push_back(args[i]);
        }
    }
    if (!parsed.outDir) throw Error("--out-dir", "validate needs an output folder (--out-dir DIR)");
    return parsed;
}

// Every file of the run, report.json last: it lists them all, so the next run into DIR removes
// the ones it does not write again (a light that is gone leaves no mismatch map behind).
void commitValidationFiles(const std::string& dir, nlohmann::json& report, const ImageRgba8& gpuImage,
                           const ImageRgba8& referenceImage, const reference::ShadowValidation& validation,
                           const ShadowFactorImage& factors, const std::optional<ImageRgba8>& pageMap, bool exportExr) {
    const OutputFolderLayout& layout = validationFolderLayout();
    OutputFiles outputs;
    outputs.add(dir + "/report.html", validationHtml(report));
    outputs.add(dir + "/gpu.png", encodePng(gpuImage));
    outputs.add(dir + "/reference.png", encodePng(referenceImage));
    for (const reference::LightShadowValidation& light : validation.lights) {
        outputs.add(dir + "/mismatch-" + std::to_string(light.slot) + ".png",
                    encodePng(mismatchMap(light, validation.width, validation.height)));
    }
    if (validation.sun) {
        outputs.add(dir + "/mismatch-sun.png",
                    encodePng(mismatchMap(validation.sun->verdicts, validation.sun->inBand, validation.width, validation.height)));
        outputs.add(dir + "/cascades.png", encodePng(cascadeOverlay(gpuImage, factors.sunCascades)));
    }
    if (pageMap) outputs.add(dir + "/pages.png", encodePng(*pageMap));
    if (exportExr) addExrImages(outputs, dir, factors);
    const std::vector<std::string> files = outputFolderFiles(outputs, dir, layout);
    report["files"] = files;
    outputs.add(dir + "/report.json", report.dump(2) + "\n");
    prepareOutputFolder(outputs, dir, layout, files);
    outputs.commit();
}

// The summary on stdout: a line per light type (and per cascade), then all.
void printValidationSummary(const Scene& scene, const RenderOptions& options, const render::Renderer& renderer,
                            const reference::ShadowValidation& validation) {
    auto line = [](const char* name, const reference::ShadowCounts& c) {
        std::printf("%-7s compared %10llu  false shadow %8llu  false lit %8llu  edge band %8llu  misclassified outside "
                    "band %.3f%%\n",
                    name, static_cast<unsigned long long>(c.compared), static_cast<unsigned long long>(c.falseShadow),
                    static_cast<unsigned long long>(c.falseLit), static_cast<unsigned long long>(c.edgeBand),
                    100.0 * c.misclassifiedOutsideBand());
    };
    const ShadowSettings& shadows = renderer.settings().shadows;
    std::printf("shadow validation: %s, %ux%u, %zu shadowed lights, %s filter, %s resolution (views at %s), %s, %s "
                "point layout\n",
                scene.source.c_str(), options.width, options.height, validation.lights.size(),
                shadowFilterName(shadows.filter), shadowResolutionName(shadows).c_str(),
                describeShadowTiers(renderer.shadowPlan()).c_str(), shadowFormatName(shadows.format),
                pointShadowLayoutName(shadows.pointLayout));
    for (const std::string& said : {droppedLightsLine(renderer), unshadowedLightsLine(renderer)}) {
        if (!said.empty()) std::printf("%s\n", said.c_str());
    }
    line("spots", validation.spots);
    line("points", validation.points);
    if (validation.sun) {
        line("sun", validation.sun->counts);
        for (size_t i = 0; i < validation.sun->cascades.size(); ++i) {
            line(("  c" + std::to_string(i)).c_str(), validation.sun->cascades[i]);
        }
        line("  split", validation.sun->splitBand);
    }
    line("all", validation.overall);
}

}  // namespace

int runValidateCommand(const std::vector<std::string>& args) {
    const ValidateArgs parsed = parseValidateArgs(args);
    if (parsed.help) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    const std::string dir = *parsed.outDir;
    const OutputFolderLayout& layout = validationFolderLayout();
    checkOutputFolder(dir, layout);

    const RenderOptions options = parseRenderOptions(parsed.renderArgs);
    if (!options.shadows.enabled) throw Error("--shadows", "validate compares shadows: they must be on");
    const Scene scene = loadSceneForOptions(options);
    checkOutputFolder(dir, layout);  // again, now that the files the scene reads are known

    vk::Context context(contextOptionsFrom(options));
    render::RenderSettings settings = renderSettingsFrom(options);
    settings.collectShadowFactors = true;
    render::Renderer renderer(context, scene, settings);
    const ImageRgba8 gpuImage = renderer.render(1, 0).image;
    const ShadowFactorImage factors = renderer.readShadowFactors();
    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) +
                                  " validation message(s) (printed above); no output written");
    }

    const reference::ReferenceRenderer referenceRenderer(scene, referenceSettingsFrom(options, true));
    const ImageRgba8 referenceImage = referenceRenderer.render();
    const float band = parsed.edgeBandPixels;
    const reference::ShadowValidation validation = reference::validateShadows(
        referenceRenderer.embree(), factors, renderer.lights(), renderer.shadowPlan(),
        band > 0.0f ? reference::EdgeBand::ofScreenPixels(band, scene.camera, options.height) : reference::EdgeBand{});

    nlohmann::json report = validationJson(validation, scene, renderer, band);
    std::optional<ImageRgba8> pageMap;
    if (settings.shadows.virtualPages()) {
        // The virtual levels the frame's shadows read (the render command's --shadow-pages).
        pageMap = shadowPageOverlay(gpuImage, shadowPageLevels(scene, renderer.lights(), renderer.shadowPlan(), settings.width,
                                                               settings.height, settings.shadows));
        report["page_map"] = "pages.png";
    }
    commitValidationFiles(dir, report, gpuImage, referenceImage, validation, factors, pageMap, parsed.exportExr);
    printValidationSummary(scene, options, renderer, validation);
    std::printf("wrote %s/report.json and report.html\n", dir.c_str());
    return 0;
}

}  // namespace punctual::app
