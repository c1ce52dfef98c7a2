// Broken KHR_draco_mesh_compression and EXT_meshopt_compression data: each file must throw one
// punctual::Error line naming the file and what is broken (the primitive for Draco, the buffer
// view for meshopt), never crash or read out of bounds. The files start as the valid scenes of
// tests/support/gltf_geometry_variants.h and have one thing broken.
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "gltf_geometry_variants.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"

namespace punctual {
namespace {

using nlohmann::json;
using testing::GeometryEncoding;
using unit_testing::TempDir;

// A variant scene's JSON and binary buffer, to break and write back.
struct VariantFile {
    json doc;
    std::vector<unsigned char> bin;
    std::string path;

    VariantFile(const TempDir& dir, GeometryEncoding encoding) {
        path = testing::writeGeometryScene(dir.path().string(), testing::exactCubeGeometry(), encoding);
        std::ifstream gltf(path);
        doc = json::parse(gltf);
        std::ifstream binFile(dir.path() / doc["buffers"][0]["uri"].get<std::string>(), std::ios::binary);
        bin.assign(std::istreambuf_iterator<char>(binFile), std::istreambuf_iterator<char>());
    }

    const std::string& write() const {
        const std::string binPath = path.substr(0, path.rfind('/') + 1) + doc["buffers"][0]["uri"].get<std::string>();
        unit_testing::writeFile(binPath, bin);
        unit_testing::writeFile(path, doc.dump());
        return path;
    }

