// Output paths as users give them: nothing a user owns is ever destroyed. /dev/null and FIFOs
// are written in place, symbolic links written through, two options naming one file refused,
// a user's "out.png.partial" left alone, stale files of an earlier validate run removed (only
// those), and every path problem found before the frame is rendered.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "gpu_test_support.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;
using testing::cat;
using testing::quoted;
using testing::readText;
using testing::RunResult;
using testing::runPunctual;

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

ino_t inodeOf(const std::string& path) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 ? st.st_ino : 0;
}

mode_t typeOf(const std::string& path) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 ? (st.st_mode & S_IFMT) : 0;
}

bool isPng(const std::string& bytes) { return bytes.rfind("\x89PNG\r\n\x1a\n", 0) == 0; }

// A run that fails on its output paths before any work: one clear error naming `mention`, and
// nothing rendered (the render prints its scene line first).
void expectRefusedUpFront(const RunResult& run, const std::string& args, const std::string& mention) {
    testing::expectOneClearError(run, args, mention);
    EXPECT_EQ(run.exitCode, 1) << args;
    EXPECT_EQ(run.out, "") << args << ": the command did work before refusing its outputs";
}

constexpr const char* kSmall = "render --validate --size 32x18 --lights 2,1";

TEST(CliOutputs, WritesIntoDevNullWithoutReplacingIt) {
    testing::TempFolder folder;
    const RunResult run = runPunctual(folder, cat(kSmall, " --out /dev/null --stats ", quoted(folder.file("s.json"))));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(typeOf("/dev/null"), mode_t(S_IFCHR)) << "/dev/null was replaced";
    EXPECT_NE(run.out.find("wrote /dev/null"), std::string::npos);
}

TEST(CliOutputs, WritesIntoAFifoWithAReader) {
    testing::TempFolder folder;
    const std::string fifo = folder.file("pipe.png");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // The reader waits in open() until punctual opens the FIFO for writing, then reads to the end.
    std::future<std::string> read = std::async(std::launch::async, [&] { return readText(fifo); });
    const RunResult run = runPunctual(folder, cat(kSmall, " --out ", quoted(fifo)));
    if (run.exitCode != 0) {
        const int unblock = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // release the reader
        if (unblock >= 0) ::close(unblock);
    }
    ASSERT_EQ(run.exitCode, 0) << run.err;
    ASSERT_EQ(read.wait_for(std::chrono::seconds(60)), std::future_status::ready);
    EXPECT_TRUE(isPng(read.get()));
    EXPECT_EQ(typeOf(fifo), mode_t(S_IFIFO)) << "the FIFO was replaced";
}

TEST(CliOutputs, RefusesAFifoWithoutAReaderInsteadOfHanging) {
    testing::TempFolder folder;
    const std::string fifo = folder.file("pipe.png");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string stats = folder.file("stats.json");
    const std::string args = cat(kSmall, " --stats ", quoted(stats), " --out ", quoted(fifo));
    std::future<RunResult> run = std::async(std::launch::async, [&] { return runPunctual(folder, args); });
    if (run.wait_for(std::chrono::seconds(120)) != std::future_status::ready) {
        ADD_FAILURE() << "punctual hung on a FIFO without a reader";
        const int unblock = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // let it finish
        run.wait();
        if (unblock >= 0) ::close(unblock);
    }
    const RunResult result = run.get();
    testing::expectOneClearError(result, args, "no reader");
    EXPECT_FALSE(fs::exists(stats)) << "an output of a failed run was kept";
    EXPECT_EQ(typeOf(fifo), mode_t(S_IFIFO));
    testing::expectNothingLeftBehind(folder, args, {"pipe.png"});
}

TEST(CliOutputs, WritesThroughASymbolicLink) {
    testing::TempFolder folder;
    fs::create_directories(folder.file("real"));
    writeText(folder.file("real/frame.png"), "old");
    fs::create_symlink("real/frame.png", folder.file("link.png"));
    const RunResult run = runPunctual(folder, cat(kSmall, " --out ", quoted(folder.file("link.png"))));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(typeOf(folder.file("link.png")), mode_t(S_IFLNK)) << "the link was replaced";
    EXPECT_EQ(readPng(folder.file("real/frame.png")).width, 32u);
    testing::expectNothingLeftBehind(folder, "symlink", {"link.png", "real"});
    for (const auto& entry : fs::directory_iterator(folder.file("real"))) {
        EXPECT_EQ(entry.path().filename(), "frame.png") << "left behind beside the target";
    }
}

