#pragma once
// The six faces of an axis-aligned box, for every builder of box meshes (default_scene.cpp's
// appendBoxMesh, procedural_meshes.cpp's MeshBuilder): each face's outward normal n and in-plane
// axes u, v with cross(u, v) = n, so the corners (-u-v), (+u-v), (+u+v), (-u+v) of
// kBoxFaceCorners run counter-clockwise seen from outside (glTF front faces).
#include <array>

#include <glm/glm.hpp>

namespace punctual {

struct BoxFace {
    glm::vec3 n, u, v;
};

inline constexpr std::array<BoxFace, 6> kBoxFaces = {{
    {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
    {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
    {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
    {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},
    {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
}};

// A face's corners in (u, v), counter-clockwise seen from outside.
inline constexpr std::array<glm::vec2, 4> kBoxFaceCorners = {{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};

}  // namespace punctual
