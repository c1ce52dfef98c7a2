#include "core/output_target.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <system_error>
#include <vector>

#include "core/concat.h"
#include "core/deferred_signals.h"
#include "core/error.h"
#include "core/input_files_read.h"

namespace punctual {
namespace fs = std::filesystem;

namespace {

constexpr int kMaxSymlinkHops = 40;  // as the kernel's own limit (ELOOP)

std::string quotedPath(const fs::path& path) { return concat("'", path.string(), "'"); }

// The longest file name the file system at `folder` (or its nearest existing ancestor) allows.
size_t nameMaxNear(fs::path folder) {
    for (int i = 0; i < 64 && !folder.empty(); ++i) {
        const long max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
        if (max > 0) return size_t(max);
        if (folder == folder.parent_path()) break;
        folder = folder.parent_path();
    }
    return NAME_MAX;
}

// The first folder on the way to `path` that is a file (the cause of ENOTDIR).
std::string firstFileOnTheWay(const fs::path& path) {
    fs::path prefix;
    for (const fs::path& part : path.parent_path()) {
        prefix /= part;
        struct stat st {};
        if (::stat(prefix.c_str(), &st) != 0) break;
        if (!S_ISDIR(st.st_mode)) return concat(quotedPath(prefix), " is a file, not a folder");
    }
    return "a part of the path is not a folder";
}

// What a failed lookup (stat, lstat) of `path` means, in words.
std::string lookupProblem(const fs::path& path, int error) {
    switch (error) {
        case ENOTDIR: return firstFileOnTheWay(path);
        case ELOOP: return "too many levels of symbolic links";
        case EACCES: return "permission denied on the way to it (a folder is not searchable)";
        case ENAMETOOLONG: {
            const size_t max = nameMaxNear(path.parent_path());
            for (const fs::path& part : path) {
                if (part.string().size() > max) {
                    return concat("file name is too long (", part.string().size(), " bytes, at most ", max, ")");
                }
            }
            return concat("path is too long (", path.string().size(), " bytes, at most ", PATH_MAX - 1, ")");
        }
        default: return std::strerror(error);
    }
}

// The folder an output goes into must exist and be a folder.
void checkFolder(const std::string& subject, const fs::path& folder) {
    struct stat st {};
    if (::stat(folder.c_str(), &st) == 0) {
        if (!S_ISDIR(st.st_mode)) throw Error(subject, concat(quotedPath(folder), " is a file, not a folder"));
        return;
    }
    const int error = errno;  // read before anything else can change it
    if (error == ENOENT) throw Error(subject, concat("folder ", quotedPath(folder), " does not exist"));
    throw Error(subject, lookupProblem(folder / "x", error));
}

}  // namespace

bool OutputTarget::sameFileAs(const OutputTarget& other) const {
    if (kind == Kind::Missing || other.kind == Kind::Missing) {
        return kind == other.kind && file == other.file;
    }
    return device == other.device && inode == other.inode;
}

OutputTarget resolveOutputTarget(const std::string& path) {
    if (path.empty()) throw Error("output", "empty file name");
    OutputTarget target;
    target.requested = path;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) throw Error(path, "is a folder, expected a file name");
        if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
            target.kind = OutputTarget::Kind::Stream;
            target.file = path;
            target.device = st.st_dev;
            target.inode = st.st_ino;
            return target;
        }
        if (S_ISBLK(st.st_mode)) throw Error(path, "is a block device; refusing to write an output over it");
        if (!S_ISREG(st.st_mode)) throw Error(path, "is not a regular file (a socket?); refusing to replace it");
    } else if (const int error = errno; error != ENOENT) {
        throw Error(path, lookupProblem(path, error));
    }
    // A regular file or a new name, perhaps behind symbolic links (a dangling one is written
    // through too, as the shell's '>' does): follow them to the name the rename must replace.
    fs::path name = path;
    for (int hops = 0;; ++hops) {
        struct stat link {};
        if (::lstat(name.c_str(), &link) != 0) {
            if (const int error = errno; error != ENOENT) throw Error(path, lookupProblem(name, error));
            break;
        }
        if (!S_ISLNK(link.st_mode)) break;
        if (hops == kMaxSymlinkHops) throw Error(path, "too many levels of symbolic links");
        std::error_code ec;
        const fs::path next = fs::read_symlink(name, ec);
        if (ec) throw Error(path, concat("cannot read the symbolic link ", quotedPath(name), ": ", ec.message()));
        name = next.is_absolute() ? next : name.parent_path() / next;
    }
    if (!name.has_filename()) throw Error(path, "expected a file name, not a folder name ending in '/'");
    const fs::path folder = name.has_parent_path() ? name.parent_path() : fs::path(".");
    checkFolder(path, folder);
    const std::string fileName = name.filename().string();
    const size_t nameMax = nameMaxNear(folder);
    if (fileName.size() > nameMax) {
        throw Error(path, concat("file name is too long (", fileName.size(), " bytes, at most ", nameMax, ")"));
    }
    std::error_code ec;
    const fs::path canonicalFolder = fs::canonical(folder, ec);
    if (ec) throw Error(path, concat("cannot resolve folder ", quotedPath(folder), ": ", ec.message()));
    target.file = canonicalFolder / fileName;
    if (::lstat(target.file.c_str(), &st) == 0) {
        // Checked above through the path as given; a change since is refused, not guessed at.
        if (!S_ISREG(st.st_mode)) throw Error(path, "changed while being checked; refusing to replace it");
        target.kind = OutputTarget::Kind::Regular;
        target.device = st.st_dev;
        target.inode = st.st_ino;
        if (const InputFileIdentity* input = findInputFileRead(st.st_dev, st.st_ino)) {
            const std::string same = input->path == path ? "" : concat(" ('", input->path, "')");
            throw Error(path, concat("is an input of this run", same,
                                     "; punctual never writes an output over a file it reads"));
        }
    } else if (const int error = errno; error != ENOENT) {
        throw Error(path, lookupProblem(target.file, error));
    }
    return target;
}

