#pragma once
// `punctual play --video`: the frames as an H.264 MP4, encoded by ffmpeg (Debian's ffmpeg package;
// scripts/install-deps.sh installs it) where it is on PATH, the one program punctual runs that it
// does not ship. ffmpeg reads files, so each frame's PNG goes into a private temporary folder as
// it is rendered; the video is read back and committed with the sequence's other files (nothing
// enters DIR before then), and the folder is removed whatever happens.
#include <cstdint>
#include <filesystem>
#include <string>

namespace punctual::report {

class SequenceVideo {
public:
    // Throws Error("--video", ...) when ffmpeg is not on PATH, or the folder cannot be made.
    SequenceVideo();
    ~SequenceVideo();
    SequenceVideo(const SequenceVideo&) = delete;
    SequenceVideo& operator=(const SequenceVideo&) = delete;

    // The next frame, as PNG bytes.
    void addFrame(const std::string& png);
    // The frames at `fps` frames a second (each side padded to an even size, as yuv420p needs),
    // as MP4 bytes. Throws Error("--video", ...) naming ffmpeg's exit status.
    std::string encode(double fps) const;

private:
    std::string ffmpeg_;
    std::filesystem::path folder_;
    uint32_t frames_ = 0;
};

}  // namespace punctual::report
