#pragma once
// One geometry written as glTF in every way the loader can read triangles: a triangle list (the
// reference), a strip, fans, KHR_mesh_quantization's integer types, KHR_draco_mesh_compression
// and EXT_meshopt_compression, the last two built with the libraries' own encoders. The
// loader tests compare the triangles each file loads to the list's; the GPU tests compare the
// images. Each file is a whole scene: the geometry under a camera, a directional and a point
// light.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace punctual::testing {

// Quads, four corners each, counter-clockwise seen from the side the normal points to.
struct QuadGeometry {
    std::vector<glm::vec3> positions;  // 4 per quad
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    size_t quadCount() const { return positions.size() / 4; }
};

// An axis-aligned box from `min` to `max`, one quad a face (24 corners), UVs from `uvMin` to
// `uvMax` on every face.
QuadGeometry boxGeometry(const glm::vec3& min, const glm::vec3& max, const glm::vec2& uvMin = glm::vec2(0.0f),
                         const glm::vec2& uvMax = glm::vec2(1.0f));

// A cube whose corners every encoding here stores exactly, up to float rounding: its sides
// are equal (so each coordinate is either end of the range the quantizers use) and its
// coordinates are multiples of 1/8 (so the exponential filter's short mantissas hold them).
QuadGeometry exactCubeGeometry();

enum class GeometryEncoding {
    List,                           // indexed TRIANGLES, two triangles a quad: the reference
    Strip,                          // one indexed TRIANGLE_STRIP, quads joined by degenerate triangles
    Fan,                            // one indexed TRIANGLE_FAN primitive a quad
    QuantizedByte,                  // POSITION BYTE, NORMAL BYTE normalized, TEXCOORD_0 UNSIGNED_BYTE
    QuantizedUnsignedByteNormalized,  // POSITION UNSIGNED_BYTE normalized, NORMAL SHORT normalized,
                                      // TEXCOORD_0 BYTE normalized
    QuantizedShortNormalized,       // POSITION SHORT normalized, NORMAL BYTE normalized, TEXCOORD_0 SHORT
    QuantizedUnsignedShort,         // POSITION UNSIGNED_SHORT, NORMAL SHORT normalized,
                                    // TEXCOORD_0 UNSIGNED_SHORT normalized
    Draco,                          // Draco, sequential connectivity, lossless attributes
    DracoQuantized,                 // Draco, edgebreaker connectivity, quantized attributes
    Meshopt,                        // meshopt: float attributes, no filter, TRIANGLES indices (which
                                    // may start a triangle at another corner)
    MeshoptFiltered,                // meshopt: EXPONENTIAL positions, OCTAHEDRAL normals (BYTE),
                                    // UNSIGNED_SHORT normalized UVs, INDICES indices (UNSIGNED_INT)
};

const std::vector<GeometryEncoding>& allGeometryEncodings();
std::string encodingName(GeometryEncoding encoding);  // e.g. "quantized-byte", for file and test names

// How far a loaded value may lie from the geometry's own for `encoding` (world space for
// positions; 0 for the lossless encodings).
struct EncodingTolerance {
    float position = 0.0f;
    float normal = 0.0f;
    float uv = 0.0f;
};
EncodingTolerance encodingTolerance(GeometryEncoding encoding, const QuadGeometry& geometry);

// Writes `folder`/NAME.gltf and NAME.bin (NAME = encodingName) and returns the .gltf's path.
std::string writeGeometryScene(const std::string& folder, const QuadGeometry& geometry, GeometryEncoding encoding);

}  // namespace punctual::testing
