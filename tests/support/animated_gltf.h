#pragma once
// A small glTF file to animate (the animation tests, CPU and GPU): a 2 m square in the XY plane
// at z = 0 (node 0, its mesh with one morph target that moves every vertex 2 m along +z), a
// camera 3 m in front of it looking down -z (node 1) and a spot 2 m in front shining at it (node
// 2, KHR_lights_punctual). Channels are added as plain float arrays; write() puts them, with the
// geometry, in one data: URI buffer.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace punctual::testing {

struct AnimatedGltf {
    enum Node { kSquare = 0, kCamera = 1, kSpot = 2 };

    AnimatedGltf();

    // Adds a channel to animation `animation` (created as needed) driving `path` ("translation",
    // "rotation", "scale", "weights") of `node` with `interpolation`, keyframes `times` and their
    // flattened `values` (3 per CUBICSPLINE keyframe, as glTF stores them).
    void addChannel(size_t animation, int node, const std::string& path, const std::string& interpolation,
                    const std::vector<float>& times, const std::vector<float>& values);
    // Appends a FLOAT accessor of `components` numbers an element holding `values`; its index.
    int addAccessor(const std::vector<float>& values, size_t components);

    // The file's text, its buffer a data: URI.
    std::string text() const;
    // Writes text() to `path`; returns `path`.
    std::string write(const std::string& path) const;

    nlohmann::json doc;
    std::vector<unsigned char> bin;
};

}  // namespace punctual::testing
