// A commit is all or nothing even when a signal arrives in the middle of it, and no output may
// replace a file the run read. Each case runs the commit in a forked child, so a signal kills only
// the child, and the parent then looks at what is on disk: every output new (the signal was held
// until the commit ended, then delivered) or every file as it was (the commit failed), never a mix,
// and never a hidden temporary left behind.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_files_read.h"
#include "core/output_files.h"
#include "core/output_target.h"
#include "gltf_test_files.h"
#include "scene/input_file.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test (gltf_test_files.h), with names in it.
class Scratch : public unit_testing::TempDir {
public:
    std::string file(const std::string& name) const { return (path() / name).string(); }
};

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeText(const std::string& path, const std::string& text) { unit_testing::writeFile(path, text); }

// Every name in the folder, recursively, relative to it (temporaries are hidden ".NAME.XXXXXX").
std::vector<std::string> listing(const fs::path& folder) {
    std::vector<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) names.push_back(entry.path().lexically_relative(folder).string());
    std::sort(names.begin(), names.end());
    return names;
}

// The step at which the child injects its event, and which event.
int gInjectAt = -1;
int gStepsSeen = 0;
bool gInjectFailure = false;

void injectAtStep(const char* /*step*/) {
    if (gStepsSeen++ != gInjectAt) return;
    if (gInjectFailure) throw Error("test", "a failure injected into the commit");
    ::raise(SIGINT);
}

// The outputs of one commit: two files that exist (replaced), one new file, one in a new folder.
struct Layout {
    explicit Layout(const Scratch& scratch)
        : existingA(scratch.file("a.png")), existingB(scratch.file("b.json")), fresh(scratch.file("c.png")),
          folder(scratch.file("sub")), inFolder(scratch.file("sub/d.txt")) {
        writeText(existingA, "old a");
        writeText(existingB, "old b");
    }
    void commit() const {
        OutputFiles outputs;
        outputs.addFolder(folder);
        outputs.add(existingA, "new a");
        outputs.add(existingB, "new b");
        outputs.add(fresh, "new c");
        outputs.add(inFolder, "new d");
        outputs.commit();
    }
    std::string existingA, existingB, fresh, folder, inFolder;
};

// Runs the commit in a child with an event at step `at`; returns the child's wait status.
int commitInChild(const Layout& layout, int at, bool failure) {
    const pid_t child = ::fork();
    if (child == 0) {
        gInjectAt = at;
        gInjectFailure = failure;
        OutputFiles::observeStepsForTesting(&injectAtStep);
        try {
            layout.commit();
        } catch (const Error&) {
            std::_Exit(100);
        }
        std::_Exit(gStepsSeen);  // a commit that saw no event says how many steps it took
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return status;
}

// How many steps a commit of the layout takes (counted in a child, so this process keeps no state):
// a folder, 4 temporaries, 2 backups and 4 renames.
int stepsOfACommit() {
    Scratch scratch;
    const Layout layout(scratch);
    const int status = commitInChild(layout, 1000, false);
    EXPECT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 11);
    return WEXITSTATUS(status);
}

TEST(OutputInterrupts, ASignalAtEveryStepOfACommitLetsItFinishAllNew) {
    const int steps = stepsOfACommit();
    for (int at = 0; at < steps; ++at) {
        Scratch scratch;
        const Layout layout(scratch);
        const int status = commitInChild(layout, at, false);
        // The signal was held back, then delivered once the commit was done: the child died of it.
        ASSERT_TRUE(WIFSIGNALED(status)) << "step " << at << ": the child was not ended by the signal";
        EXPECT_EQ(WTERMSIG(status), SIGINT) << "step " << at;
        EXPECT_EQ(readText(layout.existingA), "new a") << "step " << at;
        EXPECT_EQ(readText(layout.existingB), "new b") << "step " << at;
        EXPECT_EQ(readText(layout.fresh), "new c") << "step " << at;
        EXPECT_EQ(readText(layout.inFolder), "new d") << "step " << at;
        EXPECT_EQ(listing(scratch.path()), (std::vector<std::string>{"a.png", "b.json", "c.png", "sub", "sub/d.txt"}))
            << "step " << at << ": a temporary or backup was left behind";
    }
}

