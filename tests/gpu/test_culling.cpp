// Light culling against brute force: every light-grid method's images (tiled, clustered,
// tiled-2.5d, zbin, zbin-2d) are bit-identical to brute force on the default scene and on adversarial scenes, a
// CPU reference of the tile, cluster and depth-mask tests shows no light reaching a pixel is ever
// culled, and per-object lists lose light where an object is lit by more than 8 lights.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <map>
#include <memory>
#include <set>

#include "culling.h"
#include "culling_test_scenes.h"
#include "gpu_test_support.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "scene/outdoor_scene.h"
#include "scene/study_scenes.h"
#include "shading.h"

namespace punctual {
namespace {

using render::LightListMethod;

// Every scene's lights kept, however many (a frame's grid has a bit for each light it keeps).
render::RenderSettings settingsFor(LightListMethod method, uint32_t width = 256, uint32_t height = 144) {
    render::RenderSettings settings = testing::renderSettings(width, height);
    settings.method = method;
    settings.maxLights = {PUNCTUAL_MAX_LIGHT_CAPACITY, PUNCTUAL_MAX_LIGHT_CAPACITY};
    return settings;
}

// The index-array words the lists of a grid's cells take (culling.h, lightListWords), from its
// masks: what the counting frame must have sized the array to.
uint64_t indexListWords(const std::vector<uint32_t>& masks, uint32_t gridWords) {
    uint64_t words = 0;
    for (size_t cell = 0; cell < masks.size() / gridWords; ++cell) {
        uint32_t count = 0;
        for (uint32_t w = 0; w < gridWords; ++w) count += uint32_t(std::popcount(masks[cell * gridWords + w]));
        if (count > 0) words += gpu::lightListWords(count);
    }
    return words;
}

// One kernel's run against the reference grid: its grid read back as masks must be `expected` word
// for word; with index lists also its image `expectedImage`, and its index array exactly as long
// as the lists (indexListWords).
struct KernelRun {
    bool subgroupKernel = false;
    uint32_t tileThreads = 0;
    bool indexLists = false;
    size_t comparedWords = 0;
};

KernelRun compareKernelGrid(vk::Context& context, const Scene& scene, const render::RenderSettings& settings,
                            const std::string& trace, const std::vector<uint32_t>& expected, const ImageRgba8& expectedImage) {
    render::Renderer renderer(context, scene, settings);
    const render::LightGridLayout& layout = renderer.gridLayout();
    const KernelRun run{layout.subgroupKernel, layout.tileThreads, layout.indexLists, expected.size()};
    // The 64-invocation reference's own settings: nothing to compare.
    if (settings.tileThreads == 64 && !layout.subgroupKernel) return run;
    SCOPED_TRACE(trace + ", " + std::to_string(layout.tileThreads) + " invocations" +
                 (layout.subgroupKernel ? ", subgroup kernel" : ""));
    const ImageRgba8 image = renderer.render(1, 0).image;
    const std::vector<uint32_t> actual = renderer.readLightGrid();
    EXPECT_EQ(actual.size(), expected.size());
    size_t differing = 0;
    for (size_t i = 0; i < std::min(actual.size(), expected.size()); ++i) differing += actual[i] != expected[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u);
    if (layout.indexLists) {
        EXPECT_TRUE(image.pixels == expectedImage.pixels);
        const uint64_t words = indexListWords(expected, layout.gridWords);
        EXPECT_EQ(renderer.readLightIndexWordsUsed(), words);
        EXPECT_EQ(renderer.lightListBytes(), 4 * (uint64_t(layout.cellCount()) + 1 + std::max<uint64_t>(words, 1)));
    }
    return run;
}

ImageRgba8 renderImage(vk::Context& context, const Scene& scene, const render::RenderSettings& settings) {
    render::Renderer renderer(context, scene, settings);
    return renderer.render(1, 0).image;
}

struct ReferenceCheck {
    size_t reachingPairs = 0;       // (pixel, light) with attenuation > 0
    size_t culledOnGpu = 0;         // of those, missing from the GPU's cell
    size_t culledByReference = 0;   // of those, missing from the CPU reference's cell
    size_t maskBits = 0;            // bits compared between the GPU and CPU masks (occupied cells)
    size_t maskDisagreements = 0;
    size_t coarseBits = 0;           // coarse pass: (big tile, light) pairs compared
    size_t coarseDisagreements = 0;  // of those, where the GPU and CPU coarse masks differ
    size_t coarseKept = 0;           // of those, lights the GPU's coarse pass kept
    size_t fineOutsideCoarse = 0;    // (tile, light) bits set in a fine cell but not its big tile
};

// Rebuilds every cell's masks on the CPU with the shared culling.h tests and checks, pixel by
// pixel, that every light with attenuation x cone > 0 at the pixel's surface point is in its
// cell, in both the GPU's grid and the CPU reference.
ReferenceCheck checkAgainstReference(render::Renderer& renderer) {
    const render::LightGridLayout& layout = renderer.gridLayout();
    const uint32_t width = renderer.settings().width;
    const uint32_t height = renderer.settings().height;
    const std::vector<float> depth = renderer.readDepth();
    const std::vector<uint32_t> grid = renderer.readLightGrid();
    const std::vector<uint32_t> coarseGrid = renderer.readCoarseGrid();
    const gpu::GpuDepthRange range = renderer.readDepthRange();
    const FrameLights& lights = renderer.lights();
    const glm::mat4& projection = renderer.projection();
    const glm::vec2 depthToView(projection[3][2], projection[2][2]);
    const glm::vec4 ndcToView(1.0f / projection[0][0], 1.0f / projection[1][1], projection[2][0], projection[2][1]);
    const glm::mat4 inverseViewProjection = glm::inverse(projection * renderer.view());
    const uint32_t lightCount = lights.spotCount + lights.pointCount;
    const uint32_t words = layout.gridWords;  // a cell's mask words (gpu::gridWordsOf the lights)
    EXPECT_EQ(words, gpu::gridWordsOf(lightCount));

    // The slice of a depth in the frame's stored slice starts: the shaders' search (culling.h).
    auto sliceOf = [&](float d) {
        return layout.slices > 1 ? gpu::clusterSliceOfDepth(d, range.sliceStartDepth, layout.slices) : 0u;
    };
    auto cellOf = [&](uint32_t x, uint32_t y) {
        return ((y / layout.tileSize) * layout.tilesX + x / layout.tileSize) * layout.slices + sliceOf(depth[size_t(y) * width + x]);
    };
    // The word and bit of a light in a cell: the culling kernel's mapping (culling.h).
    auto bitOf = [&](uint32_t light, uint32_t& word) {
        word = gpu::lightGridWord(light);
        return 1u << gpu::lightGridBit(light);
    };

    // Per-cell and per-tile depth extents, as the culling kernel finds them.
    std::vector<float> cellNear(layout.cellCount(), 1e30f), cellFar(layout.cellCount(), 0.0f);
    std::vector<float> tileNear(layout.tilesX * layout.tilesY, 1e30f), tileFar(layout.tilesX * layout.tilesY, 0.0f);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const float d = depth[size_t(y) * width + x];
            if (gpu::isBackgroundDepth(d)) continue;
            const uint32_t cell = cellOf(x, y);
            const float distance = gpu::viewDistanceFromDepth(d, depthToView);
            cellNear[cell] = std::min(cellNear[cell], distance);
            cellFar[cell] = std::max(cellFar[cell], distance);
            const uint32_t tile = cell / layout.slices;
            tileNear[tile] = std::min(tileNear[tile], distance);
            tileFar[tile] = std::max(tileFar[tile], distance);
        }
    }
    // tiled-2.5d: each tile's occupied depth cells over its extent (culling.h), as the kernel builds them.
    std::vector<uint32_t> tileDepthMask(layout.tilesX * layout.tilesY, 0u);
    if (layout.hasCullFlag(PUNCTUAL_CULL_DEPTH_MASK)) {
        for (uint32_t y = 0; y < height; ++y) {
            for (uint32_t x = 0; x < width; ++x) {
                const float d = depth[size_t(y) * width + x];
                if (gpu::isBackgroundDepth(d)) continue;
                const uint32_t tile = cellOf(x, y) / layout.slices;
                const float scale = gpu::depthMaskScale(tileNear[tile], tileFar[tile]);
                tileDepthMask[tile] |= 1u << gpu::depthMaskCell(gpu::viewDistanceFromDepth(d, depthToView), tileNear[tile], scale);
            }
        }
    }
    std::vector<gpu::CullLight> cullLights;
    for (const gpu::GpuPunctualLight& light : lights.packed) cullLights.push_back(gpu::makeCullLight(light, renderer.view()));
    // The screen rectangle (NDC) of `tiles` x `tiles` fine tiles from fine tile (tx, ty), cut at
    // the viewport as the kernels cut it.
    auto tileRect = [&](uint32_t tx, uint32_t ty, uint32_t tiles, glm::vec2& ndcMin, glm::vec2& ndcMax) {
        const uint32_t side = layout.tileSize * tiles;
        const glm::vec2 ndcA = glm::vec2(float(tx * layout.tileSize) / float(width), float(ty * layout.tileSize) / float(height)) * 2.0f - 1.0f;
        const glm::vec2 ndcB = glm::min(glm::vec2(float(tx * layout.tileSize + side) / float(width),
                                                  float(ty * layout.tileSize + side) / float(height)),
                                        glm::vec2(1.0f)) * 2.0f - 1.0f;
        ndcMin = glm::min(ndcA, ndcB);
        ndcMax = glm::max(ndcA, ndcB);
    };
    // The coarse pass: each big tile keeps the lights that meet its column, near to far plane.
    const uint32_t coarseTilesX = layout.coarseTilesX();
    std::vector<uint32_t> coarse(size_t(coarseTilesX) * layout.coarseTilesY() * words, 0u);
    for (uint32_t cy = 0; cy < layout.coarseTilesY(); ++cy) {
        for (uint32_t cx = 0; cx < coarseTilesX; ++cx) {
            glm::vec2 ndcMin, ndcMax;
            tileRect(cx * layout.coarseTiles, cy * layout.coarseTiles, layout.coarseTiles, ndcMin, ndcMax);
            const gpu::TileVolume column = gpu::makeTileColumn(ndcMin, ndcMax, depthToView, ndcToView);
            for (uint32_t light = 0; light < lightCount; ++light) {
                if (!gpu::lightMayTouchTile(cullLights[light], column)) continue;
                uint32_t word = 0;
                const uint32_t bit = bitOf(light, word);
                coarse[(size_t(cy) * coarseTilesX + cx) * words + word] |= bit;
            }
        }
    }
    // Clustered and tiled-2.5d (tiles up to 32 pixels, no transparent spans): the rectangle of
    // pixel columns and rows of each slice (per cluster) or depth cell (per tile and cell), as the
    // kernel marks them block by block. Clustered: a 2x2 block whose geometry lies in one slice
    // marks the whole block (cut at the tile's and the viewport's edge), another each of its
    // geometry pixels. tiled-2.5d: every cell the block's geometry falls in gets the whole block.
    const render::RenderSettings& settings = renderer.settings();
    const bool rectsMarked = layout.tileSize <= 32 && (renderer.cameraDraws().transparentDraws == 0 || settings.opaqueCullingDepth);
    const bool sliceRects = rectsMarked && layout.slices > 1;
    const bool depthCellRects = rectsMarked && layout.hasCullFlag(PUNCTUAL_CULL_DEPTH_MASK);
    const size_t rectCount = depthCellRects ? size_t(layout.tilesX) * layout.tilesY * PUNCTUAL_DEPTH_MASK_CELLS : layout.cellCount();
    std::vector<glm::uvec4> cellRect(rectCount, glm::uvec4(~0u, ~0u, 0u, 0u));  // first x, y; last x, y (pixels)
    auto markRect = [&](size_t key, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
        cellRect[key] = glm::uvec4(std::min(cellRect[key].x, x0), std::min(cellRect[key].y, y0),
                                   std::max(cellRect[key].z, x1), std::max(cellRect[key].w, y1));
    };
    for (uint32_t y = 0; (sliceRects || depthCellRects) && y < height; y += 2) {
        for (uint32_t x = 0; x < width; x += 2) {
            const uint32_t tile = (y / layout.tileSize) * layout.tilesX + x / layout.tileSize;
            const uint32_t x1 = std::min(x + 1, std::min((x / layout.tileSize + 1) * layout.tileSize, width) - 1);
            const uint32_t y1 = std::min(y + 1, std::min((y / layout.tileSize + 1) * layout.tileSize, height) - 1);
            std::vector<glm::uvec3> geometry;  // x, y, depth bits of the block's pixels with geometry
            for (uint32_t py = y; py <= y1; ++py) {
                for (uint32_t px = x; px <= x1; ++px) {
                    const float d = depth[size_t(py) * width + px];
                    if (!gpu::isBackgroundDepth(d)) geometry.push_back(glm::uvec3(px, py, std::bit_cast<uint32_t>(d)));
                }
            }
            auto depthOf = [](const glm::uvec3& p) { return std::bit_cast<float>(p.z); };
            if (depthCellRects) {
                const float scale = gpu::depthMaskScale(tileNear[tile], tileFar[tile]);
                uint32_t cells = 0;
                for (const glm::uvec3& p : geometry) {
                    cells |= 1u << gpu::depthMaskCell(gpu::viewDistanceFromDepth(depthOf(p), depthToView), tileNear[tile], scale);
                }
                for (; cells; cells &= cells - 1) markRect(size_t(tile) * PUNCTUAL_DEPTH_MASK_CELLS + std::countr_zero(cells), x, y, x1, y1);
                continue;
            }
            if (geometry.empty()) continue;
            float nearest = 0.0f, farthest = 2.0f;
            for (const glm::uvec3& p : geometry) {
                nearest = std::max(nearest, depthOf(p));
                farthest = std::min(farthest, depthOf(p));
            }
            const size_t tileCell = size_t(tile) * layout.slices;
            if (sliceOf(nearest) == sliceOf(farthest)) {
                markRect(tileCell + sliceOf(nearest), x, y, x1, y1);
                continue;
            }
            for (const glm::uvec3& p : geometry) markRect(tileCell + sliceOf(depthOf(p)), p.x, p.y, p.x, p.y);
        }
    }
    // The NDC rectangle of a pixel rectangle (first x, y; last x, y), as the kernel computes it.
    auto pixelRectNdc = [&](const glm::uvec4& r, glm::vec2& ndcMin, glm::vec2& ndcMax) {
        const glm::vec2 a = glm::vec2(float(r.x) / float(width), float(r.y) / float(height)) * 2.0f - 1.0f;
        const glm::vec2 b = glm::vec2(float(r.z + 1) / float(width), float(r.w + 1) / float(height)) * 2.0f - 1.0f;
        ndcMin = glm::min(a, b);
        ndcMax = glm::max(a, b);
    };
    std::vector<uint32_t> reference(grid.size(), 0u);
    for (uint32_t ty = 0; ty < layout.tilesY; ++ty) {
        for (uint32_t tx = 0; tx < layout.tilesX; ++tx) {
            glm::vec2 ndcMin, ndcMax;
            tileRect(tx, ty, 1, ndcMin, ndcMax);
            const uint32_t tile = ty * layout.tilesX + tx;
            if (tileFar[tile] == 0.0f) continue;
            const size_t coarseBase =
                layout.coarseTiles ? (size_t(ty / layout.coarseTiles) * coarseTilesX + tx / layout.coarseTiles) * words : 0;
            const float maskScale = gpu::depthMaskScale(tileNear[tile], tileFar[tile]);
            for (uint32_t slice = 0; slice < layout.slices; ++slice) {
                const uint32_t cell = tile * layout.slices + slice;
                if (cellFar[cell] == 0.0f) continue;
                // zbin-2d: the tile at every depth, near plane to far plane (the bins hold depth).
                // Clustered: the slice's rectangle of pixels.
                glm::vec2 cellMin = ndcMin, cellMax = ndcMax;
                if (sliceRects) pixelRectNdc(cellRect[cell], cellMin, cellMax);
                const gpu::TileVolume volume =
                    layout.hasCullFlag(PUNCTUAL_CULL_DEPTHLESS_TILES) ? gpu::makeTileColumn(ndcMin, ndcMax, depthToView, ndcToView)
                                 : gpu::makeTileVolume(cellMin, cellMax, cellNear[cell], cellFar[cell], ndcToView);
                for (uint32_t light = 0; light < lightCount; ++light) {
                    uint32_t word = 0;
                    const uint32_t bit = bitOf(light, word);
                    if (layout.coarseTiles && !(coarse[coarseBase + word] & bit)) continue;
                    if (!gpu::lightMayTouchTile(cullLights[light], volume)) continue;
                    if (layout.hasCullFlag(PUNCTUAL_CULL_DEPTH_MASK)) {
                        // An occupied depth cell within the light's extent whose segment it meets.
                        uint32_t cells = gpu::lightDepthMask(cullLights[light], tileNear[tile], maskScale) & tileDepthMask[tile];
                        bool meets = false;
                        for (; cells && !meets; cells &= cells - 1) {
                            const uint32_t depthCell = uint32_t(std::countr_zero(cells));
                            glm::vec2 rectMin = ndcMin, rectMax = ndcMax;
                            if (depthCellRects) pixelRectNdc(cellRect[size_t(tile) * PUNCTUAL_DEPTH_MASK_CELLS + depthCell], rectMin, rectMax);
                            meets = gpu::lightMayTouchTile(
                                cullLights[light], gpu::makeDepthCellVolume(rectMin, rectMax, depthCell, tileNear[tile], tileFar[tile], ndcToView));
                        }
                        if (!meets) continue;
                    }
                    reference[cell * words + word] |= bit;
                }
            }
        }
    }

