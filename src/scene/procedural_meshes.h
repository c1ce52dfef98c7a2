#pragma once
// Meshes built in code for the procedural scenes (scene/rooms_scene.h): boxes merged into one
// mesh, lathes (profiles turned about the vertical axis: columns, barrels, vases) and crossed
// foliage cards, plus the foliage's leaf texture. Everything is the same bit for bit on every run
// and platform: angles come from unitCircle (a polynomial of our own, not the maths library's
// sin/cos, whose last bit may differ between libraries).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual {

// (cos, sin) of 2 pi k / n, exact at the quarter turns, within 2e-7 elsewhere. Only +, *, / and
// integer arithmetic: the result is the same wherever IEEE floats are.
glm::vec2 unitCircle(uint32_t k, uint32_t n);

// Collects one mesh's vertices and triangles (counter-clockwise seen from the front), then
// appends them to a scene as one Mesh.
class MeshBuilder {
public:
    // An axis-aligned box between `min` and `max`: 24 vertices (flat normals), 12 triangles.
    void addBox(const glm::vec3& min, const glm::vec3& max);
    // The profile (radius, height), bottom to top, every radius > 0, turned about the y axis in
    // `segments` steps: 2 x segments x (points - 1) triangles for the sides (smooth normals from
    // the profile's slope), plus segments - 2 for each cap (a flat fan at the bottom and top).
    void addLathe(std::span<const glm::vec2> profile, uint32_t segments);
    // One rectangle centred on `center`, spanning +-halfU along `u` and +-halfV along `v` (unit,
    // perpendicular), facing cross(u, v), texture coordinates 0..1 with v = 0 at the top: 2 triangles.
    void addCard(const glm::vec3& center, const glm::vec3& u, const glm::vec3& v, float halfU, float halfV);

    size_t triangleCount() const { return indices_.size() / 3; }
    // Appends the mesh (local bounds included) and returns its index in scene.meshes.
    uint32_t appendTo(Scene& scene, const std::string& name, uint32_t material) const;

private:
    uint32_t addVertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv);

    std::vector<Vertex> vertices_;
    std::vector<uint32_t> indices_;
};

// Triangles of MeshBuilder::addLathe for a profile of `points` points.
constexpr uint64_t latheTriangles(uint32_t points, uint32_t segments) {
    return 2ull * segments * (points - 1) + 2ull * (segments - 2);
}

// A `side` x `side` RGBA8 texture of a spray of leaves on a stem: green (sRGB) where a leaf is,
// alpha 255 there and 0 between the leaves, for alphaMode MASK cards; every mip level generated.
Texture leafTexture(uint32_t side, uint64_t seed);

}  // namespace punctual