TEST(OutputInterrupts, AFailureAtEveryStepRollsBackToAllOld) {
    const int steps = stepsOfACommit();
    for (int at = 0; at < steps; ++at) {
        Scratch scratch;
        const Layout layout(scratch);
        struct stat before {};
        ASSERT_EQ(::stat(layout.existingA.c_str(), &before), 0);
        const int status = commitInChild(layout, at, true);
        ASSERT_TRUE(WIFEXITED(status)) << "step " << at;
        EXPECT_EQ(WEXITSTATUS(status), 100) << "step " << at << ": the injected failure did not reach the caller";
        EXPECT_EQ(readText(layout.existingA), "old a") << "step " << at;
        EXPECT_EQ(readText(layout.existingB), "old b") << "step " << at;
        struct stat st {};
        ASSERT_EQ(::stat(layout.existingA.c_str(), &st), 0);
        EXPECT_EQ(st.st_ino, before.st_ino) << "step " << at << ": the old file was replaced, not kept";
        EXPECT_EQ(listing(scratch.path()), (std::vector<std::string>{"a.png", "b.json"}))
            << "step " << at << ": a new file, folder or temporary was left behind";
    }
}

TEST(OutputInputs, AnOutputNamingAFileTheRunReadIsRefusedHoweverSpelt) {
    Scratch scratch;
    const std::string scene = scratch.file("scene.gltf");
    writeText(scene, "{\"asset\": {\"version\": \"2.0\"}}");
    fs::create_symlink("scene.gltf", scratch.file("link.png"));
    fs::create_hard_link(scene, scratch.file("hard.png"));
    fs::create_directories(scratch.file("dir"));
    const std::string before = readText(scene);

    // Without a log nothing is noted: a library user or test that loads a scene keeps no state.
    std::vector<unsigned char> bytes;
    ASSERT_EQ(readRegularFile(scene, 1 << 20, bytes), "");
    EXPECT_NO_THROW(resolveOutputTarget(scene));

    const InputFileLog log;
    ASSERT_EQ(readRegularFile(scene, 1 << 20, bytes), "");
    for (const std::string& spelling :
         {scene, scratch.file("link.png"), scratch.file("hard.png"), scratch.file("dir/../scene.gltf")}) {
        try {
            resolveOutputTarget(spelling);
            ADD_FAILURE() << spelling << " was accepted as an output";
        } catch (const Error& error) {
            EXPECT_NE(std::string(error.what()).find("is an input of this run"), std::string::npos) << error.what();
        }
        OutputFiles outputs;
        outputs.add(spelling, "PNG bytes");
        EXPECT_THROW(outputs.commit(), Error) << spelling;
    }
    EXPECT_EQ(readText(scene), before) << "the scene changed";
    EXPECT_EQ(listing(scratch.path()), (std::vector<std::string>{"dir", "hard.png", "link.png", "scene.gltf"}));
    // Another file in the same folder is still an output like any other.
    EXPECT_NO_THROW(resolveOutputTarget(scratch.file("image.png")));
}

TEST(OutputInputs, AStaleOutputThatIsNowAnInputIsKept) {
    Scratch scratch;
    const std::string texture = scratch.file("old-output.png");
    writeText(texture, "a texture the scene reads");
    const InputFileLog log;
    std::vector<unsigned char> bytes;
    ASSERT_EQ(readRegularFile(texture, 1 << 20, bytes), "");
    OutputFiles outputs;
    outputs.add(scratch.file("new.png"), "new");
    outputs.removeAfterCommit(texture);
    outputs.commit();
    EXPECT_EQ(readText(texture), "a texture the scene reads");
}

}  // namespace
}  // namespace punctual
