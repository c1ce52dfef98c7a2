#include "scene/input_file.h"

#include "core/input_files_read.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>

namespace punctual {
namespace {

// What a stat() result is, when it is not a regular file; empty for a regular file.
std::string typeProblem(const struct stat& info) {
    if (S_ISREG(info.st_mode)) return "";
    if (S_ISDIR(info.st_mode)) return "a directory, not a regular file";
    if (S_ISFIFO(info.st_mode)) return "a named pipe (FIFO), not a regular file";
    if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode)) return "a device, not a regular file";
    if (S_ISSOCK(info.st_mode)) return "a socket, not a regular file";
    return "not a regular file";
}

std::string errnoProblem(int error) {
    if (error == ENOENT) return "no such file";
    if (error == EACCES) return "permission denied";
    if (error == ENOTDIR) return "no such file (a folder on its path is a file)";
    if (error == ELOOP) return "too many levels of symbolic links";
    if (error == ENAMETOOLONG) return "the path is too long";
    return std::strerror(error);
}

std::string sizeProblem(uint64_t size, uint64_t maxBytes) {
    return std::to_string(size) + " bytes, more than the " + std::to_string(maxBytes) + " punctual can read";
}

std::string readProblem(int error, std::vector<unsigned char>& bytes) {
    bytes.clear();
    if (error == EISDIR) return "a directory, not a regular file";
    return "read error: " + std::string(std::strerror(error));
}

// Closes the descriptor on every path out of readRegularFile.
class FileDescriptor {
public:
    explicit FileDescriptor(int fd) : fd_(fd) {}
    ~FileDescriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

// Opens `path` by the reader's rules into `file` (stat first, so a FIFO is never opened at all;
// then the descriptor's own fstat, in `info`). Returns the problem, or empty.
std::string openRegularFile(const std::string& path, uint64_t maxBytes, int& file, struct stat& info) {
    file = -1;
    if (std::string problem = regularFileProblem(path, maxBytes); !problem.empty()) return problem;
    // The path may have been replaced between the stat and the open: O_NONBLOCK keeps even a
    // FIFO swapped in from blocking the open, and fstat checks what was really opened.
    file = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
    if (file < 0) return errnoProblem(errno);
    if (::fstat(file, &info) != 0) return errnoProblem(errno);
    if (std::string problem = typeProblem(info); !problem.empty()) return problem;
    if (uint64_t(info.st_size) > maxBytes) return sizeProblem(uint64_t(info.st_size), maxBytes);
    noteInputFileRead(info.st_dev, info.st_ino, path);
    return "";
}

// Reads into `bytes` until it is full or the file ends, then trims it to what was read. Returns
// the problem (a read error), or empty.
std::string fill(int file, std::vector<unsigned char>& bytes) {
    size_t filled = 0;
    while (filled < bytes.size()) {
        const ssize_t got = ::read(file, bytes.data() + filled, bytes.size() - filled);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) return readProblem(errno, bytes);
        if (got == 0) break;
        filled += size_t(got);
    }
    bytes.resize(filled);
    return "";
}

}  // namespace

std::string regularFileProblem(const std::string& path, uint64_t maxBytes) {
    if (path.empty()) return "no such file (the path is empty)";
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) {
        const int error = errno;
        struct stat link {};
        if (error == ENOENT && ::lstat(path.c_str(), &link) == 0) return "a broken symbolic link";
        return errnoProblem(error);
    }
    if (std::string problem = typeProblem(info); !problem.empty()) return problem;
    if (uint64_t(info.st_size) > maxBytes) return sizeProblem(uint64_t(info.st_size), maxBytes);
    noteInputFileRead(info.st_dev, info.st_ino, path);
    return "";
}

namespace {

// Opens `path` by the reader's rules and reads it into `bytes`: its first `headBytes` bytes when
// given (fewer if it is shorter), else all of it, never past `maxBytes`.
std::string readOpened(const std::string& path, uint64_t maxBytes, std::optional<size_t> headBytes,
                       std::vector<unsigned char>& bytes) {
    bytes.clear();
    int descriptor = -1;
    struct stat info {};
    const std::string problem = openRegularFile(path, maxBytes, descriptor, info);
    const FileDescriptor file(descriptor);
    if (!problem.empty()) return problem;
    // st_size is a hint (a file may grow or shrink while we read, and some kernel files report
    // 0): read what it announces, then on until end of file, but never past maxBytes.
    bytes.resize(headBytes ? *headBytes : size_t(info.st_size));
    if (std::string failure = fill(file.get(), bytes); !failure.empty()) return failure;
    if (headBytes || bytes.size() < size_t(info.st_size)) return "";  // the head, or a file that shrank
    std::vector<unsigned char> chunk(65536);
    while (true) {
        const ssize_t got = ::read(file.get(), chunk.data(), chunk.size());
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) return readProblem(errno, bytes);
        if (got == 0) break;
        if (uint64_t(bytes.size()) + uint64_t(got) > maxBytes) {
            const uint64_t size = uint64_t(bytes.size()) + uint64_t(got);
            bytes.clear();
            return sizeProblem(size, maxBytes);
        }
        bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + got);
    }
    return "";
}

}  // namespace

std::string readRegularFileHead(const std::string& path, uint64_t maxBytes, size_t headBytes,
                                std::vector<unsigned char>& bytes) {
    return readOpened(path, maxBytes, headBytes, bytes);
}

std::string readRegularFile(const std::string& path, uint64_t maxBytes, std::vector<unsigned char>& bytes) {
    return readOpened(path, maxBytes, std::nullopt, bytes);
}

}  // namespace punctual
