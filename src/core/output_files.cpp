#include "core/output_files.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/concat.h"
#include "core/deferred_signals.h"
#include "core/error.h"
#include "core/input_files_read.h"
#include "core/output_target.h"

namespace punctual {
namespace fs = std::filesystem;

namespace {

OutputFiles::StepObserver gStepObserver = nullptr;

void stepDone(const char* step) {
    if (gStepObserver) gStepObserver(step);
}

// One output on its way: the target, and what the commit has done for it so far (so a failure
// can undo exactly that).
struct Step {
    const std::string* path = nullptr;
    const std::string* contents = nullptr;
    OutputTarget target;
    std::string temporary;  // the new contents, until renamed over the target
    std::string backup;     // a hard link to the file being replaced, until the commit succeeds
    int stream = -1;        // an open device or FIFO
    bool published = false;
};

// 0 on success, else errno. Loops over short writes and interruptions.
int writeAll(int fd, const std::string& bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        done += size_t(n);
    }
    return 0;
}

// The permission bits a file created by a plain open() would get (mkstemp makes 0600).
mode_t newFileMode() {
    const mode_t mask = ::umask(0);  // umask can only be read by setting it; set it straight back
    ::umask(mask);
    return 0666 & ~mask;
}

// A reader that closes a FIFO early must give an error, not kill the process with SIGPIPE.
class IgnoreSigpipe {
public:
    IgnoreSigpipe() {
        struct sigaction ignore {};
        ignore.sa_handler = SIG_IGN;
        ::sigaction(SIGPIPE, &ignore, &previous_);
    }
    ~IgnoreSigpipe() { ::sigaction(SIGPIPE, &previous_, nullptr); }
    IgnoreSigpipe(const IgnoreSigpipe&) = delete;
    IgnoreSigpipe& operator=(const IgnoreSigpipe&) = delete;

private:
    struct sigaction previous_ {};
};

// Opens a character device or FIFO for writing as it is: no O_CREAT, no O_TRUNC. Non-blocking,
// so a FIFO nobody reads fails (ENXIO) instead of hanging; blocking again once open.
int openStream(const OutputTarget& target) {
    const int fd = ::open(target.file.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
        const int error = errno;
        if (error == ENXIO) throw Error(target.requested, "is a FIFO with no reader (start the reader first)");
        throw Error(target.requested, concat("cannot open it for writing: ", std::strerror(error)));
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !(S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode))) {
        ::close(fd);
        throw Error(target.requested, "changed while being written; refusing to write it");
    }
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
        const int error = errno;
        ::close(fd);
        throw Error(target.requested, concat("cannot write to it: ", std::strerror(error)));
    }
    return fd;
}

// Writes the new contents to a fresh temporary beside the target, with the permissions (and,
// where allowed, the owner) of the file it replaces, flushed to disk before the rename so a
// crash cannot leave an empty file where the old one was.
void writeTemporary(Step& step) {
    const std::string& subject = *step.path;
    const int fd = createTemporaryBeside(step.target.file, subject, step.temporary);
    int error = writeAll(fd, *step.contents);
    struct stat old {};
    if (step.target.kind == OutputTarget::Kind::Regular && ::stat(step.target.file.c_str(), &old) == 0) {
        if (error == 0 && ::fchmod(fd, old.st_mode & 0777) != 0) error = errno;
        if (::fchown(fd, old.st_uid, old.st_gid) != 0 && ::fchown(fd, uid_t(-1), old.st_gid) != 0) {
            // Not the owner and not in its group: the new file is ours, as any editor's would be.
        }
    } else if (error == 0 && ::fchmod(fd, newFileMode()) != 0) {
        error = errno;
    }
    if (error == 0 && ::fsync(fd) != 0) error = errno;
    if (::close(fd) != 0 && error == 0) error = errno;
    if (error != 0) {
        if (error == ENOSPC || error == EDQUOT) throw Error(subject, folderWriteProblem(step.target.folder(), error));
        throw Error(subject, concat("cannot write file: ", std::strerror(error)));
    }
}

// Keeps the file about to be replaced under a second, fresh name, so a failure later in the
// commit can rename it back (same contents, same inode). Without hard links (some file
// systems) there is no backup; such files are renamed last.
void keepBackup(Step& step) {
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name;
        ::close(createTemporaryBeside(step.target.file, *step.path, name));
        ::unlink(name.c_str());  // only the unique name is wanted, for link() below
        if (::link(step.target.file.c_str(), name.c_str()) == 0) {
            step.backup = name;
            return;
        }
        if (errno != EEXIST) return;
    }
}

// Renames the temporary over the target; 0 or errno. A new file must still be new: a file
// that appeared under its name since the check is not replaced (and so never removed by a
// rollback either).
int publish(const Step& step) {
    const char* from = step.temporary.c_str();
    const char* to = step.target.file.c_str();
    if (step.target.kind == OutputTarget::Kind::Missing) {
        if (::renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_NOREPLACE) == 0) return 0;
        if (errno != EINVAL && errno != ENOSYS) return errno;  // else: the file system cannot; plain rename
    }
    return ::rename(from, to) == 0 ? 0 : errno;
}

}  // namespace

void OutputFiles::observeStepsForTesting(StepObserver observer) { gStepObserver = observer; }

void OutputFiles::add(const std::string& path, std::string contents) {
    files_.emplace_back(path, std::move(contents));
}

void OutputFiles::addFolder(const std::string& path) { folders_.push_back(path); }

void OutputFiles::removeAfterCommit(const std::string& path) { stale_.push_back(path); }

