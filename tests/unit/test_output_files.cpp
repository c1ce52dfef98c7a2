// Output files never cost the user a file: what a path names (a regular file, a symbolic link,
// /dev/null, a FIFO) decides how it is written, two outputs naming one file are refused, a failed
// commit leaves every existing file as it was (contents and inode), temporaries have names no
// user file can have, and a stale file is removed only when an earlier run listed it.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "core/output_target.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;

// A folder of its own under the system temp folder, removed at the end.
class Scratch {
public:
    Scratch() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::random_device random;
        path_ = fs::temp_directory_path() / ("punctual_outputs_" + std::string(info->name()) + "_" + std::to_string(random()));
        fs::create_directories(path_);
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

ino_t inodeOf(const std::string& path) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 ? st.st_ino : 0;
}

std::set<std::string> namesIn(const fs::path& folder) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
    return names;
}

// The commit's error message; fails the test when it does not throw.
std::string commitError(OutputFiles& outputs) {
    try {
        outputs.commit();
    } catch (const Error& error) {
        return error.what();
    }
    ADD_FAILURE() << "commit() did not fail";
    return "";
}

TEST(OutputFiles, WritesNewFilesAndReplacesExistingOnes) {
    Scratch scratch;
    writeText(scratch.file("old.txt"), "old");
    OutputFiles outputs;
    outputs.add(scratch.file("old.txt"), "new");
    outputs.add(scratch.file("fresh.txt"), "fresh");
    outputs.commit();
    EXPECT_EQ(readText(scratch.file("old.txt")), "new");
    EXPECT_EQ(readText(scratch.file("fresh.txt")), "fresh");
    EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"old.txt", "fresh.txt"}));  // no temporaries left
}

TEST(OutputFiles, KeepsThePermissionsOfTheFileItReplaces) {
    Scratch scratch;
    writeText(scratch.file("x.txt"), "old");
    ASSERT_EQ(::chmod(scratch.file("x.txt").c_str(), 0640), 0);
    OutputFiles outputs;
    outputs.add(scratch.file("x.txt"), "new");
    outputs.add(scratch.file("new.txt"), "new");
    outputs.commit();
    struct stat st {};
    ASSERT_EQ(::stat(scratch.file("x.txt").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0640u);
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ASSERT_EQ(::stat(scratch.file("new.txt").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0666u & ~mask);  // as a plain open() would make it, not mkstemp's 0600
}

TEST(OutputFiles, WritesThroughASymbolicLink) {
    Scratch scratch;
    fs::create_directories(scratch.file("real"));
    writeText(scratch.file("real/x.png"), "old");
    fs::create_symlink("real/x.png", scratch.file("link.png"));
    fs::create_symlink("real/missing.png", scratch.file("dangling.png"));
    OutputFiles outputs;
    outputs.add(scratch.file("link.png"), "new");
    outputs.add(scratch.file("dangling.png"), "created");
    outputs.commit();
    EXPECT_TRUE(fs::is_symlink(scratch.file("link.png")));
    EXPECT_TRUE(fs::is_symlink(scratch.file("dangling.png")));
    EXPECT_EQ(readText(scratch.file("real/x.png")), "new");
    EXPECT_EQ(readText(scratch.file("real/missing.png")), "created");
    EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"real", "link.png", "dangling.png"}));
    EXPECT_EQ(namesIn(scratch.file("real")), (std::set<std::string>{"x.png", "missing.png"}));
}

TEST(OutputFiles, WritesIntoDevNullInPlace) {
    OutputFiles outputs;
    outputs.add("/dev/null", "bytes nobody keeps");
    outputs.commit();
    struct stat st {};
    ASSERT_EQ(::lstat("/dev/null", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/null was replaced";
    for (const std::string& name : namesIn("/dev")) EXPECT_EQ(name.rfind(".null", 0), std::string::npos) << name;
}

TEST(OutputFiles, WritesIntoAFifoWithAReader) {
    Scratch scratch;
    const std::string fifo = scratch.file("pipe");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Opening for reading with O_NONBLOCK returns at once and counts as a reader.
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(reader, 0);
    OutputFiles outputs;
    outputs.add(fifo, "through the pipe");
    outputs.commit();
    char buffer[64] = {};
    const ssize_t n = ::read(reader, buffer, sizeof(buffer));
    ::close(reader);
    EXPECT_EQ(std::string(buffer, size_t(std::max<ssize_t>(n, 0))), "through the pipe");
    struct stat st {};
    ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
    EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"pipe"}));
}

