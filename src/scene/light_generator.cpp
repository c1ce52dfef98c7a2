#include "scene/light_generator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "gpu_types.h"
#include "scene/light_reach.h"

namespace punctual {

namespace {

// The most lights of each kind any frame can keep (--max-lights S,P sets how many it does).
constexpr uint32_t kMaxLights = PUNCTUAL_MAX_LIGHT_CAPACITY;
constexpr float kDegree = 0.0174532925f;  // pi / 180
// Redraws go to the bounds widened by this fraction of their diagonal: at least the shortest
// generated range (0.25 x the diagonal), so a light in the margin can still reach the model.
constexpr float kRedrawMargin = 0.25f;
constexpr uint32_t kPlacementAttempts = 32;

[[noreturn]] void throwOverCaps(uint64_t spotCount, uint64_t pointCount) {
    throw Error("--lights", "at most " + std::to_string(kMaxLights) + " spot and " + std::to_string(kMaxLights) +
                                " point lights (got " + std::to_string(spotCount) + "," +
                                std::to_string(pointCount) + ")");
}

// A unit vector pointing down, tilted in x and z by up to atan(maxTilt) from vertical. Built from
// a random offset in a square and normalised (no trigonometry, so no libm differences).
glm::vec3 downwardDirection(PortableRandom& random, float maxTilt) {
    const float tiltX = random.uniform(-maxTilt, maxTilt);
    const float tiltZ = random.uniform(-maxTilt, maxTilt);
    return glm::normalize(glm::vec3(tiltX, -1.0f, tiltZ));
}

}  // namespace

PortableRandom::PortableRandom(uint64_t seed) {
    std::seed_seq sequence{static_cast<uint32_t>(seed & 0xffffffffu), static_cast<uint32_t>(seed >> 32)};
    engine_.seed(sequence);
}

float PortableRandom::uniform() {
    // mt19937 yields 32 random bits; keep the top 24 (a float's significand) so that
    // k * 2^-24 is exact for every k in [0, 2^24) and the result is strictly below 1.
    const uint32_t bits = static_cast<uint32_t>(engine_()) >> 8;
    return static_cast<float>(bits) * (1.0f / 16777216.0f);
}

float PortableRandom::uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

glm::vec3 randomLightColor(PortableRandom& random) {
    // A fully saturated random hue (three random channels stretched so the smallest is 0 and the
    // largest 1), mixed with white by a random saturation of at most 85%: tinted whites to vivid
    // colours, so neighbouring lights can be told apart in an image (a missing light shows). The
    // largest channel stays exactly 1 and the smallest is 1 - saturation >= 0.15.
    const glm::vec3 raw(random.uniform(), random.uniform(), random.uniform());
    const float saturation = random.uniform(0.0f, 0.85f);
    const float lo = std::min({raw.r, raw.g, raw.b});
    const float spread = std::max({raw.r, raw.g, raw.b}) - lo;
    if (spread <= 0.0f) return glm::vec3(1.0f);
    const glm::vec3 hue = (raw - lo) / spread;
    return glm::mix(glm::vec3(1.0f), hue, saturation);
}

float constantDensityRangeScale(uint32_t lights) {
    if (lights == 0) return 1.0f;
    return std::cbrt(float(kDensityReferenceLights) / float(lights));
}

float generatedLightRange(float drawn, const LightRange& rule) {
    switch (rule.kind) {
        case LightRange::Kind::Drawn: return drawn;
        case LightRange::Kind::Metres: return rule.metres;
        case LightRange::Kind::ConstantDensity: return drawn;  // scaled once all are drawn (fittedDensityScale)
    }
    return drawn;
}

float fittedDensityScale(const std::vector<Light>& lights, const std::vector<glm::vec3>& probes) {
    if (lights.size() == kDensityReferenceLights) return 1.0f;
    if (probes.empty()) return constantDensityRangeScale(uint32_t(lights.size()));
    std::vector<float> leastScales;  // per (light, probe) pair that can count
    for (const Light& light : lights) {
        const float cosOuter = std::cos(light.outerConeAngle);
        for (const glm::vec3& probe : probes) {
            const glm::vec3 toProbe = probe - light.position;
            const float distance = glm::length(toProbe);
            if (light.type == LightType::Spot && !(glm::dot(toProbe, light.direction) > cosOuter * distance)) continue;
            leastScales.push_back(distance / std::max(light.range, 1e-6f));
        }
    }
    const auto atOne = size_t(std::count_if(leastScales.begin(), leastScales.end(), [](float s) { return s < 1.0f; }));
    const double wanted = double(atOne) * double(kDensityReferenceLights) / double(lights.size());
    const size_t k = size_t(std::llround(wanted));
    if (atOne == 0 || k == 0) return 1.0f;
    if (k >= leastScales.size()) return *std::max_element(leastScales.begin(), leastScales.end()) * 1.001f;
    // s between the k-th and (k+1)-th smallest: exactly k pairs below it.
    std::nth_element(leastScales.begin(), leastScales.begin() + std::ptrdiff_t(k), leastScales.end());
    const float above = leastScales[k];
    const float below = *std::max_element(leastScales.begin(), leastScales.begin() + std::ptrdiff_t(k));
    return 0.5f * (below + above);
}

namespace {

// Where a generated light's first draw goes, and where its redraws go when the first cannot reach
// anything the camera sees (replaceLights).
struct PlacementRegions {
    Bounds first;
    Bounds widened;
};

PlacementRegions placementRegions(const Bounds& bounds, float diagonal) {
    const glm::vec3 size = bounds.size();
    const float horizontal = std::max(size.x, size.z);
    // Height band: above the lowest 10% (the floor and what stands on it) and below the top 10%
    // (a ceiling). A flat scene (a terrain, a single quad) has no useful height: hang the lights at
    // a height proportional to its horizontal size instead, as if above a floor.
    float yLow = bounds.min.y + 0.1f * size.y;
    float yHigh = bounds.min.y + 0.9f * size.y;
    if (size.y < 0.1f * horizontal) {
        yLow = bounds.min.y + 0.05f * horizontal;
        yHigh = bounds.min.y + 0.2f * horizontal;
    }
    // The redraws' region: the bounds widened by a margin on every side but the bottom (below the
    // lowest surface a light reaches nothing a camera above it sees), so that a closed model, which
    // fills its own bounds, has lights around it.
    const float margin = kRedrawMargin * diagonal;
    return {Bounds{glm::vec3(bounds.min.x, yLow, bounds.min.z), glm::vec3(bounds.max.x, yHigh, bounds.max.z)},
            Bounds{glm::vec3(bounds.min.x - margin, bounds.min.y, bounds.min.z - margin),
                   glm::vec3(bounds.max.x + margin, std::max(bounds.max.y, yHigh) + margin, bounds.max.z + margin)}};
}

// Every range times `scale`, and every intensity times its square (intensity ~ range^2, as drawn).
void scaleRanges(std::vector<Light>& lights, float scale) {
    for (Light& light : lights) {
        light.range *= scale;
        light.intensity *= scale * scale;
    }
}

}  // namespace

void replaceLights(Scene& scene, uint32_t spotCount, uint32_t pointCount, uint64_t seed, const LightRange& range) {
    if (spotCount > kMaxLights || pointCount > kMaxLights) throwOverCaps(spotCount, pointCount);
    if (scene.bounds.empty())
        throw Error("--lights", "the scene has no geometry whose bounds could hold generated lights");

    const Bounds& bounds = scene.bounds;
    const float diagonal = std::max(glm::length(bounds.size()), 1e-3f);
    const PlacementRegions regions = placementRegions(bounds, diagonal);
    const Bounds& first = regions.first;
    const Bounds& widened = regions.widened;

    PortableRandom random(seed);
    auto randomPosition = [&](const Bounds& region) {
        const float x = random.uniform(region.min.x, region.max.x);
        const float y = random.uniform(region.min.y, region.max.y);
        const float z = random.uniform(region.min.z, region.max.z);
        // uniform(lo, hi) rounds once; clamp so "inside the region" holds exactly.
        return glm::clamp(glm::vec3(x, y, z), region.min, region.max);
    };
    auto drawSpot = [&](uint32_t i, const Bounds& region) {
        Light light;
        light.name = "generated spot " + std::to_string(i);
        light.type = LightType::Spot;
        light.position = randomPosition(region);
        light.direction = downwardDirection(random, 0.5f);  // tilt <= atan(0.5 * sqrt 2) = 35.3 deg
        light.color = randomLightColor(random);
        light.outerConeAngle = random.uniform(25.0f, 50.0f) * kDegree;
        light.innerConeAngle = light.outerConeAngle * random.uniform(0.5f, 0.9f);
        light.range = generatedLightRange(diagonal * random.uniform(0.25f, 0.45f), range);
        // Spots are brighter per steradian than points (they light a smaller area): on the axis
        // at half the range the illuminance is I * 0.879 / (r/2)^2 = 3.5 * I / r^2, i.e.
        // 0.26-0.53 lux for I = (0.075-0.15) r^2.
        light.intensity = light.range * light.range * random.uniform(0.075f, 0.15f);
        light.castsShadow = true;
        return light;
    };
    auto drawPoint = [&](uint32_t i, const Bounds& region) {
        Light light;
        light.name = "generated point " + std::to_string(i);
        light.type = LightType::Point;
        light.position = randomPosition(region);
        light.direction = glm::vec3(0.0f, -1.0f, 0.0f);  // unused by points
        light.color = randomLightColor(random);
        light.range = generatedLightRange(diagonal * random.uniform(0.25f, 0.45f), range);
        // 0.09-0.18 lux at half the range (see above), since points overlap more.
        light.intensity = light.range * light.range * random.uniform(0.025f, 0.05f);
        light.castsShadow = true;
        return light;
    };

    // A light that reaches nothing the camera sees is drawn again (not for auto ranges: their
    // redraws would depend on ranges not yet fitted, and pull lights towards what the camera sees,
    // against a constant density) (all its parameters, from the
    // same random sequence, so the result still depends on the seed alone): first in the same
    // region, so a scene whose camera is inside (a room) keeps its lights where they were meant to
    // be, then in the widened one, which a closed model needs. After kPlacementAttempts draws
    // that all fail, the first is kept. Without any geometry in view there is nothing to test, and
    // every first draw stands, as it always did.
    const LightReach reach(scene);
    auto place = [&](auto&& draw, uint32_t i) {
        const Light firstDraw = draw(i, first);
        if (range.kind == LightRange::Kind::ConstantDensity) return firstDraw;
        if (reach.empty() || reach.reaches(firstDraw)) return firstDraw;
        for (uint32_t attempt = 1; attempt < kPlacementAttempts; ++attempt) {
            Light light = draw(i, attempt < kPlacementAttempts / 2 ? first : widened);
            if (reach.reaches(light)) return light;
        }
        return firstDraw;
    };

    std::vector<Light> lights;
    lights.reserve(size_t(spotCount) + pointCount);
    for (uint32_t i = 0; i < spotCount; ++i) lights.push_back(place(drawSpot, i));
    for (uint32_t i = 0; i < pointCount; ++i) lights.push_back(place(drawPoint, i));
    if (range.kind == LightRange::Kind::ConstantDensity) scaleRanges(lights, fittedDensityScale(lights, reach.samplePoints()));
    scene.lights = std::move(lights);
}

namespace {

// Parses one decimal field of `text`: digits only, at most 2^64 - 1. `what` names it in errors.
uint64_t parseField(const std::string& field, const std::string& text, const char* what) {
    const std::string usage = " (expected S,P or S,P,SEED with non-negative integers, got \"" + text + "\")";
    if (field.empty()) throw Error("--lights", std::string("missing ") + what + usage);
    uint64_t value = 0;
    for (const char c : field) {
        if (c < '0' || c > '9')
            throw Error("--lights", std::string(what) + " \"" + field + "\" is not a non-negative integer" + usage);
        const auto digit = static_cast<uint64_t>(c - '0');
        if (value > (std::numeric_limits<uint64_t>::max() - digit) / 10)
            throw Error("--lights", std::string(what) + " \"" + field + "\" is too large" + usage);
        value = value * 10 + digit;
    }
    return value;
}

}  // namespace

LightCounts parseLightCounts(const std::string& text) {
    std::vector<std::string> fields;
    size_t start = 0;
    while (true) {
        const size_t comma = text.find(',', start);
        fields.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (fields.size() < 2 || fields.size() > 3)
        throw Error("--lights", "expected S,P or S,P,SEED (spot count, point count, optional seed), got \"" + text + "\"");

    const uint64_t spot = parseField(fields[0], text, "spot count");
    const uint64_t point = parseField(fields[1], text, "point count");
    LightCounts counts;
    if (fields.size() == 3) counts.seed = parseField(fields[2], text, "seed");
    if (spot > kMaxLights || point > kMaxLights) throwOverCaps(spot, point);
    counts.spot = static_cast<uint32_t>(spot);
    counts.point = static_cast<uint32_t>(point);
    return counts;
}

void setLightRanges(Scene& scene, float fraction) {
    const float diagonal = glm::length(scene.bounds.max - scene.bounds.min);
    if (!(fraction > 0.0f) || !(diagonal > 0.0f)) throw Error("light range", "needs a positive fraction and scene bounds");
    for (Light& light : scene.lights) {
        if (light.type == LightType::Directional) continue;
        const float range = fraction * diagonal;
        const float scale = light.range > 0.0f ? range / light.range : 1.0f;  // an infinite range keeps its intensity
        light.intensity *= scale * scale;
        light.range = range;
    }
}

void keepFirstLights(Scene& scene, uint32_t spotCount, uint32_t pointCount) {
    uint32_t spots = 0;
    uint32_t points = 0;
    std::erase_if(scene.lights, [&](const Light& light) {
        if (light.type == LightType::Spot) return ++spots > spotCount;
        if (light.type == LightType::Point) return ++points > pointCount;
        return false;
    });
}

}  // namespace punctual