    ReferenceCheck check;
    for (size_t i = 0; i < grid.size(); ++i) {
        if (cellFar[i / words] == 0.0f) continue;  // empty cells are never read, nor written
        for (uint32_t b = 0; b < 32; ++b) {
            ++check.maskBits;
            check.maskDisagreements += ((grid[i] ^ reference[i]) >> b) & 1u;
        }
        if (layout.coarseTiles) {
            const uint32_t tile = uint32_t(i / words) / layout.slices;
            const uint32_t tx = tile % layout.tilesX;
            const uint32_t ty = tile / layout.tilesX;
            const size_t coarseWord =
                (size_t(ty / layout.coarseTiles) * coarseTilesX + tx / layout.coarseTiles) * words + i % words;
            check.fineOutsideCoarse += size_t(std::popcount(grid[i] & ~coarseGrid[coarseWord]));
        }
    }
    for (size_t i = 0; i < coarseGrid.size() && layout.coarseTiles; ++i) {
        // Only the bits of real lights: the last word's low bits.
        const uint32_t word = uint32_t(i % words);
        const uint32_t first = gpu::lightGridFirstLight(word);
        const uint32_t end = std::min(lightCount, first + 32);
        for (uint32_t light = first; light < end; ++light) {
            const uint32_t bit = 1u << gpu::lightGridBit(light);
            ++check.coarseBits;
            check.coarseKept += (coarseGrid[i] & bit) ? 1 : 0;
            check.coarseDisagreements += ((coarseGrid[i] ^ coarse[i]) & bit) ? 1 : 0;
        }
    }
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const float d = depth[size_t(y) * width + x];
            if (gpu::isBackgroundDepth(d)) continue;
            const glm::vec4 ndc((float(x) + 0.5f) / float(width) * 2.0f - 1.0f, (float(y) + 0.5f) / float(height) * 2.0f - 1.0f, d, 1.0f);
            const glm::vec4 world = inverseViewProjection * ndc;
            const glm::vec3 position = glm::vec3(world) / world.w;
            const uint32_t cell = cellOf(x, y);
            // zbin: the pixel's bin mask, ANDed with the tile's as forward.frag does (all ones otherwise).
            const uint32_t* binMask = layout.zBins ? renderer.zBins()->binMask(zBinOfDepth(renderer.zBins()->gpu, d)) : nullptr;
            for (uint32_t light = 0; light < lightCount; ++light) {
                if (gpu::punctualAttenuation(lights.packed[light], position) <= 0.0f) continue;
                ++check.reachingPairs;
                uint32_t word = 0;
                const uint32_t bit = bitOf(light, word);
                const uint32_t binWord = binMask ? binMask[word] : ~0u;
                if (!(grid[cell * words + word] & binWord & bit)) ++check.culledOnGpu;
                if (!(reference[cell * words + word] & binWord & bit)) ++check.culledByReference;
            }
        }
    }
    return check;
}

