#pragma once
// The scene model every part of punctual reads: the GPU passes, light setup and the Embree
// reference. It holds only what a glTF scene (or a built-in one) really has; nothing is padded
// to the per-frame caps here.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace punctual {

struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};

    bool empty() const { return min.x > max.x; }
    void extend(const glm::vec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
    void extend(const Bounds& b) { if (!b.empty()) { extend(b.min); extend(b.max); } }
    glm::vec3 center() const { return (min + max) * 0.5f; }
    glm::vec3 size() const { return max - min; }
    float radius() const { return glm::length(max - min) * 0.5f; }  // of the bounding sphere about center()
    Bounds transformed(const glm::mat4& m) const;  // AABB of the 8 transformed corners
};

// Interleaved vertex, 40 bytes; the layout the vertex shaders read. uv1 is glTF's TEXCOORD_1
// (zero where the file has none).
struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec2 uv1{0.0f};
};
static_assert(sizeof(Vertex) == 40);

// One mip level of a texture: RGBA8, rows top to bottom.
struct TextureLevel {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;
};

// Decoded texture: RGBA8, sRGB-encoded colour (glTF base-colour and emissive textures are sRGB),
// linear alpha. Level 0 is width x height x rgba; `mipLevels` holds levels 1.. down to 1x1 once
// generateMipmaps (scene/texture_mips.h) has run, which the glTF loader does for every texture.
struct Texture {
    std::string name;
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;
    std::vector<TextureLevel> mipLevels;

    uint32_t levelCount() const { return 1 + uint32_t(mipLevels.size()); }
};

// A glTF sampler, as Vulkan samples it (render/scene_gpu.cpp) and the reference mirrors it
// (reference/texture_sampler.h). glTF leaves an absent filter to the implementation: trilinear.
enum class TextureFilter : uint8_t { Nearest, Linear };
enum class TextureWrap : uint8_t { Repeat, MirroredRepeat, ClampToEdge };
struct TextureSampler {
    TextureFilter magFilter = TextureFilter::Linear;
    TextureFilter minFilter = TextureFilter::Linear;
    TextureFilter mipFilter = TextureFilter::Linear;
    bool mipmaps = true;  // false for glTF's minFilter NEAREST or LINEAR: level 0 only
    TextureWrap wrapU = TextureWrap::Repeat;
    TextureWrap wrapV = TextureWrap::Repeat;

    bool operator==(const TextureSampler&) const = default;
};

// KHR_texture_transform: uv' = T(offset) * R(rotation) * S(scale) * uv (the matrix is built in
// shaders/shared/materials.h, for the GPU and the reference alike).
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians
    glm::vec2 scale{1.0f};
};

// A material's use of a texture: which image, read through which sampler, from which texture
// coordinate set, transformed how.
struct TextureRef {
    int image = -1;         // index into Scene::textures, -1 for none
    uint32_t texCoord = 0;  // TEXCOORD_0 or TEXCOORD_1
    TextureSampler sampler;
    TextureTransform transform;

    bool present() const { return image >= 0; }
};

// glTF's alphaMode. OPAQUE ignores alpha; MASK keeps a fragment where alpha >= alphaCutoff and
// drops it elsewhere, in every pass that draws it (depth, forward, every shadow caster pass);
// BLEND is drawn after the opaque surfaces, blended over them.
enum class AlphaMode : uint8_t { Opaque, Mask, Blend };

// glTF metallic-roughness material, with emission (KHR_materials_emissive_strength) and alpha.
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};  // linear
    float metallic = 1.0f;            // glTF defaults
    float roughness = 1.0f;
    TextureRef baseColorTexture;
    // Emitted radiance (linear, the units of shaded radiance): emissiveFactor x emissiveStrength x
    // the emissive texture. The camera sees it; it lights nothing else.
    glm::vec3 emissiveFactor{0.0f};
    float emissiveStrength = 1.0f;
    TextureRef emissiveTexture;
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;  // MASK only
    // false: back faces (as wound in the file) are not drawn, and primary rays pass through them.
    // Shadow casters are two-sided either way (README, "Materials").
    bool doubleSided = false;

    glm::vec3 emission() const { return emissiveFactor * emissiveStrength; }
};

