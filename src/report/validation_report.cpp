#include "report/validation_report.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "report/exr_encoding.h"

namespace punctual::report {
namespace {

nlohmann::json countsJson(const reference::ShadowCounts& c) {
    return {
        {"compared", c.compared},
        {"false_shadow", c.falseShadow},
        {"false_lit", c.falseLit},
        {"misclassified_fraction", c.misclassified()},
        {"edge_band", c.edgeBand},
        {"outside_edge_band",
         {{"compared", c.comparedOutsideBand},
          {"false_shadow", c.falseShadowOutsideBand},
          {"false_lit", c.falseLitOutsideBand},
          {"misclassified_fraction", c.misclassifiedOutsideBand()}}},
    };
}

}  // namespace

const OutputFolderLayout& validationFolderLayout() {
    static const OutputFolderLayout layout = {"report.json",
                                              {"report.json", "report.html", "gpu.png", "reference.png",
                                               "mismatch-*.png", "cascades.png", "pages.png", "positions.exr", "shadow-factor-*.exr"},
                                              {}};
    return layout;
}

nlohmann::json validationJson(const reference::ShadowValidation& validation, const Scene& scene,
                              const render::Renderer& renderer, float edgeBandPixels) {
    const ShadowSettings& s = renderer.settings().shadows;
    nlohmann::json report;
    report["scene"] = scene.source;
    report["size"] = {{"width", validation.width}, {"height", validation.height}};
    report["settings"] = {{"resolution", shadowResolutionName(s)},
                          {"format", shadowFormatName(s.format)},
                          {"budget_bytes", s.budgetBytes},
                          {"filter", shadowFilterName(s.filter)},
                          {"samples", s.diskSamples},
                          {"penumbra", s.diskRadius},
                          {"bias", {s.bias.x, s.bias.y, s.bias.z, s.bias.w}},
                          {"point_layout", pointShadowLayoutName(s.pointLayout)},
                          {"culling", render::methodName(renderer.settings().method)}};
    std::ostringstream band;
    if (edgeBandPixels > 0.0f) {
        band << edgeBandPixels << " screen pixel(s)";
    } else {
        band << "one shadow texel";
    }
    report["rule"] = "GPU dark when its filtered factor < 0.5; edge band: ray visibility changes within " + band.str() +
                     " of the point (4 probe rays); misclassified_fraction counts every compared pixel, "
                     "outside_edge_band those outside the band";
    report["edge_band_px"] = edgeBandPixels;
    report["overall"] = countsJson(validation.overall);
    report["spot"] = countsJson(validation.spots);
    report["point"] = countsJson(validation.points);
    nlohmann::json lights = nlohmann::json::array();
    for (const reference::LightShadowValidation& light : validation.lights) {
        nlohmann::json entry = countsJson(light.counts);
        entry["slot"] = light.slot;
        entry["type"] = light.isPoint ? "point" : "spot";
        entry["scene_light"] = light.sceneLight;
        entry["name"] = scene.lights.at(light.sceneLight).name;
        entry["mismatch_map"] = "mismatch-" + std::to_string(light.slot) + ".png";
        lights.push_back(entry);
    }
    report["lights"] = lights;
    // Lights the comparison leaves out because they have no shadow map (over --shadowed, or casting none).
    const uint32_t punctualLights = renderer.lights().spotCount + renderer.lights().pointCount;
    report["unshadowed_lights"] = {{"count", renderer.shadowPlan().unshadowedLights(punctualLights)},
                                   {"over_cap", renderer.shadowPlan().droppedByCap},
                                   {"of", punctualLights}};
    if (validation.sun) {
        // The sun: overall, per cascade (by the cascade the GPU read), and the split band (pixels
        // within one texel of where the cascade read changes).
        const reference::SunShadowValidation& sun = *validation.sun;
        const ShadowPlan& plan = renderer.shadowPlan();
        nlohmann::json directional = countsJson(sun.counts);
        directional["scene_light"] = sun.sceneLight;
        directional["name"] = scene.lights.at(sun.sceneLight).name;
        directional["mismatch_map"] = "mismatch-sun.png";
        directional["cascade_map"] = "cascades.png";
        directional["cascade_blend"] = cascadeBlendName(s.cascades.blend);
        directional["shadow_distance_m"] = plan.cascades.shadowDistance;
        nlohmann::json cascades = nlohmann::json::array();
        for (uint32_t i = 0; i < sun.cascades.size(); ++i) {
            nlohmann::json entry = countsJson(sun.cascades[i]);
            entry["cascade"] = i;
            entry["far_m"] = plan.cascades.splits[i];
            entry["resolution"] = plan.views[plan.cascades.firstView + i].resolution;
            entry["texel_m"] = cascadeTexelSize(plan, i);
            cascades.push_back(std::move(entry));
        }
        directional["cascades"] = cascades;
        directional["split_band"] = countsJson(sun.splitBand);
        report["directional"] = directional;
    }
    return report;
}

ImageRgba8 mismatchMap(const reference::LightShadowValidation& light, uint32_t width, uint32_t height) {
    return mismatchMap(light.verdicts, light.inBand, width, height);
}

ImageRgba8 mismatchMap(const std::vector<reference::PixelVerdict>& verdicts, const std::vector<uint8_t>& inBand,
                       uint32_t width, uint32_t height) {
    ImageRgba8 image;
    image.width = width;
    image.height = height;
    image.pixels.assign(size_t(width) * height * 4, 0);
    for (size_t i = 0; i < verdicts.size(); ++i) {
        glm::u8vec3 colour(0);
        switch (verdicts[i]) {
            case reference::PixelVerdict::NotCompared: colour = {0, 0, 0}; break;
            case reference::PixelVerdict::AgreeLit: colour = {70, 70, 70}; break;
            case reference::PixelVerdict::AgreeShadow: colour = {150, 150, 150}; break;
            case reference::PixelVerdict::FalseShadow: colour = {255, 40, 40}; break;
            case reference::PixelVerdict::FalseLit: colour = {40, 90, 255}; break;
        }
        if (inBand[i]) colour /= uint8_t(2);
        image.pixels[i * 4 + 0] = colour.r;
        image.pixels[i * 4 + 1] = colour.g;
        image.pixels[i * 4 + 2] = colour.b;
        image.pixels[i * 4 + 3] = 255;
    }
    return image;
}

ImageRgba8 cascadeOverlay(const ImageRgba8& frame, const std::vector<uint8_t>& cascades) {
    static const glm::vec3 kColours[PUNCTUAL_MAX_CASCADES] = {{1.0f, 0.2f, 0.2f}, {0.2f, 1.0f, 0.2f}, {0.3f, 0.4f, 1.0f},
                                                              {1.0f, 1.0f, 0.2f}};
    ImageRgba8 image = frame;
    for (size_t i = 0; i < cascades.size() && i * 4 + 3 < image.pixels.size(); ++i) {
        if (cascades[i] == 0 || cascades[i] > PUNCTUAL_MAX_CASCADES) continue;
        const glm::vec3 tint = kColours[cascades[i] - 1];
        for (int c = 0; c < 3; ++c) {
            // Half the frame's own brightness (so the shadows stay readable), half the tint.
            const float value = 0.5f * float(image.pixels[i * 4 + size_t(c)]) + 127.0f * tint[c];
            image.pixels[i * 4 + size_t(c)] = uint8_t(std::min(value, 255.0f));
        }
    }
    return image;
}

std::string validationHtml(const nlohmann::json& report) {
    std::ostringstream html;
    auto percent = [](double fraction) {
        std::ostringstream s;
        s.precision(3);
        s << 100.0 * fraction << "%";
        return s.str();
    };
    html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>punctual shadow validation</title>\n"
         << "<style>body{font-family:sans-serif;background:#111;color:#ddd} img{max-width:48%;margin:4px}"
         << " table{border-collapse:collapse} td,th{border:1px solid #444;padding:2px 8px;text-align:right}"
         << " .maps img{max-width:31%}</style></head><body>\n"
         << "<h1>Shadows: GPU against Embree</h1>\n<p>Scene: " << report["scene"].get<std::string>() << ". Settings: "
         << report["settings"].dump() << ".<br>Rule: " << report["rule"].get<std::string>() << ".<br>Lights without a "
         << "shadow (not compared): " << report["unshadowed_lights"]["count"] << " of " << report["unshadowed_lights"]["of"]
         << ", " << report["unshadowed_lights"]["over_cap"] << " of them over --shadowed.</p>\n"
         << "<p><img src=\"gpu.png\" alt=\"GPU\"><img src=\"reference.png\" alt=\"Embree reference\"><br>"
         << "Left: GPU. Right: Embree reference (ray-traced shadows).</p>\n"
         << "<table><tr><th>light</th><th>type</th><th>compared</th><th>false shadow</th><th>false lit</th>"
         << "<th>edge band</th><th>misclassified</th><th>misclassified outside band</th></tr>\n";
    auto row = [&](const std::string& name, const std::string& type, const nlohmann::json& c) {
        html << "<tr><td>" << name << "</td><td>" << type << "</td><td>" << c["compared"] << "</td><td>"
             << c["false_shadow"] << "</td><td>" << c["false_lit"] << "</td><td>" << c["edge_band"] << "</td><td>"
             << percent(c["misclassified_fraction"].get<double>()) << "</td><td>"
             << percent(c["outside_edge_band"]["misclassified_fraction"].get<double>()) << "</td></tr>\n";
    };
    row("all", "", report["overall"]);
    row("spots", "spot", report["spot"]);
    row("points", "point", report["point"]);
    for (const auto& light : report["lights"]) {
        row(std::to_string(light["slot"].get<int>()) + " " + light["name"].get<std::string>(),
            light["type"].get<std::string>(), light);
    }
    if (report.contains("directional")) {
        const nlohmann::json& sun = report["directional"];
        row("sun " + sun["name"].get<std::string>(), "directional", sun);
        for (const auto& cascade : sun["cascades"]) {
            std::ostringstream name;
            name << "  cascade " << cascade["cascade"] << " (to " << cascade["far_m"].get<double>() << " m, "
                 << cascade["resolution"] << " texels)";
            row(name.str(), "directional", cascade);
        }
        row("  split band", "directional", sun["split_band"]);
    }
    html << "</table>\n<h2>Mismatch maps</h2>\n<p>Red: false shadow (GPU dark, ray lit). Blue: false lit (GPU lit, "
         << "ray blocked). Grey: agreement (dark: lit, light: shadowed). Half brightness: edge band. Black: the light "
         << "does not reach the pixel.</p>\n<div class=\"maps\">\n";
    for (const auto& light : report["lights"]) {
        html << "<figure style=\"display:inline-block;width:31%\"><img style=\"max-width:100%\" src=\""
             << light["mismatch_map"].get<std::string>() << "\"><figcaption>" << light["slot"] << " ("
             << light["type"].get<std::string>() << ")</figcaption></figure>\n";
    }
    if (report.contains("page_map")) {
        html << "<figure style=\"display:inline-block;width:31%\"><img style=\"max-width:100%\" src=\"pages.png\">"
             << "<figcaption>virtual shadow pages: the finest level each pixel's lights read (red 0 = 16384 "
             << "texels, blue 9 = 32)</figcaption></figure>\n";
    }
    if (report.contains("directional")) {
        html << "<figure style=\"display:inline-block;width:31%\"><img style=\"max-width:100%\" src=\"mismatch-sun.png\">"
             << "<figcaption>sun</figcaption></figure>\n"
             << "<figure style=\"display:inline-block;width:31%\"><img style=\"max-width:100%\" src=\"cascades.png\">"
             << "<figcaption>the sun's cascades: red 0, green 1, blue 2, yellow 3</figcaption></figure>\n";
    }
    html << "</div></body></html>\n";
    return html.str();
}

void addExrImages(OutputFiles& outputs, const std::string& folder, const ShadowFactorImage& factors) {
    const size_t pixels = size_t(factors.width) * factors.height;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> positions(pixels * 3);
    for (size_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 3; ++c) positions[i * 3 + c] = factors.covered[i] ? factors.positions[i][c] : nan;
    }
    outputs.add(folder + "/positions.exr", encodeExr(positions, factors.width, factors.height, 3, "positions.exr"));
    for (uint32_t slot = 0; slot < factors.slots; ++slot) {
        std::vector<float> values(pixels);
        for (size_t i = 0; i < pixels; ++i) {
            const uint8_t f = factors.factors[i * factors.slots + slot];
            values[i] = f == PUNCTUAL_SHADOW_FACTOR_NOT_REACHED ? nan : float(f) / 254.0f;
        }
        const std::string name = "shadow-factor-" + std::to_string(slot) + ".exr";
        outputs.add(folder + "/" + name, encodeExr(values, factors.width, factors.height, 1, name));
    }
}

}  // namespace punctual::report