std::vector<testing::NamedScene> allScenes() {
    std::vector<testing::NamedScene> scenes = testing::adversarialCullingScenes();
    scenes.insert(scenes.begin(), testing::NamedScene{"default scene", makeDefaultScene()});
    scenes.push_back({"1,000 lights", testing::manyLightsScene(600, 400)});
    return scenes;
}

TEST(Culling, CulledImagesAreBitIdenticalToBruteForce) {
    auto context = testing::makeValidatedContext();
    for (const testing::NamedScene& named : allScenes()) {
        SCOPED_TRACE(named.name);
        const ImageRgba8 brute = renderImage(*context, named.scene, settingsFor(LightListMethod::Brute));
        testing::saveTestImage("culling-" + named.name, brute);
        // Not a vacuous comparison: every scene shows lit pixels.
        EXPECT_GT(testing::fractionBrighterThan(brute, 24), 0.02);
        for (LightListMethod method : render::gridMethods()) {
            // Tile sizes 8, 16 and 32 with the coarse pass (8 and 4 fine tiles a big tile's side,
            // 2 at 32), and 16 without it.
            const std::vector<std::pair<uint32_t, bool>> tilings = {{8u, true}, {16u, true}, {32u, true}, {16u, false}};
            for (const auto& [tileSize, coarse] : tilings) {
                render::RenderSettings settings = settingsFor(method);
                settings.tileSize = tileSize;
                settings.coarseTiles = coarse;
                const ImageRgba8 culled = renderImage(*context, named.scene, settings);
                EXPECT_TRUE(culled.pixels == brute.pixels)
                    << render::methodName(method) << " tile " << tileSize << (coarse ? "" : ", no coarse pass");
            }
        }
    }
    testing::expectNoValidationMessages(*context);
}

