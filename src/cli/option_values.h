#pragma once
// The values of command-line options: numbers, switches and lists, each parsed whole (no trailing
// characters) and refused in one line naming the option. Shared by the render option table
// (cli/render_option_table.cpp) and the commands' own options.
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lights/light_setup.h"
#include "lights/shadow_setup.h"

namespace punctual::cli {

// The whole of `text` as a number of type T (std::from_chars: no locale, no leading '+').
template <typename T>
bool parseNumber(const std::string& text, T& value) {
    const char* first = text.data();
    const char* last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(first, last, value);
    return ec == std::errc() && end == last && !text.empty();
}

// The value after the option args[i], with i moved onto it. An option's value never starts with
// "--": `--heatmap --out x.png` is a missing value, not a heat map written to a file called
// "--out". Throws Error(args[i], "needs a value").
const std::string& optionValue(const std::vector<std::string>& args, size_t& i);

// A whole number. Options that are render settings take any: their ranges are checked in one
// place, validateRenderSettings (render/render_settings.h), once every option is read.
uint32_t parseWhole(const std::string& option, const std::string& text);
// A switch: "on" or "off".
bool parseOnOff(const std::string& option, const std::string& text);
// A whole number of an option that is not a render setting (--device, --frames), in its range.
uint32_t parseCount(const std::string& option, const std::string& text, uint32_t min, uint32_t max);
// A finite number.
float parseFloat(const std::string& option, const std::string& text);
// "1,1,1,0" -> exactly `count` comma-separated numbers; `expected` says what they are.
std::vector<float> parseNumberList(const std::string& option, const std::string& text, size_t count,
                                   const std::string& expected);
// "S,P" -> the most spot and point lights that cast a shadow (ranges: validateShadowSettings).
void parseShadowedCounts(const std::string& text, ShadowSettings& shadows);
// --max-lights S,P: whole numbers (their range is validateRenderSettings's to check).
LightCapacity parseLightCapacity(const std::string& text);

}  // namespace punctual::cli