TEST(CliOutputs, RefusesTwoOutputsNamingOneFileBeforeRendering) {
    testing::TempFolder folder;
    // Names without an extension, so that any option may name them (a .png is refused for --stats).
    const std::string mine = folder.file("x");
    writeText(mine, "mine");
    const ino_t inode = inodeOf(mine);
    fs::create_symlink("x", folder.file("link"));
    const std::string again = cat(folder.path(), "/./x");
    for (const std::string& options :
         {cat("--out ", quoted(mine), " --stats ", quoted(mine)), cat("--out ", quoted(mine), " --heatmap ", quoted(again)),
          cat("--stats ", quoted(mine), " --heatmap ", quoted(folder.file("link"))),
          cat("--out ", quoted(folder.file("new.png")), " --heatmap ", quoted(cat(folder.path(), "/./new.png")))}) {
        const std::string args = cat(kSmall, " ", options);
        expectRefusedUpFront(runPunctual(folder, args), args, "two outputs cannot share a file");
        EXPECT_EQ(readText(mine), "mine") << args;
        EXPECT_EQ(inodeOf(mine), inode) << args;
        testing::expectNothingLeftBehind(folder, args, {"x", "link"});
    }
}

TEST(CliOutputs, NeverTouchesAUsersPartialFile) {
    testing::TempFolder folder;
    const std::string partial = folder.file("out.png.partial");
    writeText(partial, "mine");
    const ino_t inode = inodeOf(partial);
    RunResult run = runPunctual(folder, cat(kSmall, " --out ", quoted(folder.file("out.png"))));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(readText(partial), "mine");
    EXPECT_EQ(inodeOf(partial), inode);
    // An output named like another's temporary once was: both arrive, each with its contents.
    run = runPunctual(folder, cat(kSmall, " --out ", quoted(folder.file("x.json.partial")), " --stats ",
                                  quoted(folder.file("x.json"))));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_TRUE(isPng(readText(folder.file("x.json.partial"))));
    EXPECT_TRUE(nlohmann::json::accept(readText(folder.file("x.json"))));
}

TEST(CliOutputs, PathProblemsAreFoundBeforeRendering) {
    testing::TempFolder folder;
    const std::string file = folder.file("a.txt");
    writeText(file, "a file");
    const std::string longName = folder.file(std::string(300, 'n') + ".png");
    struct Case {
        std::string args;
        std::string mention;
    };
    const std::vector<Case> cases = {
        {cat(kSmall, " --out ", quoted(file + "/x.png")), "a.txt' is a file, not a folder"},
        {cat(kSmall, " --out ", quoted(folder.file("x.png")), " --stats ", quoted(file + "/s.json")),
         "a.txt' is a file, not a folder"},
        {cat(kSmall, " --heatmap ", quoted(longName)), "file name is too long"},
        {cat(kSmall, " --out ", quoted(folder.file("no/such/x.png"))), "does not exist"},
        {cat(kSmall, " --out ", quoted(folder.path())), "is a folder"},
        {cat("reference --size 32x18 --out ", quoted(file + "/x.png")), "a.txt' is a file, not a folder"},
        {cat("reference --size 32x18 --out ", quoted(longName)), "file name is too long"},
        {cat("validate --size 32x18 --out-dir ", quoted(file)), "is a file, not a folder"},
        {cat("validate --size 32x18 --out-dir ", quoted(file + "/v")), "a.txt' is a file, not a folder"},
        {cat("validate --size 32x18 --out-dir ", quoted(longName)), "file name is too long"},
        {cat("bench --quick --out-dir ", quoted(file)), "is a file, not a folder"},
        {cat("bench --quick --out-dir ", quoted(file + "/b")), "a.txt' is a file, not a folder"},
    };
    for (const Case& c : cases) {
        expectRefusedUpFront(runPunctual(folder, c.args), c.args, c.mention);
        testing::expectNothingLeftBehind(folder, c.args, {"a.txt"});
    }
    // A validate folder whose report.json is a folder cannot take the report.
    fs::create_directories(folder.file("v/report.json"));
    const std::string args = cat("validate --size 32x18 --out-dir ", quoted(folder.file("v")));
    expectRefusedUpFront(runPunctual(folder, args), args, "report.json: is a folder");
}

// Permissions do not stop root, so as root the runs that meet a read-only folder or file go
// through setpriv as the unprivileged user 'nobody'.
std::string asUnprivileged() { return ::geteuid() == 0 ? "--reuid=65534 --regid=65534 --clear-groups " : ""; }

RunResult runUnprivileged(const testing::TempFolder& folder, const std::string& args) {
    if (::geteuid() != 0) return runPunctual(folder, args);
    const std::string command = cat("setpriv ", asUnprivileged(), quoted(PUNCTUAL_BINARY), " ", args, " >",
                                    quoted(folder.file("stdout.txt")), " 2>", quoted(folder.file("stderr.txt")));
    const int status = std::system(command.c_str());
    RunResult result;
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = readText(folder.file("stdout.txt"));
    result.err = readText(folder.file("stderr.txt"));
    return result;
}