TEST(Culling, NoLightReachingAPixelIsCulled) {
    auto context = testing::makeValidatedContext();
    for (const testing::NamedScene& named : allScenes()) {
        for (LightListMethod method : render::gridMethods()) {
            for (bool coarse : {true, false}) {
                SCOPED_TRACE(named.name + " / " + render::methodName(method) + (coarse ? "" : ", no coarse pass"));
                render::RenderSettings settings = settingsFor(method);
                settings.coarseTiles = coarse;
                render::Renderer renderer(*context, named.scene, settings);
                renderer.render(1, 0);
                const ReferenceCheck check = checkAgainstReference(renderer);
                EXPECT_GT(check.reachingPairs, 1000u);
                EXPECT_EQ(check.culledOnGpu, 0u);
                EXPECT_EQ(check.culledByReference, 0u);
                // The GPU kernel and the CPU reference run the same tests on the same inputs; only
                // float rounding at a shape's very edge may flip a bit.
                EXPECT_LE(double(check.maskDisagreements), 1e-3 * double(check.maskBits));
                // The coarse pass: the same on the CPU, and every fine cell's lights within its
                // big tile's. Not vacuous: the default scene's 96 lights spread over the hall, so
                // its big tiles drop some (the adversarial scenes' few lights each span the
                // 256x144 frame's 4x3 big tiles).
                EXPECT_EQ(check.coarseBits > 0, coarse);
                EXPECT_LE(double(check.coarseDisagreements), 1e-3 * double(check.coarseBits));
                EXPECT_EQ(check.fineOutsideCoarse, 0u);
                if (coarse && named.name == "default scene") {
                    EXPECT_LT(double(check.coarseKept), 0.9 * double(check.coarseBits));
                }
            }
        }
    }
    testing::expectNoValidationMessages(*context);
}

