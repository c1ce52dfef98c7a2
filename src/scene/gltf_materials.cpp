// glTF materials -> punctual Materials: metallic-roughness factors; base-colour and emissive
// textures with their samplers, texture coordinate sets (KHR_texture_transform may override
// them) and transforms; emission with KHR_materials_emissive_strength; alphaMode and doubleSided.
// Each image is turned into a Texture once, with its mip chain, however many materials use it.
#include <algorithm>
#include <cmath>

#include "core/concat.h"
#include "core/error.h"
#include "core/log.h"
#include "scene/gltf_detail.h"
#include "scene/texture_mips.h"

namespace punctual::gltf_detail {
namespace {

std::string inQuotes(const std::string& name) { return "'" + name + "'"; }

// glTF sampler enums (the WebGL values the spec reuses).
constexpr int kNearest = 9728;
constexpr int kLinear = 9729;
constexpr int kNearestMipmapNearest = 9984;
constexpr int kLinearMipmapNearest = 9985;
constexpr int kNearestMipmapLinear = 9986;
constexpr int kLinearMipmapLinear = 9987;
constexpr int kClampToEdge = 33071;
constexpr int kMirroredRepeat = 33648;
constexpr int kRepeat = 10497;

const tinygltf::Value* member(const tinygltf::ExtensionMap& extensions, const char* extension, const char* name) {
    const auto found = extensions.find(extension);
    if (found == extensions.end() || !found->second.IsObject() || !found->second.Has(name)) return nullptr;
    return &found->second.Get(name);
}

}  // namespace

MaterialConverter::MaterialConverter(const tinygltf::Model& model, const std::string& path,
                                     const ImageDecoding& decoding, const UriFiles& files,
                                     std::vector<Texture>& textures)
    : model_(model), path_(path), decoding_(decoding), files_(files), textures_(textures) {}

void MaterialConverter::fail(const std::string& problem) const { throw Error(path_, problem); }

Material MaterialConverter::convert(size_t index) {
    const tinygltf::Material& source = model_.materials[index];
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    Material material;
    material.name = source.name.empty() ? "material " + std::to_string(index) : source.name;
    const std::string who = "material " + inQuotes(material.name);
    // The spec bounds these factors to [0, 1]; the shading model assumes it.
    if (pbr.baseColorFactor.size() == 4)
        material.baseColorFactor =
            glm::clamp(glm::vec4(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                                 float(pbr.baseColorFactor[2]), float(pbr.baseColorFactor[3])),
                       0.0f, 1.0f);
    material.metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
    material.roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
    material.doubleSided = source.doubleSided;
    material.baseColorTexture = textureRef(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                           pbr.baseColorTexture.extensions, who, "base colour");

    // Emission. The spec bounds emissiveFactor to [0, 1] and leaves brighter emitters to
    // KHR_materials_emissive_strength, but files from before the extension (the Cornell box's
    // lamp: 10) write larger factors; they are kept, since they say what the author meant.
    if (source.emissiveFactor.size() == 3) {
        const glm::vec3 factor(float(source.emissiveFactor[0]), float(source.emissiveFactor[1]),
                               float(source.emissiveFactor[2]));
        if (!std::isfinite(factor.x) || !std::isfinite(factor.y) || !std::isfinite(factor.z))
            fail(who + ": emissiveFactor is not finite");
        material.emissiveFactor = glm::max(factor, glm::vec3(0.0f));
    }
    if (const tinygltf::Value* strength =
            member(source.extensions, "KHR_materials_emissive_strength", "emissiveStrength")) {
        const double value = strength->IsNumber() ? strength->GetNumberAsDouble() : -1.0;
        if (!(value >= 0.0) || !std::isfinite(float(value)))
            fail(who + ": KHR_materials_emissive_strength's emissiveStrength must be a finite number >= 0");
        material.emissiveStrength = float(value);
    }
    material.emissiveTexture = textureRef(source.emissiveTexture.index, source.emissiveTexture.texCoord,
                                          source.emissiveTexture.extensions, who, "emissive");

    if (source.alphaMode == "MASK") {
        material.alphaMode = AlphaMode::Mask;
        if (!(source.alphaCutoff >= 0.0) || !std::isfinite(source.alphaCutoff))
            fail(who + ": alphaCutoff must be a finite number >= 0");
        material.alphaCutoff = float(source.alphaCutoff);
    } else if (source.alphaMode == "BLEND") {
        material.alphaMode = AlphaMode::Blend;
    } else if (source.alphaMode != "OPAQUE" && !source.alphaMode.empty()) {
        fail(who + ": alphaMode " + inQuotes(source.alphaMode) + " is not OPAQUE, MASK or BLEND");
    }
    return material;
}

TextureRef MaterialConverter::textureRef(int textureIndex, int texCoord, const tinygltf::ExtensionMap& extensions,
                                         const std::string& who, const char* slot) {
    TextureRef ref;
    if (textureIndex < 0) return ref;
    if (size_t(textureIndex) >= model_.textures.size())
        fail(who + " uses texture " + std::to_string(textureIndex) + ", which does not exist");
    const tinygltf::Texture& texture = model_.textures[size_t(textureIndex)];

    // KHR_texture_transform: offset, rotation, scale, and a texCoord that overrides the
    // textureInfo's.
    const auto number = [&](const tinygltf::Value& value, const char* what) {
        const double x = value.IsNumber() ? value.GetNumberAsDouble() : std::nan("");
        if (!std::isfinite(float(x))) fail(who + ": KHR_texture_transform's " + what + " is not a finite number");
        return float(x);
    };
    const auto pair = [&](const char* name, glm::vec2 fallback) {
        const tinygltf::Value* value = member(extensions, "KHR_texture_transform", name);
        if (!value) return fallback;
        if (!value->IsArray() || value->ArrayLen() != 2)
            fail(who + ": KHR_texture_transform's " + name + " is not an array of two numbers");
        return glm::vec2(number(value->Get(0), name), number(value->Get(1), name));
    };
    ref.transform.offset = pair("offset", glm::vec2(0.0f));
    ref.transform.scale = pair("scale", glm::vec2(1.0f));
    if (const tinygltf::Value* rotation = member(extensions, "KHR_texture_transform", "rotation"))
        ref.transform.rotation = number(*rotation, "rotation");
    if (const tinygltf::Value* set = member(extensions, "KHR_texture_transform", "texCoord")) {
        if (!set->IsInt()) fail(who + ": KHR_texture_transform's texCoord is not an integer");
        texCoord = set->GetNumberAsInt();
    }
    if (texCoord < 0 || texCoord > 1) {
        log::warn(path_ + ": " + who + ": the " + slot + " texture reads TEXCOORD_" + std::to_string(texCoord) +
                  ", but only TEXCOORD_0 and TEXCOORD_1 are read; using the factor alone");
        return ref;
    }
    ref.texCoord = uint32_t(texCoord);
    ref.sampler = sampler(texture.sampler, who);

    // EXT_texture_webp names the WebP image, preferred where it decoded; the plain source is the
    // fallback the extension asks files to carry.
    int imageIndex = texture.source;
    if (const tinygltf::Value* webp = member(texture.extensions, "EXT_texture_webp", "source"); webp && webp->IsInt()) {
        const int webpImage = webp->GetNumberAsInt();
        if (webpImage >= 0 && size_t(webpImage) < model_.images.size() && imageDecoded(webpImage))
            imageIndex = webpImage;
    }
    if (imageIndex < 0 || size_t(imageIndex) >= model_.images.size()) {
        log::warn(path_ + ": " + who + ": texture " + std::to_string(textureIndex) + " has no image we can decode; using " +
                  (std::string(slot) == "emissive" ? "emissiveFactor" : "baseColorFactor") + " instead");
        return ref;
    }
    ref.image = textureOfImage(imageIndex, who, slot);
    return ref;
}

TextureSampler MaterialConverter::sampler(int samplerIndex, const std::string& who) const {
    TextureSampler result;  // no sampler: repeat, and the implementation's choice of filter: trilinear
    if (samplerIndex < 0) return result;
    if (size_t(samplerIndex) >= model_.samplers.size())
        fail(who + ": a texture uses sampler " + std::to_string(samplerIndex) + ", which does not exist");
    const tinygltf::Sampler& source = model_.samplers[size_t(samplerIndex)];
    const std::string name = "sampler " + std::to_string(samplerIndex);
    switch (source.magFilter) {
        case -1: break;
        case kNearest: result.magFilter = TextureFilter::Nearest; break;
        case kLinear: result.magFilter = TextureFilter::Linear; break;
        default: fail(name + ": magFilter " + std::to_string(source.magFilter) + " is not NEAREST or LINEAR");
    }
    switch (source.minFilter) {
        case -1: break;
        case kNearest: result.minFilter = TextureFilter::Nearest; result.mipmaps = false; break;
        case kLinear: result.minFilter = TextureFilter::Linear; result.mipmaps = false; break;
        case kNearestMipmapNearest: result.minFilter = TextureFilter::Nearest; result.mipFilter = TextureFilter::Nearest; break;
        case kLinearMipmapNearest: result.minFilter = TextureFilter::Linear; result.mipFilter = TextureFilter::Nearest; break;
        case kNearestMipmapLinear: result.minFilter = TextureFilter::Nearest; result.mipFilter = TextureFilter::Linear; break;
        case kLinearMipmapLinear: result.minFilter = TextureFilter::Linear; result.mipFilter = TextureFilter::Linear; break;
        default: fail(name + ": minFilter " + std::to_string(source.minFilter) + " is not a glTF filter");
    }
    const auto wrap = [&](int mode, const char* axis) {
        switch (mode) {
            case kRepeat: return TextureWrap::Repeat;
            case kMirroredRepeat: return TextureWrap::MirroredRepeat;
            case kClampToEdge: return TextureWrap::ClampToEdge;
            default: fail(name + ": " + axis + " " + std::to_string(mode) + " is not a glTF wrap mode");
        }
    };
    result.wrapU = wrap(source.wrapS, "wrapS");
    result.wrapV = wrap(source.wrapT, "wrapT");
    return result;
}

bool MaterialConverter::imageDecoded(int imageIndex) const {
    const tinygltf::Image& image = model_.images[size_t(imageIndex)];
    const size_t expectedBytes = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0)) * 4;
    return !image.image.empty() && image.image.size() == expectedBytes;
}

