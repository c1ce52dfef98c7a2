#include "lights/shadow_view_signature.h"

#include "core/byte_words.h"

namespace punctual {
namespace {

// 64-bit FNV-1a over 64-bit words.
class WordHash {
public:
    void add(uint64_t word) {
        hash_ ^= word;
        hash_ *= 0x100000001b3ull;
    }
    void addBytes(const void* data, size_t size) {
        addBytesAsWords(data, size, [&](uint64_t word) { add(word); });
    }
    template <typename T>
    void addValue(const T& value) {
        addBytes(&value, sizeof(T));
    }
    uint64_t value() const { return hash_; }

private:
    uint64_t hash_ = 0xcbf29ce484222325ull;
};

uint64_t fingerprint(const Scene& scene, const Object& object) {
    WordHash hash;
    hash.addValue(object.model);
    const Mesh& mesh = scene.meshes.at(object.mesh);
    hash.addBytes(scene.vertices.data() + mesh.vertexOffset, size_t(mesh.vertexCount) * sizeof(Vertex));
    hash.addBytes(scene.indices.data() + mesh.firstIndex, size_t(mesh.indexCount) * sizeof(uint32_t));
    const Material& material = scene.materials.at(mesh.material);
    hash.add(uint64_t(material.alphaMode));
    hash.addValue(material.alphaCutoff);
    hash.addValue(material.baseColorFactor.a);
    const TextureRef& texture = material.baseColorTexture;
    hash.add(uint64_t(int64_t(texture.image)));
    hash.add(texture.texCoord);
    hash.addValue(texture.sampler);
    hash.addValue(texture.transform);
    return hash.value();
}

}  // namespace

std::vector<uint64_t> casterFingerprints(const Scene& scene, const ShadowPlan& plan) {
    std::vector<uint64_t> fingerprints(scene.objects.size(), 0);
    std::vector<bool> casts(scene.objects.size(), false);
    for (const ShadowView& view : plan.views) {
        for (const uint32_t object : view.casters) casts.at(object) = true;
    }
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        if (casts[i]) fingerprints[i] = fingerprint(scene, scene.objects[i]);
    }
    return fingerprints;
}

uint64_t shadowViewSignature(const ShadowView& view, const std::vector<uint64_t>& fingerprints) {
    return shadowViewSignature(view, view.casters, fingerprints);
}

uint64_t shadowViewSignature(const ShadowView& view, const std::vector<uint32_t>& casters,
                             const std::vector<uint64_t>& fingerprints) {
    WordHash hash;
    hash.addValue(view.gpu.viewProjection);
    hash.add(view.resolution);
    hash.add(view.isCascade);
    hash.add(casters.size());
    for (const uint32_t object : casters) {
        hash.add(object);
        hash.add(fingerprints.at(object));
    }
    return hash.value();
}

uint64_t shadowPageSignature(const ShadowView& view, uint32_t level, uint32_t column, uint32_t row,
                             const std::vector<uint32_t>& casters, const std::vector<uint64_t>& fingerprints) {
    WordHash hash;
    hash.add(shadowViewSignature(view, casters, fingerprints));
    hash.add(level);
    hash.add(uint64_t(column) | uint64_t(row) << 32);
    return hash.value();
}

}  // namespace punctual