TEST(Culling, EveryKernelAndWorkgroupSizeWritesTheSameGrids) {
    // The culling kernels run one subgroup a tile (the device's subgroup size, 8 invocations on
    // lavapipe): tiled, tiled-2.5d, zbin and zbin-2d in tile_culling.comp and clustered in
    // cluster_culling.comp where the device has subgroup arithmetic, all with --subgroup-tiles off
    // in light_culling.comp. Each must write the masks of light_culling.comp at 64 invocations a tile,
    // word for word (for clustered, also in the cells no pixel reads: the same cells written): on the
    // default scene at tile sizes 8, 16 (with and without the coarse pass) and 13 (odd: half
    // blocks), and with 64 invocations in the subgroup kernels, more than a subgroup on most
    // devices (their several-subgroup paths); on glass panes (transparent spans), on the near posts
    // (foreground before background in one tile) and on the outdoor street (sky between objects).
    // Sanitized: the default scene at 16 with the coarse pass, 13 without and 64 invocations.
    // (Renderers are costly to make on lavapipe: the cases are few.)
    // Every kernel also writes index lists (--light-lists indices): read back as masks they must be
    // these masks word for word, their image the masks' image, and the index array exactly as long
    // as the lists (the counting frame's size: no word claimed twice or left over).
    auto context = testing::makeValidatedContext();
    const bool subgroupArithmetic = context->computeSubgroupArithmetic();
    struct Case {
        uint32_t tileSize;
        bool coarse;
        uint32_t threads;  // 0: the device's subgroup size
    };
    const std::vector<std::pair<testing::NamedScene, std::vector<Case>>> runs = {
        {{"default scene", makeDefaultScene()},
         {{8u, true, 0u}, {16u, true, 0u}, {16u, false, 0u}, {13u, false, 0u}, {16u, true, 64u}}},
        {{"glass panes", study::glassPanesScene(9.0f)}, {{16u, true, 0u}}},
        {testing::adversarialCullingScenes()[3], {{13u, false, 0u}}},
        // Sky between the street's objects: blocks holding background pixels, which give their
        // slice (clustered) the whole block's rectangle when their geometry lies in one slice.
        {{"outdoor", makeOutdoorScene()}, {{16u, true, 0u}}},
        // Past the design notes' 96: cells of 32 words, the subgroup kernels' eleven triples
        // against the shared-memory kernel's four chunks.
        {{"1,000 lights", testing::manyLightsScene(600, 400)}, {{16u, true, 0u}, {13u, false, 0u}}},
        // Candidate lists (subgroup_tiles.glsl) past their buffer's 2,048: with no coarse pass every
        // light is a candidate, so a tile's candidates are tested in several fills, at the subgroup
        // size and at 64 invocations (several subgroups' sums on most devices).
        {{"2,500 lights", testing::manyLightsScene(1500, 1000)}, {{16u, false, 0u}, {16u, false, 64u}}},
    };
    size_t comparedWords = 0;
    size_t setWords = 0;
    size_t indexListsCompared = 0;
    std::set<LightListMethod> subgroupMethods;
    for (const auto& [named, cases] : runs) {
        for (LightListMethod method : render::gridMethods()) {
            for (const Case& c : cases) {
                render::RenderSettings settings = settingsFor(method);
                settings.tileSize = c.tileSize;
                settings.coarseTiles = c.coarse;
                settings.subgroupTiles = false;
                settings.tileThreads = 64;
                render::Renderer reference(*context, named.scene, settings);
                const ImageRgba8 expectedImage = reference.render(1, 0).image;
                const std::vector<uint32_t> expected = reference.readLightGrid();
                for (size_t i = 0; i < expected.size(); ++i) setWords += expected[i] != 0 ? 1 : 0;
                // The default kernel, and also the shared-memory one at the subgroup size, each
                // writing both list forms.
                for (bool subgroupTiles : {true, false}) {
                    for (const render::LightListFormInfo& form : render::kLightListForms) {
                        settings.subgroupTiles = subgroupTiles;
                        settings.tileThreads = c.threads;
                        settings.lightLists = form.value;
                        const std::string trace = named.name + " / " + render::methodName(method) + " tile " +
                                                  std::to_string(c.tileSize) + (c.coarse ? "" : ", no coarse pass") +
                                                  ", " + form.name;
                        const KernelRun run = compareKernelGrid(*context, named.scene, settings, trace, expected, expectedImage);
                        if (c.threads == 64 && !run.subgroupKernel) break;  // that is the reference
                        EXPECT_EQ(run.tileThreads, c.threads ? c.threads : std::clamp(context->subgroupSize(), 4u, 64u));
                        if (run.subgroupKernel) subgroupMethods.insert(method);
                        comparedWords += run.comparedWords;
                        indexListsCompared += run.indexLists ? 1 : 0;
                    }
                }
            }
        }
    }
    // Not vacuous: grids with lights were compared, and where the device has subgroup arithmetic
    // every grid method ran a subgroup kernel.
    EXPECT_GT(setWords, comparedWords / 20);
    EXPECT_GT(indexListsCompared, 2 * render::gridMethods().size());
    // every grid method whose culling flags a one-subgroup kernel implements ran one.
    if (subgroupArithmetic) {
        std::set<LightListMethod> expected;
        for (LightListMethod method : render::gridMethods()) {
            const render::LightListMethodInfo& info = render::methodInfo(method);
            const uint32_t implemented = info.depthSlices ? PUNCTUAL_CLUSTER_KERNEL_CULL_FLAGS : PUNCTUAL_TILE_KERNEL_CULL_FLAGS;
            if ((info.cullFlags & ~implemented) == 0) expected.insert(method);
        }
        EXPECT_EQ(subgroupMethods, expected);
        EXPECT_TRUE(subgroupMethods.contains(LightListMethod::Tiled));
    }
    testing::expectNoValidationMessages(*context);
}

