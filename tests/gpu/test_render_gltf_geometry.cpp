// The cube of tests/support/gltf_geometry_variants.h in every encoding the loader reads, rendered
// and compared with the render of its plain triangle list. The encodings that give the list's
// triangles bit for bit (strips, fans, lossless Draco, meshopt with the exponential filter on
// coordinates it holds exactly and an INDICES stream) must give the same image bit for bit. The
// others may change a pixel by one 8-bit step, no more: those that store the cube through a node
// transform or quantize it (KHR_mesh_quantization, quantized Draco) move vertices by float
// rounding, and meshopt's TRIANGLES codec starts some triangles at another corner, which changes
// the rounding of the interpolated values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "gltf_geometry_variants.h"
#include "gpu_test_support.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"

namespace punctual {
namespace {

using testing::GeometryEncoding;

bool bitExact(GeometryEncoding encoding) {
    switch (encoding) {
        case GeometryEncoding::Strip:
        case GeometryEncoding::Fan:
        case GeometryEncoding::Draco:
        case GeometryEncoding::MeshoptFiltered: return true;
        default: return false;
    }
}

TEST(RenderGltfGeometry, EveryEncodingRendersLikeTheTriangleList) {
    testing::TempFolder folder;
    const testing::QuadGeometry cube = testing::exactCubeGeometry();
    auto context = testing::makeValidatedContext();
    const auto render = [&](GeometryEncoding encoding) {
        const Scene scene = loadGltf(testing::writeGeometryScene(folder.path(), cube, encoding));
        EXPECT_EQ(scene.triangleCount(), 12u) << testing::encodingName(encoding);
        render::Renderer renderer(*context, scene, testing::renderSettings(96, 96));
        return renderer.render(1, 0).image;
    };
    const ImageRgba8 reference = render(GeometryEncoding::List);
    testing::saveTestImage("gltf-geometry-list", reference);
    // The comparisons below mean something only if the cube covers a good part of the frame,
    // lit: three faces in view, each under a different mix of the two lights.
    size_t covered = 0;
    for (size_t i = 0; i < reference.pixels.size(); i += 4)
        if (reference.pixels[i] + reference.pixels[i + 1] + reference.pixels[i + 2] > 0) ++covered;
    ASSERT_GT(covered, size_t(96 * 96 / 5)) << "the cube covers too little of the frame to compare";

    for (GeometryEncoding encoding : testing::allGeometryEncodings()) {
        if (encoding == GeometryEncoding::List) continue;
        const std::string name = testing::encodingName(encoding);
        const ImageRgba8 image = render(encoding);
        ASSERT_EQ(image.pixels.size(), reference.pixels.size()) << name;
        int largest = 0;
        size_t differing = 0;
        for (size_t i = 0; i < image.pixels.size(); ++i) {
            const int difference = std::abs(int(image.pixels[i]) - int(reference.pixels[i]));
            largest = std::max(largest, difference);
            if (difference != 0) ++differing;
        }
        if (bitExact(encoding)) {
            EXPECT_EQ(differing, 0u) << name << ": " << differing << " channel values differ, by up to " << largest;
        } else {
            EXPECT_LE(largest, 1) << name << ": " << differing << " channel values differ, by up to " << largest;
        }
        if (largest != 0) testing::saveTestImage("gltf-geometry-" + name, image);
    }
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
