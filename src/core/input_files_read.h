#pragma once
// The files a run has read, so that no output ever replaces one of them.
//
// Every input goes through one reader (scene/input_file.h), which notes here the identity
// (device and inode, from fstat of the open descriptor) of each file it opens while a log is
// installed. resolveOutputTarget (core/output_target.h), which every output check and the final
// commit go through, refuses a target with the identity of a noted input. Identity, not path: a
// symbolic link, a '..', a hard link or a different spelling of the scene all name one inode.
// `render s.gltf --out s.gltf` and `--out texture.png` (a texture the scene reads) fail in one line
// before the render, and the scene is left byte for byte as it was.
#include <sys/types.h>

#include <string>
#include <vector>

namespace punctual {

struct InputFileIdentity {
    dev_t device = 0;
    ino_t inode = 0;
    std::string path;  // as the reader was given it, for messages
};

// Installs a log for its lifetime (commands install one in main()); nested logs are not supported.
// Without one, nothing is noted: library users and unit tests that load scenes keep no state.
class InputFileLog {
public:
    InputFileLog();
    ~InputFileLog();
    InputFileLog(const InputFileLog&) = delete;
    InputFileLog& operator=(const InputFileLog&) = delete;
};

// Called by the reader for every file it opened.
void noteInputFileRead(dev_t device, ino_t inode, const std::string& path);

// The noted input with this identity, or nullptr.
const InputFileIdentity* findInputFileRead(dev_t device, ino_t inode);

}  // namespace punctual