// A method with a culling flag the one-subgroup kernels lack culls with the general kernel,
// light_culling.comp, which implements every flag: a new flag needs its case there alone
// (culling.h, docs/EXTENDING.md).
TEST(Culling, AFlagTheSubgroupKernelsLackKeepsAMethodOnTheGeneralKernel) {
    constexpr uint32_t kUnknownToSubgroupKernels = 1u << 31;
    static_assert((kUnknownToSubgroupKernels & (PUNCTUAL_TILE_KERNEL_CULL_FLAGS | PUNCTUAL_CLUSTER_KERNEL_CULL_FLAGS)) == 0);
    for (const render::LightListMethodInfo& method : render::kLightListMethods) {
        if (!method.usesLightGrid()) continue;
        render::LightListMethodInfo flagged = method;
        const auto layoutOf = [](const render::LightListMethodInfo& info) {
            return render::LightGridLayout::forMethod(info, 640, 360, 16, 16, true, 32, true);
        };
        flagged.cullFlags |= kUnknownToSubgroupKernels;
        EXPECT_FALSE(layoutOf(flagged).subgroupKernel) << method.name;
        EXPECT_EQ(layoutOf(flagged).cullFlags, flagged.cullFlags) << method.name;  // the flag reaches the kernel
        const uint32_t implemented = method.depthSlices ? PUNCTUAL_CLUSTER_KERNEL_CULL_FLAGS : PUNCTUAL_TILE_KERNEL_CULL_FLAGS;
        EXPECT_EQ(layoutOf(method).subgroupKernel, (method.cullFlags & ~implemented) == 0) << method.name;
    }
}

