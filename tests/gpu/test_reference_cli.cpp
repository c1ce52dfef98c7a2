// `punctual reference` as users meet it: a good run writes the image and a summary; every bad
// input gives one clear line on stderr naming the file or option, a non-zero exit, and no
// output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "gpu_test_support.h"

namespace punctual {
namespace {

using testing::cat;
using testing::quoted;
using testing::RunResult;
using testing::runPunctual;

// One failing run: one clear error naming `mention`, and no output file, not even a temporary one
// (only the test's own glTF inputs stay in the folder).
void expectCleanFailure(const testing::TempFolder& folder, const std::string& args, const std::string& mention,
                        const std::string& png) {
    const RunResult run = runPunctual(folder, cat("reference ", args));
    testing::expectOneClearError(run, args, mention);
    EXPECT_FALSE(std::filesystem::exists(png)) << args;
    testing::expectNothingLeftBehind(folder, args, {".gltf", ".glb"});
}

TEST(ReferenceCli, WritesTheImageAndASummary) {
    testing::TempFolder folder;
    const std::string png = folder.file("reference.png");
    const RunResult run = runPunctual(folder, cat("reference --size 96x54 --lights 6,4,2 --out ", quoted(png)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "") << "no progress line when stderr is not a terminal";
    const ImageRgba8 image = readPng(png);
    EXPECT_EQ(image.width, 96u);
    EXPECT_EQ(image.height, 54u);
    EXPECT_NE(run.out.find("96x54"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("shadows on"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("rays/s"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("5184 primary"), std::string::npos) << run.out;

    const std::string flat = folder.file("flat.png");
    for (const char* off : {"--no-shadows", "--shadows off"}) {
        const RunResult noShadows =
            runPunctual(folder, cat("reference ", off, " --size 96x54 --lights 6,4,2 --out ", quoted(flat)));
        ASSERT_EQ(noShadows.exitCode, 0) << noShadows.err;
        EXPECT_NE(noShadows.out.find("+ 0 shadow"), std::string::npos) << noShadows.out;
        EXPECT_GT(testing::meanLuma(readPng(flat)), testing::meanLuma(image)) << off;
    }
}

TEST(ReferenceCli, HelpListsTheOptions) {
    testing::TempFolder folder;
    const RunResult run = runPunctual(folder, "reference --help");
    EXPECT_EQ(run.exitCode, 0);
    EXPECT_NE(run.out.find("--no-shadows"), std::string::npos);
    EXPECT_NE(run.out.find("--out"), std::string::npos);
}

TEST(ReferenceCli, BadInputFailsCleanly) {
    testing::TempFolder folder;
    const std::string png = folder.file("out.png");
    const std::string out = cat(" --size 32x18 --out ", quoted(png));

    expectCleanFailure(folder, cat(quoted(folder.file("missing.gltf")), out), "missing.gltf", png);

    const std::string truncated = folder.file("truncated.gltf");
    std::ofstream(truncated) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"me)";
    expectCleanFailure(folder, cat(quoted(truncated), out), "truncated.gltf", png);

    const std::string truncatedGlb = folder.file("truncated.glb");
    std::ofstream(truncatedGlb, std::ios::binary) << std::string("glTF\x02\x00\x00\x00\xff\x00\x00\x00", 12);
    expectCleanFailure(folder, cat(quoted(truncatedGlb), out), "truncated.glb", png);

    expectCleanFailure(folder, cat("--size 0x10 --out ", quoted(png)), "--size", png);
    expectCleanFailure(folder, cat("--size big --out ", quoted(png)), "--size", png);
    expectCleanFailure(folder, cat("--lights 65,0", out), "--lights", png);
    expectCleanFailure(folder, cat("--lights x", out), "--lights", png);
    expectCleanFailure(folder, cat("--exposure -2", out), "--exposure", png);
    expectCleanFailure(folder, cat("--size 32x18 --out ", quoted(folder.file("no-such-folder/out.png"))), "no-such-folder",
                       png);
    expectCleanFailure(folder, "--size 32x18", "--out", png);
    expectCleanFailure(folder, cat("--bogus", out), "--bogus", png);
    expectCleanFailure(folder, cat("--stats ", quoted(folder.file("s.json")), out), "--stats", png);
    expectCleanFailure(folder, cat("--shadow-res 512", out), "--shadow-res", png);
    expectCleanFailure(folder, cat("--shadows maybe", out), "--shadows", png);
    expectCleanFailure(folder, "--out", "--out", png);
}

}  // namespace
}  // namespace punctual
