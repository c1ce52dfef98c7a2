// Virtual shadow pages (--shadow-res virtual): the marking pass against its CPU mirror, Embree
// against receivers across page borders and level changes, the budget's coarsening, and the
// default scene's accuracy.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <set>

#include "core/image.h"
#include "gpu_test_support.h"
#include "lights/shadow_page_allocation.h"
#include "lights/shadow_sizing.h"
#include "lights/virtual_pages.h"
#include "scene/builtin_scenes.h"
#include "scene/default_scene.h"
#include "shadow_test_runs.h"

namespace punctual {
namespace {

using reference::PixelVerdict;

ShadowSettings virtualShadows() {
    ShadowSettings shadows;
    shadows.resolution = ShadowSettings::kVirtualResolution;
    return shadows;
}

uint64_t setBits(const std::vector<uint32_t>& words) {
    uint64_t bits = 0;
    for (const uint32_t word : words) bits += uint64_t(std::popcount(word));
    return bits;
}

// The GPU's marks and the CPU mirror's (markVirtualPagesOnCpu): pages marked by both, by one only.
struct MarkAgreement {
    uint64_t both = 0;
    uint64_t gpuOnly = 0;
    uint64_t cpuOnly = 0;
    double jaccard() const { return double(both) / double(std::max<uint64_t>(both + gpuOnly + cpuOnly, 1)); }
};

MarkAgreement compareMarks(const std::vector<uint32_t>& gpu, const std::vector<uint32_t>& cpu) {
    MarkAgreement agreement;
    for (size_t i = 0; i < std::min(gpu.size(), cpu.size()); ++i) {
        agreement.both += uint64_t(std::popcount(gpu[i] & cpu[i]));
        agreement.gpuOnly += uint64_t(std::popcount(gpu[i] & ~cpu[i]));
        agreement.cpuOnly += uint64_t(std::popcount(cpu[i] & ~gpu[i]));
    }
    return agreement;
}

void expectMarksAgree(const Scene& scene, uint32_t width, uint32_t height, const char* name) {
    auto context = testing::makeValidatedContext();
    const render::RenderSettings settings = testing::shadowRenderSettings(width, height, virtualShadows());
    render::Renderer renderer(*context, scene, settings);
    renderer.render(1, 0);
    const std::vector<uint32_t> gpu = renderer.readShadowPageMarks();
    const std::vector<uint32_t> cpu =
        markVirtualPagesOnCpu(scene, renderer.lights(), renderer.shadowPlan(), width, height, settings.shadows);
    ASSERT_EQ(gpu.size(), cpu.size());
    const MarkAgreement agreement = compareMarks(gpu, cpu);
    std::printf("[ virtual  ] %s: %llu pages marked by both, %llu by the GPU only, %llu by the CPU only\n", name,
                static_cast<unsigned long long>(agreement.both), static_cast<unsigned long long>(agreement.gpuOnly),
                static_cast<unsigned long long>(agreement.cpuOnly));
    // Not vacuous: pages at more than one level.
    EXPECT_GT(agreement.both, 50u);
    const ShadowPageAllocation& allocation = renderer.shadowPages();
    EXPECT_GE(std::count_if(allocation.pagesPerLevel.begin(), allocation.pagesPerLevel.end(), [](uint64_t n) { return n > 0; }), 2);
    // The same surfaces, a ray hit against an interpolated fragment: a few pages at the edges of
    // what is marked may differ, no more.
    EXPECT_GE(agreement.jaccard(), 0.97) << name;
    // Every page the frame marks has a slot: the allocation is the marks'.
    EXPECT_EQ(allocation.pages.size(), setBits(gpu));
    testing::expectNoValidationMessages(*context);
}

TEST(VirtualShadows, GpuMarksAgreeWithTheirCpuMirrorOnTheFloor) {
    expectMarksAgree(testing::tiltedSpotOverPostsSeenFromAbove(), testing::kFloorFrame, testing::kFloorFrame, "posts");
}

TEST(VirtualShadows, GpuMarksAgreeWithTheirCpuMirrorOnTheDefaultScene) {
    expectMarksAgree(makeDefaultScene(), 320, 180, "default scene");
}

// Hysteresis along the hall's walk (--shadow-hysteresis 1), walked back: a frame given the previous frame's
// marks holds the finer levels that frame read, so more of its pages are the previous frame's than
// without, at the cost of more pages; and the marking pass still agrees with its CPU mirror, which
// reads the same previous marks (so the lookups, which choose levels as the marking does, read
// only allocated pages).
TEST(VirtualShadows, HysteresisHoldsTheLevelsTheLastFrameReadAsItsCpuMirrorDoes) {
    auto context = testing::makeValidatedContext();
    const BuiltinScene& hall = parseBuiltinScene("hall");
    const render::RenderSettings plain = testing::shadowRenderSettings(320, 180, virtualShadows());
    // The walk backwards, the camera moving away: receivers need coarser levels than they read.
    const Scene before = makeBuiltinScene(hall, std::nullopt, 1.5);
    const Scene now = makeBuiltinScene(hall, std::nullopt, 1.0);
    render::Renderer first(*context, before, plain);
    first.render(1, 0);
    const auto previous = pageMarksByView(first.shadowPlan(), first.lights(), first.readShadowPageMarks());
    ASSERT_FALSE(previous.empty());
    // How many of a frame's marked pages the previous frame marked too (same light, face and page).
    auto sharedWithPrevious = [&](render::Renderer& renderer) {
        uint64_t shared = 0;
        for (const auto& [key, words] : pageMarksByView(renderer.shadowPlan(), renderer.lights(), renderer.readShadowPageMarks())) {
            const auto was = previous.find(key);
            if (was == previous.end()) continue;
            for (size_t w = 0; w < words.size(); ++w) shared += uint64_t(std::popcount(words[w] & was->second[w]));
        }
        return shared;
    };
    render::Renderer nearest(*context, now, plain);
    nearest.render(1, 0);
    render::RenderSettings holding = plain;
    holding.shadows.tierHysteresis = 1.0f;
    holding.shadows.previousPageMarks = previous;
    render::Renderer held(*context, now, holding);
    held.render(1, 0);
    ASSERT_FALSE(held.shadowPlan().virtualReads.previousFirstWord.empty());
    const uint64_t sharedHeld = sharedWithPrevious(held);
    const uint64_t sharedNearest = sharedWithPrevious(nearest);
    std::printf("[ virtual  ] pages shared with the previous frame: %llu held, %llu nearest; pages %zu held, %zu nearest\n",
                static_cast<unsigned long long>(sharedHeld), static_cast<unsigned long long>(sharedNearest),
                held.shadowPages().pages.size(), nearest.shadowPages().pages.size());
    EXPECT_GT(sharedHeld, sharedNearest);
    EXPECT_GT(held.shadowPages().pages.size(), nearest.shadowPages().pages.size());
    const std::vector<uint32_t> gpu = held.readShadowPageMarks();
    const std::vector<uint32_t> cpu = markVirtualPagesOnCpu(now, held.lights(), held.shadowPlan(), 320, 180, holding.shadows);
    const MarkAgreement agreement = compareMarks(gpu, cpu);
    EXPECT_GE(agreement.jaccard(), 0.97);
    EXPECT_EQ(held.shadowPages().pages.size(), setBits(gpu));
    testing::expectNoValidationMessages(*context);
}

// The compared pixels of `light` whose filter reads two pages or more, and those next to a pixel
// that reads another level; with their misclassified pixels outside the edge band.
struct SeamCounts {
    uint64_t acrossPages = 0;
    uint64_t acrossPagesWrong = 0;
    uint64_t atLevelChanges = 0;
    uint64_t atLevelChangesWrong = 0;
};

SeamCounts countSeams(const testing::ShadowRun& run, const ShadowSettings& settings) {
    SeamCounts seams;
    const reference::LightShadowValidation& light = run.validation.lights.at(0);
    const gpu::GpuPunctualLight& packed = run.lights.packed[light.packedLight];
    const uint32_t width = run.factors.width;
    std::vector<int> levels(run.factors.positions.size(), -1);
    for (size_t i = 0; i < levels.size(); ++i) {
        if (!run.factors.covered[i]) continue;
        const auto read = virtualReadOnCpu(run.plan, packed, run.factors.positions[i], run.factors.normals[i], settings);
        if (read) levels[i] = int(read->level);
    }
    for (size_t i = 0; i < levels.size(); ++i) {
        if (light.verdicts[i] == PixelVerdict::NotCompared || levels[i] < 0 || light.inBand[i]) continue;
        const bool wrong = light.verdicts[i] == PixelVerdict::FalseShadow || light.verdicts[i] == PixelVerdict::FalseLit;
        const auto read = virtualReadOnCpu(run.plan, packed, run.factors.positions[i], run.factors.normals[i], settings);
        if (!read) continue;
        const glm::uvec4 pages = gpu::virtualShadowFootprintPages(read->uv, read->reach, read->level,
                                                                  PUNCTUAL_VIRTUAL_SHADOW_SIZE, PUNCTUAL_VIRTUAL_SHADOW_PAGE);
        if (pages.x != pages.z || pages.y != pages.w) {
            ++seams.acrossPages;
            seams.acrossPagesWrong += wrong;
        }
        const size_t x = i % width;
        const bool levelChange = (x + 1 < width && levels[i + 1] >= 0 && levels[i + 1] != levels[i]) ||
                                 (i + width < levels.size() && levels[i + width] >= 0 && levels[i + width] != levels[i]);
        if (levelChange) {
            ++seams.atLevelChanges;
            seams.atLevelChangesWrong += wrong;
        }
    }
    return seams;
}

// No seams: receivers whose filters read across page borders, and receivers where the level
// changes, agree with Embree as well as the rest (the edge band aside, as everywhere).
TEST(VirtualShadows, NoSeamsAtPageBordersOrLevelChanges) {
    auto context = testing::makeValidatedContext();
    const Scene scene = testing::tiltedSpotOverPostsSeenFromAbove();
    const ShadowSettings shadows = virtualShadows();
    const testing::ShadowRun run = testing::renderAndValidateShadows(
        *context, scene, testing::shadowRenderSettings(testing::kFloorFrame, testing::kFloorFrame, shadows));
    testing::saveShadowRun("virtual-seams", run);
    const reference::ShadowCounts& counts = run.validation.spots;
    const SeamCounts seams = countSeams(run, shadows);
    std::printf("[ virtual  ] misclassified outside the band %.4f%% of %llu; across pages %llu of %llu; at level "
                "changes %llu of %llu\n",
                100.0 * counts.misclassifiedOutsideBand(), static_cast<unsigned long long>(counts.comparedOutsideBand),
                static_cast<unsigned long long>(seams.acrossPagesWrong), static_cast<unsigned long long>(seams.acrossPages),
                static_cast<unsigned long long>(seams.atLevelChangesWrong),
                static_cast<unsigned long long>(seams.atLevelChanges));
    // Not vacuous: shadows and light, many receivers across borders and at level changes.
    EXPECT_GE(testing::countVerdicts(run.validation, false, PixelVerdict::AgreeShadow), 2000u);
    EXPECT_GE(testing::countVerdicts(run.validation, false, PixelVerdict::AgreeLit), 20000u);
    EXPECT_GE(seams.acrossPages, 5000u);
    EXPECT_GE(seams.atLevelChanges, 300u);
    EXPECT_LE(counts.misclassifiedOutsideBand(), 0.002);
    EXPECT_LE(double(seams.acrossPagesWrong), 0.002 * double(seams.acrossPages));
    EXPECT_LE(double(seams.atLevelChangesWrong), 0.002 * double(seams.atLevelChanges));
    testing::expectNoValidationMessages(*context);
}

// The default scene within the default budget: every page its receivers ask for, and as accurate
// as --shadow-res auto's test asks (DefaultSceneAtAutoResolutionMisclassifiesAtMostHalfAPercent).
TEST(VirtualShadows, DefaultSceneMisclassifiesAtMostHalfAPercent) {
    auto context = testing::makeValidatedContext();
    const testing::ShadowRun run =
        testing::renderAndValidateShadows(*context, makeDefaultScene(), testing::shadowRenderSettings(320, 180, virtualShadows()));
    testing::saveShadowRun("virtual-default-scene", run);
    for (const bool isPoint : {false, true}) {
        const reference::ShadowCounts& counts = isPoint ? run.validation.points : run.validation.spots;
        EXPECT_GT(counts.comparedOutsideBand, 10000u);
        EXPECT_LE(counts.misclassifiedOutsideBand(), 0.005) << (isPoint ? "points" : "spots");
        EXPECT_GE(testing::countVerdicts(run.validation, isPoint, PixelVerdict::AgreeShadow), 500u);
    }
    for (const ShadowView& view : run.plan.views) EXPECT_EQ(view.coarserLevels, 0u);
    testing::expectNoValidationMessages(*context);
}

// The sun's cascades stay whole squares of the atlas, which grows around them to hold the pool:
// they read their squares where they moved to, as accurately as beside auto's whole views, and
// the pages fill the band beside them before the rows below (no unused texels).
TEST(VirtualShadows, TheSunsCascadesStayWholeBesideThePool) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeBuiltinScene("outdoor");
    double sunError[2] = {0.0, 0.0};
    for (const bool paged : {false, true}) {
        const ShadowSettings shadows = paged ? virtualShadows() : ShadowSettings{};
        const testing::ShadowRun run = testing::renderAndValidateShadows(*context, scene, testing::shadowRenderSettings(320, 180, shadows));
        ASSERT_TRUE(run.validation.sun.has_value());
        EXPECT_GT(run.validation.sun->counts.comparedOutsideBand, 10000u);
        sunError[paged] = run.validation.sun->counts.misclassifiedOutsideBand();
        EXPECT_LE(run.validation.overall.misclassifiedOutsideBand(), 0.005) << (paged ? "virtual" : "auto");
        if (paged) {
            EXPECT_GT(run.plan.cascades.count, 0u);
            EXPECT_GT(run.plan.atlas.height, 0u);
        }
    }
    EXPECT_NEAR(sunError[1], sunError[0], 0.0005);
    testing::expectNoValidationMessages(*context);
}

// A budget too small for every page: the least important lights' views read coarser levels, every
// page still marked gets a slot, the pool fits the budget, and the shadows stay shadows.
TEST(VirtualShadows, AShortBudgetCoarsensTheLeastImportantLightsFirst) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    ShadowSettings shadows = virtualShadows();
    shadows.budgetBytes = 1ull << 20;
    render::RenderSettings settings = testing::shadowRenderSettings(640, 360, shadows);
    settings.warnReducedShadows = false;
    render::Renderer renderer(*context, scene, settings);
    renderer.render(1, 0);
    const render::ShadowPageStats& stats = renderer.shadowPageStats();
    const ShadowPageAllocation& allocation = renderer.shadowPages();
    const ShadowPlan& plan = renderer.shadowPlan();
    EXPECT_GT(stats.marked.total(), shadowPagePoolCapacity(plan, shadows.budgetBytes, 2) + 1) << "the budget must be short";
    EXPECT_GT(stats.coarsenedPages, 0u);
    EXPECT_GE(stats.markingFrames, 2u);
    EXPECT_LE(allocation.physicalBytes(2), shadows.budgetBytes);
    EXPECT_EQ(allocation.pages.size(), setBits(renderer.readShadowPageMarks()));
    // By importance: every coarsened view's light ranks below every view left as asked.
    const std::vector<uint32_t> ranks = shadowViewRanks(plan, scene, renderer.lights(), scene.camera.position());
    uint32_t worstKept = 0;
    uint32_t bestCoarsened = UINT32_MAX;
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        if (!plan.views[v].rendered() || plan.views[v].isCascade || stats.marked.perView[v] == 0) continue;
        if (plan.views[v].coarserLevels > 0) {
            bestCoarsened = std::min(bestCoarsened, ranks[v]);
        } else {
            worstKept = std::max(worstKept, ranks[v]);
        }
    }
    EXPECT_LT(worstKept, bestCoarsened);
    testing::expectNoValidationMessages(*context);
}