TEST(Culling, NoGridMethodBeatsExactListsOfItsGranularity) {
    // A pixel's list is a function of its list cell (tile, cluster, tile and z-bin) and must hold
    // every light reaching any pixel of that cell, so no lossless method tests fewer than the
    // exact lists (the floor). Methods sharing their cells share their floor; finer cells lower it.
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    std::map<LightListMethod, CullingStats> stats;
    for (LightListMethod method : render::gridMethods()) {
        render::RenderSettings settings = settingsFor(method);
        settings.collectLightStats = true;
        render::Renderer renderer(*context, scene, settings);
        renderer.render(1, 0);
        stats[method] = computeCullingStats(renderer.readLightStats());
        const CullingStats& s = stats[method];
        SCOPED_TRACE(render::methodName(method));
        EXPECT_GT(s.affectingPerPixel, 1.0);  // not vacuous: lights reach the pixels
        EXPECT_GT(s.floorEfficiency, 1.0);
        EXPECT_GE(s.efficiency, s.floorEfficiency);
    }
    // Methods whose lists have the same cells (the same light source and slices, whatever their
    // culling flags) share their floor.
    for (const auto& [method, methodStats] : stats) {
        const render::LightListMethodInfo& info = render::methodInfo(method);
        for (const auto& [other, otherStats] : stats) {
            const render::LightListMethodInfo& otherInfo = render::methodInfo(other);
            if (info.source.value == otherInfo.source.value && info.depthSlices == otherInfo.depthSlices) {
                EXPECT_EQ(methodStats.floorEfficiency, otherStats.floorEfficiency) << info.name << ", " << otherInfo.name;
            }
        }
    }
    EXPECT_LT(stats[LightListMethod::Clustered].floorEfficiency, stats[LightListMethod::Tiled].floorEfficiency);
    EXPECT_LT(stats[LightListMethod::ZBin].floorEfficiency, stats[LightListMethod::Tiled].floorEfficiency);
    testing::expectNoValidationMessages(*context);
}