TEST(OutputFiles, AFifoWithoutAReaderFailsAtOnceAndWritesNothing) {
    Scratch scratch;
    const std::string fifo = scratch.file("pipe");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    writeText(scratch.file("a.txt"), "mine");
    const ino_t inode = inodeOf(scratch.file("a.txt"));
    OutputFiles outputs;
    outputs.add(scratch.file("a.txt"), "new");
    outputs.add(scratch.file("b.txt"), "new");
    outputs.add(fifo, "nobody reads this");
    std::future<std::string> error = std::async(std::launch::async, [&] { return commitError(outputs); });
    if (error.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
        const int unblock = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // let the hung commit finish
        ADD_FAILURE() << "commit() hung on a FIFO without a reader";
        error.wait();
        ::close(unblock);
    }
    EXPECT_NE(error.get().find("no reader"), std::string::npos);
    EXPECT_EQ(readText(scratch.file("a.txt")), "mine");
    EXPECT_EQ(inodeOf(scratch.file("a.txt")), inode);
    EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"pipe", "a.txt"}));
}

TEST(OutputFiles, RefusesTwoOutputsNamingOneFile) {
    Scratch scratch;
    const std::string mine = scratch.file("x.png");
    writeText(mine, "mine");
    const ino_t inode = inodeOf(mine);
    fs::create_symlink("x.png", scratch.file("link.png"));
    fs::create_hard_link(mine, scratch.file("hard.png"));
    const std::string spelledAgain = (scratch.path() / "." / "x.png").string();
    for (const std::string& second : {mine, spelledAgain, scratch.file("link.png"), scratch.file("hard.png")}) {
        OutputFiles outputs;
        outputs.add(mine, "image");
        outputs.add(second, "stats");
        EXPECT_NE(commitError(outputs).find("two outputs cannot share a file"), std::string::npos) << second;
        EXPECT_EQ(readText(mine), "mine") << second;
        EXPECT_EQ(inodeOf(mine), inode) << second;
        EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"x.png", "link.png", "hard.png"})) << second;
    }
    OutputFiles outputs;  // a new file named twice
    outputs.add(scratch.file("new.png"), "image");
    outputs.add((scratch.path() / "." / "new.png").string(), "stats");
    EXPECT_NE(commitError(outputs).find("two outputs cannot share a file"), std::string::npos);
    EXPECT_FALSE(fs::exists(scratch.file("new.png")));
}

TEST(OutputFiles, NeverTouchesAUsersPartialFile) {
    Scratch scratch;
    writeText(scratch.file("out.png.partial"), "mine");
    const ino_t inode = inodeOf(scratch.file("out.png.partial"));
    {
        OutputFiles outputs;
        outputs.add(scratch.file("out.png"), "image");
        outputs.commit();
    }
    EXPECT_EQ(readText(scratch.file("out.png.partial")), "mine");
    EXPECT_EQ(inodeOf(scratch.file("out.png.partial")), inode);
    // An output whose name is another output's plus ".partial": both arrive.
    OutputFiles outputs;
    outputs.add(scratch.file("x.png.partial"), "image");
    outputs.add(scratch.file("x.png"), "stats");
    outputs.commit();
    EXPECT_EQ(readText(scratch.file("x.png.partial")), "image");
    EXPECT_EQ(readText(scratch.file("x.png")), "stats");
}