namespace {

// Undoes what the commit did so far, newest first (see output_files.h).
void rollback(std::vector<Step>& steps, const std::vector<std::string>& createdFolders) {
    for (auto step = steps.rbegin(); step != steps.rend(); ++step) {
        if (step->stream >= 0) ::close(step->stream);
        if (step->published) {
            if (!step->backup.empty()) {
                ::rename(step->backup.c_str(), step->target.file.c_str());  // the old file, as it was
            } else if (step->target.kind == OutputTarget::Kind::Missing) {
                ::unlink(step->target.file.c_str());  // new: nothing was there
            }
            // (A replaced file without a backup keeps its new contents: the old are gone, and
            // removing the name too would lose both. Such files are renamed last, see publishAll.)
        } else {
            if (!step->temporary.empty()) ::unlink(step->temporary.c_str());
            if (!step->backup.empty()) ::unlink(step->backup.c_str());
        }
    }
    for (auto folder = createdFolders.rbegin(); folder != createdFolders.rend(); ++folder) ::rmdir(folder->c_str());
}

// Creates the missing folders, in order, noting each in `created` (for the rollback).
void createFolders(const std::vector<std::string>& folders, std::vector<std::string>& created) {
    for (const std::string& folder : folders) {
        if (::mkdir(folder.c_str(), 0777) == 0) {
            created.push_back(folder);
            stepDone("folder");
            continue;
        }
        const int error = errno;
        std::error_code ec;
        if (error == EEXIST && fs::is_directory(folder, ec)) continue;  // a symbolic link to a folder will do
        throw Error(folder, error == EEXIST ? "exists and is not a folder"
                                            : concat("cannot create the folder: ", std::strerror(error)));
    }
}

// Resolves every output's target; two outputs naming one file are refused.
void resolveTargets(const std::vector<std::pair<std::string, std::string>>& files, std::vector<Step>& steps) {
    for (size_t i = 0; i < files.size(); ++i) {
        steps[i].path = &files[i].first;
        steps[i].contents = &files[i].second;
        steps[i].target = resolveOutputTarget(files[i].first);
        for (size_t j = 0; j < i; ++j) {
            if (steps[i].target.sameFileAs(steps[j].target)) {
                throw Error(files[i].first,
                            concat("is the same file as '", files[j].first, "'; two outputs cannot share a file"));
            }
        }
    }
}

// Renames every temporary over its target: the undoable ones first, then those without a backup.
void publishAll(std::vector<Step>& steps) {
    std::vector<Step*> order;
    for (Step& step : steps) {
        if (step.target.kind != OutputTarget::Kind::Stream) order.push_back(&step);
    }
    std::stable_partition(order.begin(), order.end(), [](const Step* step) {
        return step->target.kind == OutputTarget::Kind::Missing || !step->backup.empty();
    });
    for (Step* step : order) {
        if (const int error = publish(*step); error != 0) {
            if (error == EEXIST) throw Error(*step->path, "appeared while punctual was running; not replaced");
            throw Error(*step->path, concat("cannot write file: ", std::strerror(error)));
        }
        step->published = true;
        stepDone("rename");
    }
}

// Writes into the open devices and FIFOs, last: their bytes cannot be taken back.
void writeStreams(std::vector<Step>& steps) {
    const IgnoreSigpipe ignoreSigpipe;
    for (Step& step : steps) {
        if (step.stream < 0) continue;
        int error = writeAll(step.stream, *step.contents);
        if (::close(step.stream) != 0 && error == 0) error = errno;
        step.stream = -1;
        if (error == EPIPE) throw Error(*step.path, "the reader closed it before everything was written");
        if (error != 0) throw Error(*step.path, concat("cannot write to it: ", std::strerror(error)));
        stepDone("stream");
    }
}

// Stale files go only once everything is in place. unlink() never follows a symbolic link and
// never removes a folder; a stale file already gone is no error. A stale name that is now a file
// this run read (a texture saved under an old output's name) is the user's input: it stays.
void removeStale(const std::vector<std::string>& stale) {
    for (const std::string& path : stale) {
        struct stat st {};
        if (::lstat(path.c_str(), &st) == 0 && findInputFileRead(st.st_dev, st.st_ino)) continue;
        ::unlink(path.c_str());
        stepDone("stale");
    }
}

}  // namespace

void OutputFiles::commit() {
    const DeferredSignals deferred;  // all new or all old, whatever signal arrives (core/deferred_signals.h)
    std::vector<std::string> createdFolders;
    std::vector<Step> steps(files_.size());
    try {
        createFolders(folders_, createdFolders);
        resolveTargets(files_, steps);
        // Streams are opened first: a FIFO without a reader fails before anything is replaced.
        for (Step& step : steps) {
            if (step.target.kind == OutputTarget::Kind::Stream) step.stream = openStream(step.target);
        }
        for (Step& step : steps) {
            if (step.target.kind == OutputTarget::Kind::Stream) continue;
            writeTemporary(step);
            stepDone("temporary");
        }
        for (Step& step : steps) {
            if (step.target.kind != OutputTarget::Kind::Regular) continue;
            keepBackup(step);
            stepDone("backup");
        }
        publishAll(steps);
        writeStreams(steps);
    } catch (...) {
        rollback(steps, createdFolders);
        throw;
    }
    for (const Step& step : steps) {
        if (!step.backup.empty()) ::unlink(step.backup.c_str());
    }
    removeStale(stale_);
    files_.clear();
    folders_.clear();
    stale_.clear();
}

}  // namespace punctual