    json& draco() { return doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]; }
    json& meshopt(size_t view) { return doc["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]; }
};

// The error loading `file` gives, which must name the file, contain every one of `keywords`
// and be one line; "" (and a test failure) when it loads.
std::string expectLoadError(const VariantFile& file, const std::vector<std::string>& keywords) {
    const std::string& path = file.write();
    try {
        loadGltf(path);
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path), std::string::npos) << message;
        for (const std::string& keyword : keywords)
            EXPECT_NE(message.find(keyword), std::string::npos) << "expected '" << keyword << "' in: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
        return message;
    }
    ADD_FAILURE() << path << " loaded";
    return "";
}

// --- Draco -------------------------------------------------------------------------------------

const char* const kDracoPrimitive = "mesh 'draco' primitive 0: KHR_draco_mesh_compression";

class GltfDracoMalformed : public ::testing::TestWithParam<GeometryEncoding> {
protected:
    TempDir dir;
};

TEST_P(GltfDracoMalformed, EveryTruncationOfTheDracoDataIsAnError) {
    VariantFile file(dir, GetParam());
    const std::string primitive = GetParam() == GeometryEncoding::Draco ? "mesh 'draco' primitive 0"
                                                                        : "mesh 'draco-quantized' primitive 0";
    const size_t full = file.doc["bufferViews"][0]["byteLength"].get<size_t>();
    ASSERT_GT(full, 20u);
    for (size_t length = 0; length < full; length += (length < 32 ? 1 : 7)) {
        file.doc["bufferViews"][0]["byteLength"] = length;
        const std::string message = expectLoadError(file, {primitive});
        if (::testing::Test::HasFailure()) {
            ADD_FAILURE() << "truncated to " << length << " of " << full << " bytes: " << message;
            return;
        }
    }
}

TEST_P(GltfDracoMalformed, CorruptedDracoDataNeverCrashes) {
    VariantFile file(dir, GetParam());
    const size_t offset = file.doc["bufferViews"][0]["byteOffset"].get<size_t>();
    const size_t length = file.doc["bufferViews"][0]["byteLength"].get<size_t>();
    const std::vector<unsigned char> original = file.bin;
    std::mt19937 random(7);
    size_t errors = 0;
    for (int round = 0; round < 60; ++round) {
        file.bin = original;
        // A few bytes after the header changed: the decoder gets past the magic and version.
        for (int k = 0; k < 1 + round % 4; ++k) {
            const size_t at = offset + 8 + random() % (length - 8);
            file.bin[at] = static_cast<unsigned char>(random());
        }
        // Draco has no checksum: a changed byte may decode to other geometry, which loads or
        // fails later (e.g. coordinates too large for the scene's bounds). Either is fine.
        try {
            loadGltf(file.write());
        } catch (const Error& e) {
            ++errors;
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
    EXPECT_GT(errors, 0u) << "no corruption was noticed: the test changes nothing that matters";
}

INSTANTIATE_TEST_SUITE_P(Encodings, GltfDracoMalformed,
                         ::testing::Values(GeometryEncoding::Draco, GeometryEncoding::DracoQuantized),
                         [](const ::testing::TestParamInfo<GeometryEncoding>& encoding) {
                             return encoding.param == GeometryEncoding::Draco ? std::string("lossless")
                                                                              : std::string("quantized");
                         });

class GltfDracoChecks : public ::testing::Test {
protected:
    TempDir dir;
    VariantFile file{dir, GeometryEncoding::Draco};
};

TEST_F(GltfDracoChecks, NotDracoDataAtAll) {
    const size_t offset = file.doc["bufferViews"][0]["byteOffset"].get<size_t>();
    std::memcpy(file.bin.data() + offset, "NOTDRACO", 8);
    expectLoadError(file, {kDracoPrimitive, "does not decode"});
}

TEST_F(GltfDracoChecks, AttributeIdTheDataLacks) {
    file.draco()["attributes"]["NORMAL"] = 9;
    expectLoadError(file, {kDracoPrimitive, "NORMAL maps to Draco attribute 9, which the data lacks"});
}

TEST_F(GltfDracoChecks, AttributeIdNotAnInteger) {
    file.draco()["attributes"]["POSITION"] = "zero";
    expectLoadError(file, {kDracoPrimitive, "attribute POSITION has no Draco attribute id"});
}

TEST_F(GltfDracoChecks, MappedAttributeMissingFromThePrimitive) {
    file.doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
    expectLoadError(file, {"KHR_draco_mesh_compression maps NORMAL, which the primitive's attributes lack"});
}

TEST_F(GltfDracoChecks, AccessorCountDiffersFromTheDecodedVertices) {
    file.doc["accessors"][0]["count"] = 23;
    expectLoadError(file, {kDracoPrimitive, "accessor 0 has count 23 but the Draco data has 24 vertices"});
}

TEST_F(GltfDracoChecks, AccessorTypeDiffersFromTheDecodedAttribute) {
    file.doc["extensionsUsed"].push_back("KHR_mesh_quantization");
    file.doc["accessors"][0]["componentType"] = 5122;  // SHORT: Draco holds floats
    expectLoadError(file, {kDracoPrimitive, "holds FLOAT but accessor 0 says SHORT"});
}

TEST_F(GltfDracoChecks, IndexCountDiffersFromTheDecodedFaces) {
    file.doc["accessors"][3]["count"] = 30;
    expectLoadError(file, {kDracoPrimitive, "indices accessor 3 has count 30 but the Draco data has 12 triangles"});
}

TEST_F(GltfDracoChecks, BufferViewThatDoesNotExist) {
    file.draco()["bufferView"] = 17;
    expectLoadError(file, {kDracoPrimitive, "refers to buffer view 17, which does not exist"});
}

TEST_F(GltfDracoChecks, BufferViewPastItsBuffer) {
    file.doc["bufferViews"][0]["byteLength"] = file.bin.size() + 100;
    expectLoadError(file, {kDracoPrimitive, "reads past the end of buffer 0"});
}

TEST_F(GltfDracoChecks, ModeOtherThanTrianglesOrStrip) {
    file.doc["meshes"][0]["primitives"][0]["mode"] = 6;
    expectLoadError(file, {"needs mode TRIANGLES or TRIANGLE_STRIP, not mode 6"});
}

// --- meshopt -------------------------------------------------------------------------------------

// Views of the meshopt scene: 0 POSITION, 1 NORMAL, 2 TEXCOORD_0, 3 the indices.
class GltfMeshoptMalformed : public ::testing::Test {
protected:
    size_t compressedOffset(size_t view) { return file.meshopt(view)["byteOffset"].get<size_t>(); }

    TempDir dir;
    VariantFile file{dir, GeometryEncoding::Meshopt};
};

TEST_F(GltfMeshoptMalformed, UnknownStreamHeader) {
    file.bin[compressedOffset(0)] = 0x11;
    expectLoadError(file, {"buffer view 0: EXT_meshopt_compression: the data is not a stream meshoptimizer"});
}

TEST_F(GltfMeshoptMalformed, TruncatedVertexStream) {
    file.meshopt(1)["byteLength"] = file.meshopt(1)["byteLength"].get<size_t>() - 5;
    expectLoadError(file, {"buffer view 1: EXT_meshopt_compression: the compressed data is truncated or corrupt"});
}

TEST_F(GltfMeshoptMalformed, TruncatedIndexStream) {
    file.meshopt(3)["byteLength"] = file.meshopt(3)["byteLength"].get<size_t>() / 2;
    expectLoadError(file, {"buffer view 3: EXT_meshopt_compression: the compressed data is truncated or corrupt"});
}

TEST_F(GltfMeshoptMalformed, CorruptedStreamsNeverCrash) {
    const std::vector<unsigned char> original = file.bin;
    std::mt19937 random(11);
    for (int round = 0; round < 80; ++round) {
        file.bin = original;
        const size_t view = size_t(round % 4);
        const size_t offset = compressedOffset(view);
        const size_t length = file.meshopt(view)["byteLength"].get<size_t>();
        for (int k = 0; k < 1 + round % 3; ++k)
            file.bin[offset + 1 + random() % (length - 1)] = static_cast<unsigned char>(random());
        try {
            loadGltf(file.write());  // garbage vertex data decodes to garbage values, which may load
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
}

TEST_F(GltfMeshoptMalformed, CountThatDisagreesWithTheViewsLength) {
    file.meshopt(0)["count"] = 23;
    expectLoadError(file, {"buffer view 0: EXT_meshopt_compression: count * byteStride is not the view's byteLength 288"});
}

TEST_F(GltfMeshoptMalformed, StrideThatDisagreesWithTheView) {
    file.meshopt(2)["byteStride"] = 4;
    file.meshopt(2)["count"] = 48;
    expectLoadError(file, {"buffer view 2: EXT_meshopt_compression: byteStride 4 differs from the view's 8"});
}

TEST_F(GltfMeshoptMalformed, ForbiddenLayoutNeverReachesMeshoptimizer) {
    // Debian's meshoptimizer asserts these; the loader must refuse them first. (tinygltf
    // refuses a view's own byteStride of 6, so only the extension says it.)
    file.doc["bufferViews"][0].erase("byteStride");
    file.doc["bufferViews"][0]["byteLength"] = 144;
    file.meshopt(0)["byteStride"] = 6;
    expectLoadError(file, {"buffer view 0: EXT_meshopt_compression: ATTRIBUTES needs a byteStride divisible by 4"});
}

TEST_F(GltfMeshoptMalformed, UnknownModeAndFilter) {
    file.meshopt(0)["mode"] = "VERTICES";
    expectLoadError(file, {"buffer view 0: EXT_meshopt_compression: unknown mode 'VERTICES'"});
    file.meshopt(0)["mode"] = "ATTRIBUTES";
    file.meshopt(0)["filter"] = "SPHERICAL";
    expectLoadError(file, {"buffer view 0: EXT_meshopt_compression: unknown filter 'SPHERICAL'"});
}

TEST_F(GltfMeshoptMalformed, MissingMembers) {
    file.meshopt(1).erase("count");
    expectLoadError(file, {"buffer view 1: EXT_meshopt_compression: has no 'count'"});
}

TEST_F(GltfMeshoptMalformed, CompressedBytesOutsideTheirBuffer) {
    file.meshopt(0)["byteOffset"] = file.bin.size();
    expectLoadError(file, {"buffer view 0: EXT_meshopt_compression: its compressed bytes lie outside buffer 0"});
    file.meshopt(0)["byteOffset"] = 0;
    file.meshopt(0)["buffer"] = 1;  // the fallback buffer holds no data
    expectLoadError(file, {"buffer view 0: EXT_meshopt_compression: its compressed bytes lie outside buffer 1"});
}

TEST_F(GltfMeshoptMalformed, DecodedSizeNoCompressedDataCouldHold) {
    const size_t count = size_t(1) << 30;
    file.meshopt(0)["count"] = count;
    file.doc["bufferViews"][0]["byteLength"] = count * 12;
    file.doc["buffers"][1]["byteLength"] = count * 12 + 1024;
    expectLoadError(file, {"buffer view 0: EXT_meshopt_compression", "could hold"});
}

TEST_F(GltfMeshoptMalformed, PlainViewInTheFallbackBuffer) {
    // Only compressed views may use a fallback buffer: it holds no data to read.
    file.doc["bufferViews"][0].erase("extensions");
    expectLoadError(file, {"mesh 'meshopt' primitive 0", "reads past the end of buffer 1"});
}

TEST_F(GltfMeshoptMalformed, ImageInACompressedView) {
    file.doc["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
    expectLoadError(file, {"image 0 is stored in buffer view 2, which EXT_meshopt_compression compresses"});
}

TEST_F(GltfMeshoptMalformed, FallbackBufferWithAMissingFileIsNeverRead) {
    // A tagged fallback buffer may have a URI; its data is what decoding gives anyway.
    file.doc["buffers"][1]["uri"] = "not-there.bin";
    EXPECT_EQ(loadGltf(file.write()).triangleCount(), 12u);
}

}  // namespace
}  // namespace punctual