TEST(OutputFiles, AFailedCommitLeavesEveryFileAsItWas) {
    Scratch scratch;
    writeText(scratch.file("a.txt"), "old a");
    writeText(scratch.file("b.txt"), "old b");
    const ino_t inodeA = inodeOf(scratch.file("a.txt"));
    const ino_t inodeB = inodeOf(scratch.file("b.txt"));
    // /dev/full takes no byte: its write fails after every file has been renamed into place,
    // the last step of the commit, which must then undo the renames.
    OutputFiles outputs;
    outputs.add(scratch.file("a.txt"), "new a");
    outputs.add(scratch.file("new.txt"), "new");
    outputs.add("/dev/full", "no room");
    outputs.add(scratch.file("b.txt"), "new b");
    const std::string error = commitError(outputs);
    EXPECT_NE(error.find("/dev/full"), std::string::npos) << error;
    EXPECT_EQ(readText(scratch.file("a.txt")), "old a");
    EXPECT_EQ(readText(scratch.file("b.txt")), "old b");
    EXPECT_EQ(inodeOf(scratch.file("a.txt")), inodeA);
    EXPECT_EQ(inodeOf(scratch.file("b.txt")), inodeB);
    EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"a.txt", "b.txt"}));
}

TEST(OutputFiles, AFailedWriteLeavesNoTemporaryAndNoFolderBehind) {
    Scratch scratch;
    writeText(scratch.file("a.txt"), "old");
    OutputFiles outputs;
    outputs.addFolder(scratch.file("made"));
    outputs.add(scratch.file("made/x.txt"), "x");
    outputs.add(scratch.file("a.txt"), "new");
    outputs.add(scratch.file("no/such/folder/y.txt"), "y");
    EXPECT_NE(commitError(outputs).find("does not exist"), std::string::npos);
    EXPECT_EQ(readText(scratch.file("a.txt")), "old");
    EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"a.txt"}));  // the folder it made is gone too
}

TEST(OutputFiles, RemovesStaleFilesOnlyWhenTheCommitSucceeds) {
    Scratch scratch;
    writeText(scratch.file("stale.png"), "earlier run");
    {
        OutputFiles outputs;
        outputs.add(scratch.file("x.txt"), "x");
        outputs.add("/dev/full", "fails");
        outputs.removeAfterCommit(scratch.file("stale.png"));
        commitError(outputs);
    }
    EXPECT_TRUE(fs::exists(scratch.file("stale.png")));
    OutputFiles outputs;
    outputs.add(scratch.file("x.txt"), "x");
    outputs.removeAfterCommit(scratch.file("stale.png"));
    outputs.commit();
    EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"x.txt"}));
}

// ---- what a path names, checked before any work ---------------------------------------------

std::string resolveError(const std::string& path) {
    try {
        checkOutputTargetWritable(resolveOutputTarget(path));
    } catch (const Error& error) {
        return error.what();
    }
    return "";
}