std::string folderWriteProblem(const fs::path& folder, int error) {
    switch (error) {
        case EACCES:
        case EPERM: return concat("folder ", quotedPath(folder), " is not writable");
        case EROFS: return concat("folder ", quotedPath(folder), " is on a read-only file system");
        case ENOSPC:
        case EDQUOT: return concat("no space left in folder ", quotedPath(folder));
        default: return concat("cannot create a file in folder ", quotedPath(folder), ": ", std::strerror(error));
    }
}

int createTemporaryBeside(const fs::path& file, const std::string& subject, std::string& temporary) {
    const fs::path folder = file.parent_path();
    const std::string name = file.filename().string();
    // "." + name + ".XXXXXX" must itself fit the file system's name limit.
    const size_t nameMax = nameMaxNear(folder);
    const size_t keep = std::min(name.size(), nameMax > 16 ? nameMax - 8 : size_t(8));
    const std::string pattern = (folder / concat(".", name.substr(0, keep), ".XXXXXX")).string();
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    const int fd = ::mkostemp(buffer.data(), O_CLOEXEC);
    if (fd < 0) {
        const int error = errno;
        throw Error(subject, folderWriteProblem(folder, error));
    }
    temporary = buffer.data();
    return fd;
}

void checkOutputTargetWritable(const OutputTarget& target) {
    if (target.kind == OutputTarget::Kind::Stream) {
        if (::access(target.file.c_str(), W_OK) != 0) {
            const int error = errno;
            throw Error(target.requested, concat("cannot write to it: ", std::strerror(error)));
        }
        return;
    }
    if (target.kind == OutputTarget::Kind::Regular && ::access(target.file.c_str(), W_OK) != 0) {
        const int error = errno;
        if (error == EROFS) throw Error(target.requested, "is on a read-only file system");
        throw Error(target.requested, error == EACCES ? "is write-protected; refusing to replace it"
                                                      : concat("cannot write to it: ", std::strerror(error)));
    }
    checkFolderWritable(target.requested, target.folder());
}

void checkFolderWritable(const std::string& subject, const fs::path& folder) {
    const DeferredSignals deferred;  // the probe file is removed even on Ctrl-C
    std::string temporary;
    const int fd = createTemporaryBeside(folder / "punctual", subject, temporary);
    ::close(fd);
    ::unlink(temporary.c_str());
}

}  // namespace punctual
