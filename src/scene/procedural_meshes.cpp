#include "scene/procedural_meshes.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "scene/box_faces.h"
#include "scene/light_generator.h"
#include "scene/texture_mips.h"

namespace punctual {

glm::vec2 unitCircle(uint32_t k, uint32_t n) {
    // Reduce to the first quadrant exactly, in integers: 4k/n = quadrant + rest/n, so the angle
    // is quadrant x (pi/2) + x with x = (pi/2) rest/n in [0, pi/2).
    const uint64_t quarterSteps = uint64_t(k % n) * 4;
    const uint32_t quadrant = uint32_t(quarterSteps / n);
    const uint64_t rest = quarterSteps - uint64_t(quadrant) * n;
    const float x = 1.57079633f * float(rest) / float(n);
    const float x2 = x * x;
    // Taylor series to x^13 and x^14, by Horner: the first term left out is below
    // (pi/2)^15 / 15! = 7e-10, far under a float's rounding.
    const float s = x * (1.0f - x2 / 6.0f * (1.0f - x2 / 20.0f * (1.0f - x2 / 42.0f * (1.0f - x2 / 72.0f *
                        (1.0f - x2 / 110.0f * (1.0f - x2 / 156.0f))))));
    const float c = 1.0f - x2 / 2.0f * (1.0f - x2 / 12.0f * (1.0f - x2 / 30.0f * (1.0f - x2 / 56.0f *
                        (1.0f - x2 / 90.0f * (1.0f - x2 / 132.0f * (1.0f - x2 / 182.0f))))));
    switch (quadrant) {  // a quarter turn maps (cos, sin) to (-sin, cos)
        case 0: return {c, s};
        case 1: return {-s, c};
        case 2: return {-c, -s};
        default: return {s, -c};
    }
}

uint32_t MeshBuilder::addVertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv) {
    vertices_.push_back(Vertex{position, normal, uv, uv * 0.5f});
    return uint32_t(vertices_.size() - 1);
}