// The overlay: written with virtual pages, tinting the frame where shadows read pages (and only
// there: the background keeps the frame's own pixels), refused in one line without them.
TEST(VirtualShadows, TheShadowPagesOverlayTintsWhereShadowsReadPages) {
    testing::TempFolder folder;
    const std::string frame = folder.file("frame.png");
    const std::string pages = folder.file("pages.png");
    const testing::RunResult run = testing::runPunctual(
        folder, testing::cat("render --validate --size 320x180 --shadow-res virtual --out ", testing::quoted(frame),
                             " --shadow-pages ", testing::quoted(pages)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const ImageRgba8 plain = readPng(frame);
    const ImageRgba8 tinted = readPng(pages);
    ASSERT_EQ(plain.pixels.size(), tinted.pixels.size());
    size_t changed = 0;
    for (size_t i = 0; i < plain.pixels.size(); ++i) changed += plain.pixels[i] != tinted.pixels[i];
    EXPECT_GT(changed, plain.pixels.size() / 4);  // most of the hall reads pages
    // The top right corner is background (no surface, no shadow), away from the legend.
    EXPECT_EQ(std::vector<uint8_t>(plain.at(319, 0), plain.at(319, 0) + 4),
              std::vector<uint8_t>(tinted.at(319, 0), tinted.at(319, 0) + 4));
    const std::string args = testing::cat("render --size 320x180 --shadow-pages ", testing::quoted(pages + "2"));
    testing::expectOneClearError(testing::runPunctual(folder, args), args, "--shadow-pages");
}

}  // namespace
}  // namespace punctual