TEST(OutputTarget, NamesEveryProblemOfAPath) {
    Scratch scratch;
    writeText(scratch.file("a.txt"), "a file");
    EXPECT_NE(resolveError(scratch.file("a.txt/x.png")).find("a.txt' is a file, not a folder"), std::string::npos)
        << resolveError(scratch.file("a.txt/x.png"));
    EXPECT_NE(resolveError(scratch.file("a.txt/sub/x.png")).find("a.txt' is a file, not a folder"), std::string::npos);
    EXPECT_NE(resolveError(scratch.file("missing/x.png")).find("does not exist"), std::string::npos);
    EXPECT_NE(resolveError(scratch.path().string()).find("is a folder"), std::string::npos);
    EXPECT_NE(resolveError(scratch.file("new/")).find("file name"), std::string::npos);
    EXPECT_NE(resolveError("").find("empty"), std::string::npos);
    const std::string longName = scratch.file(std::string(300, 'n') + ".png");
    EXPECT_NE(resolveError(longName).find("file name is too long (304 bytes, at most 255)"), std::string::npos)
        << resolveError(longName);
    std::string longPath = scratch.path().string();
    while (longPath.size() < 5000) longPath += "/" + std::string(100, 'd');
    EXPECT_NE(resolveError(longPath + "/x.png").find("too long"), std::string::npos) << resolveError(longPath);
    fs::create_symlink("loop.png", scratch.file("loop.png"));
    EXPECT_NE(resolveError(scratch.file("loop.png")).find("symbolic links"), std::string::npos);
    // A socket is not a file punctual may replace.
    const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(s, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string socketPath = scratch.file("socket");
    ASSERT_LT(socketPath.size(), sizeof(address.sun_path));
    std::memcpy(address.sun_path, socketPath.c_str(), socketPath.size() + 1);
    ASSERT_EQ(::bind(s, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
    EXPECT_NE(resolveError(socketPath).find("not a regular file"), std::string::npos);
    ::close(s);
    // Fine: a new name, an existing file, /dev/null; and the checks leave nothing behind.
    EXPECT_EQ(resolveError(scratch.file("new.png")), "");
    EXPECT_EQ(resolveError(scratch.file("a.txt")), "");
    EXPECT_EQ(resolveError("/dev/null"), "");
    EXPECT_EQ(namesIn(scratch.path()), (std::set<std::string>{"a.txt", "loop.png", "socket"}));
}

TEST(OutputTarget, ASymbolicLinkResolvesToItsTarget) {
    Scratch scratch;
    fs::create_directories(scratch.file("real"));
    writeText(scratch.file("real/x.png"), "x");
    fs::create_symlink(scratch.file("real"), scratch.file("folder-link"));
    fs::create_symlink("folder-link/x.png", scratch.file("link.png"));
    const OutputTarget target = resolveOutputTarget(scratch.file("link.png"));
    EXPECT_EQ(target.kind, OutputTarget::Kind::Regular);
    EXPECT_EQ(target.file, fs::canonical(scratch.file("real/x.png")));
    EXPECT_TRUE(target.sameFileAs(resolveOutputTarget(scratch.file("real/x.png"))));
    EXPECT_EQ(resolveOutputTarget("/dev/null").kind, OutputTarget::Kind::Stream);
}

// ---- output folders: the files of a run, and the stale ones of an earlier run ----------------

const OutputFolderLayout kLayout = {"report.json", {"report.json", "gpu.png", "mismatch-*.png", "images/heat-*.png"}, {"images"}};

TEST(OutputFolder, PatternsAllowOnlyTheCommandsOwnPlainNames) {
    EXPECT_TRUE(matchesOutputLayout(kLayout, "report.json"));
    EXPECT_TRUE(matchesOutputLayout(kLayout, "mismatch-3.png"));
    EXPECT_TRUE(matchesOutputLayout(kLayout, "images/heat-tiled.png"));
    EXPECT_FALSE(matchesOutputLayout(kLayout, "notes.txt"));
    EXPECT_FALSE(matchesOutputLayout(kLayout, "images/mismatch-3.png"));
    EXPECT_FALSE(matchesOutputLayout(kLayout, "sub/mismatch-3.png"));
    EXPECT_FALSE(matchesOutputLayout(kLayout, "../mismatch-3.png"));
    EXPECT_FALSE(matchesOutputLayout(kLayout, "/tmp/mismatch-3.png"));
    EXPECT_FALSE(matchesOutputLayout(kLayout, "images/../gpu.png"));
    EXPECT_FALSE(matchesOutputLayout(kLayout, "mismatch-/../../x.png"));
}

TEST(OutputFolder, StaleFilesAreTheListedOnesThisRunDoesNotWrite) {
    Scratch scratch;
    const std::string dir = scratch.file("out");
    fs::create_directories(dir + "/images");
    writeText(dir + "/report.json", R"({"files": ["report.json", "mismatch-1.png", "mismatch-2.png", "images/heat-a.png",
        "../outside.png", "/etc/hostname", "notes.txt", "mismatch-link.png", "mismatch-folder.png", 5,
        "images/../gpu.png"]})");
    for (const char* name : {"mismatch-1.png", "mismatch-2.png", "images/heat-a.png", "notes.txt", "mismatch-9.png"}) {
        writeText(dir + "/" + name, "old");
    }
    writeText(scratch.file("outside.png"), "not in the folder");
    fs::create_symlink("notes.txt", dir + "/mismatch-link.png");
    fs::create_directories(dir + "/mismatch-folder.png");
    EXPECT_EQ(staleOutputFiles(dir, kLayout, {"report.json", "mismatch-1.png"}),
              (std::vector<std::string>{"mismatch-2.png", "images/heat-a.png"}));
    // No manifest, or one that is not what punctual writes: nothing is stale.
    writeText(dir + "/report.json", R"({"files": "mismatch-2.png"})");
    EXPECT_TRUE(staleOutputFiles(dir, kLayout, {}).empty());
    writeText(dir + "/report.json", R"({"files": ["mismatch-2.png")");
    EXPECT_TRUE(staleOutputFiles(dir, kLayout, {}).empty());
    fs::remove(dir + "/report.json");
    EXPECT_TRUE(staleOutputFiles(dir, kLayout, {}).empty());
}

TEST(OutputFolder, ARunRemovesWhatTheLastOneWroteAndNothingElse) {
    Scratch scratch;
    const std::string dir = scratch.file("out");
    auto run = [&](const std::vector<std::string>& maps) {
        OutputFiles outputs;
        outputs.add(dir + "/gpu.png", "gpu");
        for (const std::string& map : maps) outputs.add(dir + "/" + map, "map");
        const std::vector<std::string> files = outputFolderFiles(outputs, dir, kLayout);
        std::string manifest = R"({"files": [)";
        for (size_t i = 0; i < files.size(); ++i) manifest += (i ? ", \"" : "\"") + files[i] + "\"";
        outputs.add(dir + "/report.json", manifest + "]}");
        prepareOutputFolder(outputs, dir, kLayout, files);
        outputs.commit();
    };
    run({"mismatch-0.png", "mismatch-1.png", "images/heat-x.png"});
    writeText(dir + "/notes.txt", "mine");
    writeText(dir + "/mismatch-7.png", "mine too, never listed");
    run({"mismatch-0.png"});
    EXPECT_EQ(namesIn(dir), (std::set<std::string>{"report.json", "gpu.png", "mismatch-0.png", "notes.txt",
                                                   "mismatch-7.png", "images"}));
    EXPECT_TRUE(namesIn(dir + "/images").empty());
}

TEST(OutputFolder, CheckedBeforeAnyWork) {
    Scratch scratch;
    auto checkError = [](const std::string& folder) {
        try {
            checkOutputFolder(folder, kLayout);
        } catch (const Error& error) {
            return std::string(error.what());
        }
        return std::string();
    };
    writeText(scratch.file("a.txt"), "a file");
    EXPECT_NE(checkError(scratch.file("a.txt")).find("is a file, not a folder"), std::string::npos);
    EXPECT_NE(checkError(scratch.file("a.txt/sub")).find("a.txt' is a file, not a folder"), std::string::npos);
    EXPECT_NE(checkError(scratch.file("no/sub")).find("does not exist"), std::string::npos);
    EXPECT_EQ(checkError(scratch.file("new")), "");
    EXPECT_EQ(checkError(scratch.path().string()), "");
    // Files of the command already there must be replaceable; a folder in their place is not.
    fs::create_directories(scratch.file("out/report.json"));
    EXPECT_NE(checkError(scratch.file("out")).find("report.json: is a folder"), std::string::npos)
        << checkError(scratch.file("out"));
    fs::remove(scratch.file("out/report.json"));
    writeText(scratch.file("out/images"), "not a folder");
    EXPECT_NE(checkError(scratch.file("out")).find("images: is a file, not a folder"), std::string::npos);
    EXPECT_EQ(namesIn(scratch.file("out")), (std::set<std::string>{"images"}));  // no probe left behind
}

}  // namespace
}  // namespace punctual
