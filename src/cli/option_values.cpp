#include "cli/option_values.h"

#include <cmath>

#include "core/error.h"

namespace punctual::cli {

const std::string& optionValue(const std::vector<std::string>& args, size_t& i) {
    if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) throw Error(args[i], "needs a value");
    return args[++i];
}

uint32_t parseWhole(const std::string& option, const std::string& text) {
    uint32_t value = 0;
    if (!parseNumber(text, value)) throw Error(option, "expected a whole number, got '" + text + "'");
    return value;
}

bool parseOnOff(const std::string& option, const std::string& text) {
    if (text != "on" && text != "off") throw Error(option, "expected on or off, got '" + text + "'");
    return text == "on";
}

uint32_t parseCount(const std::string& option, const std::string& text, uint32_t min, uint32_t max) {
    uint32_t value = 0;
    if (!parseNumber(text, value) || value < min || value > max) {
        throw Error(option, "expected a whole number from " + std::to_string(min) + " to " + std::to_string(max) +
                                ", got '" + text + "'");
    }
    return value;
}

float parseFloat(const std::string& option, const std::string& text) {
    float value = 0.0f;
    if (!parseNumber(text, value) || !std::isfinite(value)) {
        throw Error(option, "expected a number, got '" + text + "'");
    }
    return value;
}

std::vector<float> parseNumberList(const std::string& option, const std::string& text, size_t count,
                                   const std::string& expected) {
    std::vector<float> numbers;
    size_t start = 0;
    for (size_t i = 0; i < count; ++i) {
        const size_t comma = text.find(',', start);
        if ((i + 1 < count) != (comma != std::string::npos)) {
            throw Error(option, "expected " + expected + ", got '" + text + "'");
        }
        numbers.push_back(parseFloat(option, text.substr(start, comma - start)));
        start = comma + 1;
    }
    return numbers;
}

void parseShadowedCounts(const std::string& text, ShadowSettings& shadows) {
    const size_t comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
        throw Error("--shadowed", "expected S,P (spot and point lights), got '" + text + "'");
    }
    shadows.maxShadowedSpots = parseWhole("--shadowed", text.substr(0, comma));
    shadows.maxShadowedPoints = parseWhole("--shadowed", text.substr(comma + 1));
}

LightCapacity parseLightCapacity(const std::string& text) {
    const size_t comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
        throw Error("--max-lights", "expected S,P (spot and point lights), got '" + text + "'");
    }
    return {parseWhole("--max-lights", text.substr(0, comma)), parseWhole("--max-lights", text.substr(comma + 1))};
}

}  // namespace punctual::cli