TEST(Culling, DepthAwareMethodsSeparateForegroundFromBackground) {
    // In the near-posts scene the posts' lights must not land in the clusters of the far floor
    // behind the same tiles, nor the lights floating between them in the occupied depth cells of
    // either: clustered and tiled-2.5d test fewer lights per pixel than tiled there.
    auto context = testing::makeValidatedContext();
    const Scene scene = testing::adversarialCullingScenes()[3].scene;
    auto testedPerPixel = [&](LightListMethod method) {
        render::RenderSettings settings = settingsFor(method);
        settings.collectLightStats = true;
        render::Renderer renderer(*context, scene, settings);
        renderer.render(1, 0);
        const CullingStats stats = computeCullingStats(renderer.readLightStats());
        EXPECT_EQ(stats.pixelsMissingLight, 0u) << render::methodName(method);
        return stats.testedPerPixel;
    };
    const double tiled = testedPerPixel(LightListMethod::Tiled);
    const double clustered = testedPerPixel(LightListMethod::Clustered);
    EXPECT_LT(clustered, tiled * 0.9) << "tiled " << tiled << ", clustered " << clustered;
    // The 2.5D mask drops the lights floating in the gap between the posts and the floor from the
    // tiles on the posts' edges (measured 4.5% of tiled's tests; the lights hugging a surface
    // stay, their depth extents holding occupied cells). Without the mask it equals tiled.
    const double masked = testedPerPixel(LightListMethod::Tiled25D);
    EXPECT_LT(masked, tiled * 0.98) << "tiled " << tiled << ", tiled-2.5d " << masked;
    testing::expectNoValidationMessages(*context);
}

TEST(Culling, PerObjectListsLoseLightOnALargeFloorUnderMoreThanEightLights) {
    auto context = testing::makeValidatedContext();
    const Scene scene = testing::largeFloorScene(14);
    render::RenderSettings settings = settingsFor(LightListMethod::PerObject);
    settings.collectLightStats = true;
    render::Renderer perObject(*context, scene, settings);
    const ImageRgba8 perObjectImage = perObject.render(1, 0).image;
    const CullingStats stats = computeCullingStats(perObject.readLightStats());
    const ImageRgba8 bruteImage = renderImage(*context, scene, settingsFor(LightListMethod::Brute));

    EXPECT_EQ(perObject.perObjectLists().objectsOverCap, 1u);
    EXPECT_EQ(perObject.perObjectLists().maxCandidates, 14u);
    EXPECT_EQ(stats.maxTested, 8u);
    EXPECT_GT(stats.affectingPerPixel, 8.0);  // the floor really is lit by more than 8 lights
    EXPECT_GT(stats.missedEnergy, 0.05);
    EXPECT_GT(stats.pixelsMissingLight, stats.coveredPixels / 2);
    EXPECT_LT(testing::meanLuma(perObjectImage), testing::meanLuma(bruteImage));
    testing::expectNoValidationMessages(*context);
}

TEST(Culling, PerObjectMatchesBruteForceWhenNoObjectIsOverTheCap) {
    auto context = testing::makeValidatedContext();
    const Scene scene = testing::largeFloorScene(6);
    render::RenderSettings settings = settingsFor(LightListMethod::PerObject);
    render::Renderer perObject(*context, scene, settings);
    const ImageRgba8 perObjectImage = perObject.render(1, 0).image;
    EXPECT_EQ(perObject.perObjectLists().objectsOverCap, 0u);
    EXPECT_TRUE(perObjectImage.pixels == renderImage(*context, scene, settingsFor(LightListMethod::Brute)).pixels);
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
