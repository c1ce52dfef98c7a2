#pragma once
// Procedural lights for any scene: `--lights S,P[,SEED]` replaces a scene's lights with S spot and
// P point lights spread through its bounds, so light-count scaling can be benchmarked on any
// glTF scene. Everything here is deterministic bit for bit across compilers and standard
// libraries: the random source is std::mt19937 (its output sequence is fixed by the C++
// standard) and the conversion of its 32-bit outputs to floats is our own, because
// std::uniform_real_distribution is implementation-defined and differs between libstdc++, libc++
// and MSVC.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual {

// Deterministic, portable random floats.
class PortableRandom {
public:
    // The 64-bit seed is split into two 32-bit words fed through std::seed_seq, whose mixing
    // algorithm is also specified by the standard.
    explicit PortableRandom(uint64_t seed);

    // Uniform in [0, 1): the top 24 bits of one engine output times 2^-24. Every result is exactly
    // representable in a float, so no rounding mode or library can change it.
    float uniform();
    // lo + (hi - lo) * uniform(): in [lo, hi) up to the rounding of that one multiply-add
    // (IEEE-exact, and never contracted to an FMA under -std=c++20 on GCC/Clang).
    float uniform(float lo, float hi);

private:
    std::mt19937 engine_;
};

// A light colour: a random tint between white and a random saturated colour, scaled so its
// largest channel is exactly 1 (then intensity alone sets the peak brightness).
glm::vec3 randomLightColor(PortableRandom& random);

// How generated lights get their ranges (`--light-range R|auto`).
struct LightRange {
    enum class Kind : uint8_t {
        Drawn,            // as drawn: 0.25-0.45 x the bounds diagonal (the default)
        Metres,           // every light `metres`
        ConstantDensity,  // as drawn, all scaled so that the lights reaching a point the camera sees
                          // stay about as many as kDensityReferenceLights put there (auto;
                          // fittedDensityScale)
    };
    Kind kind = Kind::Drawn;
    float metres = 0.0f;
};

// The light count whose drawn ranges set the density `auto` keeps: the design notes' 64 + 32.
inline constexpr uint32_t kDensityReferenceLights = 64 + 32;

// The range scale that keeps the density of lights reaching a point in free space: a point lies in
// a light's reach with a probability proportional to the volume it reaches, r^3 for a sphere and
// for a cone of a given angle alike, so `lights` lights reach it about as often as the reference
// count when lights x r^3 stays the same: r scales by cbrt(kDensityReferenceLights / lights). 1
// for the reference count (exactly: cbrt(1)), 1 for none. Real scenes clip a reach by their
// bounds, the more the longer it is (the hall's 8 m of height against ranges of 12-22 m): there
// the rule let the lights reaching a pixel grow from 18 at 96 lights to 109 at 7,616 (measured).
// Auto fits its scale to the scene instead (fittedDensityScale); this is its fallback where the
// camera sees no geometry.
float constantDensityRangeScale(uint32_t lights);

// The one range scale s (every light's range times s) for which `lights` reach the points
// `probes` kDensityReferenceLights / lights.size() times as often as they do at their own ranges:
// then, as drawn from one distribution, they reach them about as often as kDensityReferenceLights
// of its lights would at their own ranges. A light reaches a point where attenuation > 0: within
// its range, and inside a spot's outer cone (which scaling does not change). So each (light,
// probe) pair has the least scale at which it counts, distance / range (none outside a cone), and
// s lies between the K-th and (K+1)-th smallest of them, K the pairs counted at scale 1 times the
// count ratio. 1 for kDensityReferenceLights lights (exactly) and where no pair counts; the
// fallback rule without probes.
float fittedDensityScale(const std::vector<Light>& lights, const std::vector<glm::vec3>& probes);

// The range of a generated light drawn at `drawn` metres under `rule` (auto: as drawn; the fit
// scales every light once all are drawn, fittedDensityScale).
float generatedLightRange(float drawn, const LightRange& rule);

// Replaces ALL of the scene's lights, directional ones included (a generated set is meant to be
// the scene's whole lighting, so results depend only on S, P and the seed), with `spotCount`
// spots followed by `pointCount` points:
//  - positions uniform in x and z over the scene bounds; y uniform in
//    [min.y + 10% of the height, min.y + 90% of the height], i.e. above the lowest surfaces and
//    below a ceiling. A flat scene (height < 10% of its larger horizontal side h) gets y in
//    [min.y + 0.05 h, min.y + 0.2 h] instead, which is above the bounds.
//  - every light must reach something the scene's camera sees (scene/light_reach.h: in range,
//    in the cone, on the visible side, nothing in between). One that does not is drawn again:
//    15 times as above, then 16 times anywhere in the bounds widened by 25% of their diagonal
//    (not below them); if all fail, the first draw is kept. So a small closed model gets lights
//    around it, not inside it, while a room modelled as one closed mesh, seen from inside, keeps
//    its lights inside.
//  - spots shine down, tilted randomly up to ~35 degrees from vertical; outer cone 25-50 degrees,
//    inner cone 0.5-0.9 x outer.
//  - ranges 0.25-0.45 x the bounds diagonal, so lights overlap whatever the scene's size; or as
//    `range` says (generatedLightRange), before the reach test, so every light still reaches
//    something the camera sees with the range it keeps. Auto ranges draw without the reach test
//    and are then scaled by one fitted factor (fittedDensityScale).
//  - intensities proportional to range^2: the illuminance at a given fraction of the range is then
//    independent of the scene's scale (scaling a scene by s scales ranges by s, intensities by s^2).
// Throws Error("--lights", ...) when a count exceeds PUNCTUAL_MAX_LIGHT_CAPACITY (the command line
// also holds them to --max-lights) or the scene has no geometry to take bounds from. Call
// Scene::computeBounds() first.
void replaceLights(Scene& scene, uint32_t spotCount, uint32_t pointCount, uint64_t seed, const LightRange& range = {});

// Sets every spot and point light's range to `fraction` x the scene's bounds diagonal and scales
// its intensity by the square of the change, as replaceLights ties them: each light keeps its
// illuminance at a given share of its range. The bench holds the overlap fixed this way while it
// varies the light count, and varies it alone in the range series. Call computeBounds() first.
void setLightRanges(Scene& scene, float fraction);

// Keeps the first `spotCount` spots and the first `pointCount` points, in their order, and every
// directional light. Subsets of one generated set are nested: a sweep over counts only ever adds
// lights, so "more lights" never also means "other lights".
void keepFirstLights(Scene& scene, uint32_t spotCount, uint32_t pointCount);

struct LightCounts {
    uint32_t spot = 0;
    uint32_t point = 0;
    uint64_t seed = 1;
};

// Parses the `--lights` argument "S,P" or "S,P,SEED" (decimal, non-negative, no spaces; SEED
// defaults to 1). Throws Error("--lights", ...) for anything else, including counts over
// PUNCTUAL_MAX_LIGHT_CAPACITY.
LightCounts parseLightCounts(const std::string& text);

}  // namespace punctual