std::string MaterialConverter::describeImage(int imageIndex) const {
    const tinygltf::Image& image = model_.images[size_t(imageIndex)];
    if (!image.uri.empty()) return concat("image ", imageIndex, " '", image.uri, "'");
    const std::string name = image.name.empty() ? "" : concat(" '", image.name, "'");
    if (image.bufferView >= 0) return concat("image ", imageIndex, name, " (in buffer view ", image.bufferView, ")");
    return concat("image ", imageIndex, name, " (embedded)");
}

int MaterialConverter::textureOfImage(int imageIndex, const std::string& who, const char* slot) {
    if (const auto known = textureOfImage_.find(imageIndex); known != textureOfImage_.end()) return known->second;
    const tinygltf::Image& image = model_.images[size_t(imageIndex)];
    int result = -1;
    if (imageDecoded(imageIndex)) {
        Texture texture;
        texture.name = !image.uri.empty() ? image.uri : !image.name.empty() ? image.name : describeImage(imageIndex);
        texture.width = uint32_t(image.width);
        texture.height = uint32_t(image.height);
        texture.rgba = image.image;
        generateMipmaps(texture);
        result = int(textures_.size());
        textures_.push_back(std::move(texture));
    } else {
        std::string reason = "has no pixel data";
        if (const auto failure = decoding_.failures.find(imageIndex); failure != decoding_.failures.end())
            reason = "cannot be decoded (" + failure->second + ")";
        else if (!image.uri.empty() && !files_.problemWith(image.uri).empty())
            reason = "cannot be read (" + files_.problemWith(image.uri) + ")";
        else if (!image.uri.empty())
            reason = "cannot be read (missing, empty or unreadable file)";
        // One warning per image, however many materials use it.
        const bool emissive = std::string(slot) == "emissive";
        log::warn(path_ + ": " + who + ": " + slot + " " + describeImage(imageIndex) + " " + reason + "; using " +
                  (emissive ? "emissiveFactor" : "baseColorFactor") + " instead");
    }
    textureOfImage_[imageIndex] = result;
    return result;
}

}  // namespace punctual::gltf_detail
