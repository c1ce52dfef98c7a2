#pragma once
// The one way punctual reads an input file: the scene itself and every file a glTF URI names
// (buffers and images, from .gltf and .glb alike). Only regular files are read. A directory, a
// FIFO, a device or a socket is refused after a stat(), before anything is opened: reading a
// directory as a stream "succeeds" with a nonsense size (tinygltf then asks for terabytes), and
// opening a FIFO blocks until some other process writes to it, possibly forever.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace punctual {

// Reads the whole regular file at `path` into `bytes`. Returns an empty string on success, or
// the problem as a short phrase for a message ("no such file", "a directory, not a regular
// file", "a named pipe (FIFO), not a regular file", ...). Never blocks on anything but the disk,
// and never allocates more than `maxBytes` (a larger file is refused by its size).
std::string readRegularFile(const std::string& path, uint64_t maxBytes, std::vector<unsigned char>& bytes);

// The first `headBytes` bytes (fewer if the file is shorter) of the file readRegularFile would
// read, by the same rules: enough to tell a file's format before reading all of it.
std::string readRegularFileHead(const std::string& path, uint64_t maxBytes, size_t headBytes,
                                std::vector<unsigned char>& bytes);

// The problem readRegularFile would report before reading (stat only), or an empty string
// when `path` names a regular file (or a symbolic link to one) of at most `maxBytes`.
std::string regularFileProblem(const std::string& path, uint64_t maxBytes);

}  // namespace punctual