// A triangle list inside Scene::indices/vertices. Indices are relative to `vertexOffset`.
struct Mesh {
    std::string name;
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    uint32_t vertexOffset = 0;
    uint32_t vertexCount = 0;
    uint32_t material = 0;
    Bounds localBounds;
};

// One drawn instance of a mesh: one glTF primitive under one node.
struct Object {
    std::string name;
    uint32_t mesh = 0;
    glm::mat4 model{1.0f};
    Bounds worldBounds;
};

enum class LightType { Point, Spot, Directional };

struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 position{0.0f};           // world space (unused for directional)
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit, the direction the light shines (node -Z)
    glm::vec3 color{1.0f};              // linear RGB
    float intensity = 1.0f;             // candela (point, spot) or lux (directional)
    float range = 0.0f;                 // metres; always finite and > 0 for point and spot
    bool rangeDerived = false;          // true when glTF gave no range and we derived one
    float innerConeAngle = 0.0f;        // radians from the axis (spot)
    float outerConeAngle = 0.785398163f;  // radians from the axis (spot), glTF default pi/4
    bool castsShadow = true;
    float shadowStrength = 1.0f;        // 0: no shadow, 1: full (blends the shadow factor towards 1)
};

struct Camera {
    std::string name;
    glm::mat4 view{1.0f};   // world -> view (camera looks down its -Z)
    float yfov = 0.8f;      // radians
    float znear = 0.05f;
    float zfar = 100.0f;    // always finite: derived from the scene bounds when glTF gives none

    glm::vec3 position() const;
    // Vulkan clip space, y down, reversed Z: depth 1 at znear, 0 at zfar (see scene.cpp).
    glm::mat4 projection(float aspect) const;
};

struct Scene {
    std::string source;  // file path, or "built-in default scene"
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;  // never empty after loading: a default material is added
    std::vector<Texture> textures;
    std::vector<Object> objects;
    std::vector<Light> lights;
    Camera camera;
    bool cameraFromFile = false;
    Bounds bounds;  // world bounds of all objects
    // The length of the scene's motion, in seconds: its glTF animations' last keyframe, or its
    // built-in path's end (scene/scene_path.h); 0 for a still scene. `punctual play` plays this long.
    double animationSeconds = 0.0;

    size_t triangleCount() const { return indices.size() / 3; }
    void computeBounds();  // fills every Object::worldBounds and Scene::bounds
};

// The radius at which an infinite-range light is cut off. KHR_lights_punctual says an absent
// range means infinite; culling needs a finite one. We cut where the illuminance falls to
// kInfiniteRangeCutoffLux: I / d^2 = E_min  =>  d = sqrt(I / E_min). With the default exposure a
// pixel of white albedo lit by E_min shows about E_min / pi = 0.1% of full scale, below one 8-bit
// step, so the cut-off is invisible.
constexpr float kInfiniteRangeCutoffLux = 0.005f;
float derivedRange(float intensityCandela, const glm::vec3& color);

// A camera looking at the scene's bounds from the front-upper-right, with the bounding sphere
// inside the vertical field of view.
Camera fitCameraToBounds(const Bounds& bounds, float yfov = 0.8f);

// The narrowest angle one pixel of a frame may span, in radians: 2^-16. A float carries about
// 7 decimal digits (2^-24 relative), and a point's direction from the eye passes through several
// roundings (the world position, the view matrix, the projection, the depth buffer's inverse in
// the culling shaders), each about 2^-24 of the distances involved. At 2^-16 a pixel is 256 of
// those steps wide, so points still land in the right pixel; with yfov 1e-8 at 120 rows a pixel
// spans 1.7e-10 rad, 1/400 of one step, and the frame renders half black.
constexpr double kMinPixelAngle = 1.0 / 65536.0;

// Throws punctual::Error(source, ...) when the camera's field of view is too narrow for float
// precision at `height` pixel rows (kMinPixelAngle), naming the smallest yfov that renders.
void checkCameraPrecision(const Camera& camera, uint32_t height, const std::string& source);

// Throws punctual::Error(source, ...) when a light has out-of-range parameters (negative or NaN
// intensity, range <= 0, cone angles outside 0 <= inner < outer <= pi/2, non-finite position).
void validateLights(const std::vector<Light>& lights, const std::string& source);

}  // namespace punctual