void MeshBuilder::addBox(const glm::vec3& min, const glm::vec3& max) {
    // The faces and their corners: scene/box_faces.h.
    const glm::vec3 center = (min + max) * 0.5f;
    const glm::vec3 half = (max - min) * 0.5f;
    for (const BoxFace& face : kBoxFaces) {
        const uint32_t base = uint32_t(vertices_.size());
        for (const glm::vec2& corner : kBoxFaceCorners) {
            addVertex(center + (face.n + face.u * corner.x + face.v * corner.y) * half, face.n,
                      glm::vec2((corner.x + 1.0f) * 0.5f, 1.0f - (corner.y + 1.0f) * 0.5f));
        }
        for (const uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices_.push_back(base + i);
    }
}

void MeshBuilder::addLathe(std::span<const glm::vec2> profile, uint32_t segments) {
    const uint32_t points = uint32_t(profile.size());
    if (points < 2 || segments < 3) return;
    // Around: angle 2 pi k / segments, k = 0 .. segments (the seam twice, for its texture
    // coordinate u = 1). Up the profile: a normal across its slope, (dy, -dr) in the (radius, y)
    // plane, from the neighbours on either side (one-sided at the ends), so the sides shade smooth.
    std::vector<glm::vec2> around(segments + 1);
    for (uint32_t k = 0; k <= segments; ++k) around[k] = unitCircle(k, segments);
    const uint32_t sideBase = uint32_t(vertices_.size());
    for (uint32_t j = 0; j < points; ++j) {
        const glm::vec2 slope = profile[std::min(j + 1, points - 1)] - profile[j > 0 ? j - 1 : 0];
        const glm::vec2 across = glm::normalize(glm::vec2(slope.y, -slope.x));  // (radial, y)
        for (uint32_t k = 0; k <= segments; ++k) {
            const glm::vec2 d = around[k];
            const float radius = profile[j].x;
            addVertex(glm::vec3(radius * d.x, profile[j].y, radius * d.y), glm::vec3(across.x * d.x, across.y, across.x * d.y),
                      glm::vec2(float(k) / float(segments), 1.0f - float(j) / float(points - 1)));
        }
    }
    // Seen from outside, a larger k lies to the left (the angle turns from +x towards +z), so the
    // quad lower-right a, upper-right d, upper-left c, lower-left b runs counter-clockwise.
    const uint32_t row = segments + 1;
    for (uint32_t j = 0; j + 1 < points; ++j) {
        for (uint32_t k = 0; k < segments; ++k) {
            const uint32_t a = sideBase + j * row + k;
            const uint32_t b = a + 1;
            const uint32_t d = a + row;
            const uint32_t c = d + 1;
            indices_.insert(indices_.end(), {a, d, c, a, c, b});
        }
    }
    // The caps: fans over each end's ring. (p0, pk, pk+1) turns from +x towards +z, which faces -y:
    // the bottom's order; the top's is reversed.
    for (const bool top : {false, true}) {
        const glm::vec2 end = top ? profile[points - 1] : profile[0];
        const glm::vec3 normal(0.0f, top ? 1.0f : -1.0f, 0.0f);
        const uint32_t base = uint32_t(vertices_.size());
        for (uint32_t k = 0; k < segments; ++k) {
            const glm::vec2 d = around[k];
            addVertex(glm::vec3(end.x * d.x, end.y, end.x * d.y), normal, glm::vec2(0.5f + 0.5f * d.x, 0.5f + 0.5f * d.y));
        }
        for (uint32_t k = 1; k + 1 < segments; ++k) {
            if (top) {
                indices_.insert(indices_.end(), {base, base + k + 1, base + k});
            } else {
                indices_.insert(indices_.end(), {base, base + k, base + k + 1});
            }
        }
    }
}

void MeshBuilder::addCard(const glm::vec3& center, const glm::vec3& u, const glm::vec3& v, float halfU, float halfV) {
    const glm::vec3 normal = glm::cross(u, v);
    const uint32_t base = uint32_t(vertices_.size());
    // A card is one face of a box, seen from +n: the same corners (scene/box_faces.h).
    for (const glm::vec2& corner : kBoxFaceCorners) {
        addVertex(center + u * (corner.x * halfU) + v * (corner.y * halfV), normal,
                  glm::vec2((corner.x + 1.0f) * 0.5f, 1.0f - (corner.y + 1.0f) * 0.5f));
    }
    indices_.insert(indices_.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

uint32_t MeshBuilder::appendTo(Scene& scene, const std::string& name, uint32_t material) const {
    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    mesh.firstIndex = uint32_t(scene.indices.size());
    mesh.indexCount = uint32_t(indices_.size());
    mesh.vertexOffset = uint32_t(scene.vertices.size());
    mesh.vertexCount = uint32_t(vertices_.size());
    for (const Vertex& vertex : vertices_) mesh.localBounds.extend(vertex.position);
    scene.vertices.insert(scene.vertices.end(), vertices_.begin(), vertices_.end());
    scene.indices.insert(scene.indices.end(), indices_.begin(), indices_.end());
    scene.meshes.push_back(std::move(mesh));
    return uint32_t(scene.meshes.size() - 1);
}

Texture leafTexture(uint32_t side, uint64_t seed) {
    Texture texture;
    texture.name = "leaves";
    texture.width = side;
    texture.height = side;
    texture.rgba.assign(size_t(side) * side * 4, 0);
    // Leaves are ellipses along a stem up the middle of the card (texture v = 1 at the bottom):
    // leaf i springs from the stem at height t_i and points up and out to one side. A texel is in
    // a leaf where (a / length)^2 + (b / width)^2 <= 1, a and b its coordinates along and across
    // the leaf's axis from the leaf's centre.
    struct Leaf {
        glm::vec2 center, axis;
        float length, width;
        float shade;
    };
    PortableRandom random(seed);
    std::vector<Leaf> leaves;
    constexpr int kLeaves = 11;
    for (int i = 0; i < kLeaves; ++i) {
        const float t = 0.12f + 0.8f * float(i) / float(kLeaves - 1);  // up the stem, 0 = bottom
        const float sideSign = i % 2 == 0 ? 1.0f : -1.0f;
        const glm::vec2 axis = glm::normalize(glm::vec2(sideSign * random.uniform(0.6f, 1.0f), random.uniform(0.4f, 0.9f)));
        const float length = random.uniform(0.13f, 0.2f) * (1.1f - 0.4f * t);
        const glm::vec2 base(0.5f, t);
        leaves.push_back({base + axis * length, axis, length, length * random.uniform(0.3f, 0.45f),
                          random.uniform(0.75f, 1.1f)});
    }
    for (uint32_t y = 0; y < side; ++y) {
        for (uint32_t x = 0; x < side; ++x) {
            const glm::vec2 p((float(x) + 0.5f) / float(side), 1.0f - (float(y) + 0.5f) / float(side));
            float shade = 0.0f;
            if (std::abs(p.x - 0.5f) < 0.012f && p.y < 0.95f) shade = 0.6f;  // the stem
            for (const Leaf& leaf : leaves) {
                const glm::vec2 d = p - leaf.center;
                const float a = glm::dot(d, leaf.axis) / leaf.length;
                const float b = (d.x * leaf.axis.y - d.y * leaf.axis.x) / leaf.width;
                if (a * a + b * b <= 1.0f) shade = leaf.shade * (std::abs(b) < 0.08f ? 0.8f : 1.0f);  // the vein darker
            }
            if (shade <= 0.0f) continue;
            uint8_t* texel = &texture.rgba[(size_t(y) * side + x) * 4];
            texel[0] = uint8_t(std::min(255.0f, 70.0f * shade));
            texel[1] = uint8_t(std::min(255.0f, 140.0f * shade));
            texel[2] = uint8_t(std::min(255.0f, 45.0f * shade));
            texel[3] = 255;
        }
    }
    generateMipmaps(texture);
    return texture;
}

}  // namespace punctual