TEST(CliOutputs, ReadOnlyFoldersAndFilesAreFoundBeforeRendering) {
    testing::TempFolder folder;
    ASSERT_EQ(::chmod(folder.path().c_str(), 0777), 0);  // stdout.txt and stderr.txt, and traversal
    const std::string readOnly = folder.file("read-only");
    fs::create_directories(readOnly);
    ASSERT_EQ(::chmod(readOnly.c_str(), 0555), 0);
    const std::string writable = folder.file("writable");
    fs::create_directories(writable);
    ASSERT_EQ(::chmod(writable.c_str(), 0777), 0);
    const std::string protectedFile = writable + "/protected.png";
    writeText(protectedFile, "mine");
    ASSERT_EQ(::chmod(protectedFile.c_str(), 0444), 0);
    const ino_t inode = inodeOf(protectedFile);
    struct Case {
        std::string args;
        std::string mention;
    };
    for (const Case& c : std::vector<Case>{
             {cat(kSmall, " --out ", quoted(readOnly + "/x.png")), "read-only' is not writable"},
             {cat(kSmall, " --out ", quoted(writable + "/x.png"), " --stats ", quoted(readOnly + "/s.json")),
              "read-only' is not writable"},
             {cat(kSmall, " --out ", quoted(protectedFile)), "write-protected"},
             {cat("validate --size 32x18 --out-dir ", quoted(readOnly)), "read-only' is not writable"},
             {cat("validate --size 32x18 --out-dir ", quoted(readOnly + "/v")), "read-only' is not writable"},
             {cat("bench --quick --out-dir ", quoted(readOnly + "/b")), "read-only' is not writable"},
         }) {
        expectRefusedUpFront(runUnprivileged(folder, c.args), c.args, c.mention);
        EXPECT_TRUE(fs::is_empty(readOnly)) << c.args;
        EXPECT_EQ(readText(protectedFile), "mine") << c.args;
        EXPECT_EQ(inodeOf(protectedFile), inode) << c.args;
        EXPECT_FALSE(fs::exists(writable + "/x.png")) << c.args;
    }
    ASSERT_EQ(::chmod(readOnly.c_str(), 0755), 0);  // so TempFolder can remove it
}

TEST(CliOutputs, ValidateRemovesOnlyTheStaleFilesItsLastRunListed) {
    testing::TempFolder folder;
    const std::string dir = folder.file("v");
    fs::create_directories(dir);
    // An earlier run's report listing a mismatch map of a light that no longer exists; files
    // of the user's beside it, listed by a tampered report or not at all.
    writeText(dir + "/report.json",
              R"({"files": ["report.json", "mismatch-39.png", "notes.txt", "../outside.png", "shadow-factor-9.exr"]})");
    writeText(dir + "/mismatch-39.png", "stale");
    writeText(dir + "/notes.txt", "mine");
    writeText(dir + "/mismatch-77.png", "mine, never listed");
    writeText(folder.file("outside.png"), "mine, outside the folder");
    fs::create_symlink("notes.txt", dir + "/shadow-factor-9.exr");  // a link is the user's
    const std::string args =
        cat("validate --validate --size 32x18 --shadow-res 256 --lights 2,1 --out-dir ", quoted(dir));
    const RunResult run = runPunctual(folder, args);
    ASSERT_EQ(run.exitCode, 0) << run.err;

    const nlohmann::json report = nlohmann::json::parse(readText(dir + "/report.json"));
    ASSERT_TRUE(report.contains("files") && report["files"].is_array()) << "report.json lists no files";
    std::set<std::string> listed;
    for (const auto& name : report["files"]) listed.insert(name.get<std::string>());
    EXPECT_EQ(listed, (std::set<std::string>{"report.json", "report.html", "gpu.png", "reference.png",
                                             "mismatch-0.png", "mismatch-1.png", "mismatch-2.png"}));
    std::set<std::string> present;
    for (const auto& entry : fs::directory_iterator(dir)) present.insert(entry.path().filename().string());
    std::set<std::string> expected = listed;
    expected.insert({"notes.txt", "mismatch-77.png", "shadow-factor-9.exr"});
    EXPECT_EQ(present, expected);
    EXPECT_EQ(readText(dir + "/notes.txt"), "mine");
    EXPECT_EQ(readText(folder.file("outside.png")), "mine, outside the folder");
}

}  // namespace
}  // namespace punctual
