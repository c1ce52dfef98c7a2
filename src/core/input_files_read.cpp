#include "core/input_files_read.h"

#include <algorithm>

namespace punctual {
namespace {

// One run reads its inputs on one thread (the loader), and outputs are resolved after them; a
// plain vector behind a pointer is all the state there is.
std::vector<InputFileIdentity>* gLog = nullptr;

}  // namespace

InputFileLog::InputFileLog() { gLog = new std::vector<InputFileIdentity>(); }

InputFileLog::~InputFileLog() {
    delete gLog;
    gLog = nullptr;
}

void noteInputFileRead(dev_t device, ino_t inode, const std::string& path) {
    if (!gLog || findInputFileRead(device, inode)) return;
    gLog->push_back({device, inode, path});
}

const InputFileIdentity* findInputFileRead(dev_t device, ino_t inode) {
    if (!gLog) return nullptr;
    const auto found = std::find_if(gLog->begin(), gLog->end(), [&](const InputFileIdentity& input) {
        return input.device == device && input.inode == inode;
    });
    return found == gLog->end() ? nullptr : &*found;
}

}  // namespace punctual
