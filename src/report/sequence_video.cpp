#include "report/sequence_video.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "core/run_program.h"

namespace punctual::report {
namespace {

std::string frameFileName(uint32_t index) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%05u.png", index);
    return name;
}

}  // namespace

SequenceVideo::SequenceVideo() : ffmpeg_(findOnPath("ffmpeg")) {
    if (ffmpeg_.empty()) {
        throw Error("--video", "needs ffmpeg on PATH to encode the frames (Debian's ffmpeg package; "
                               "scripts/install-deps.sh installs it)");
    }
    std::error_code error;
    const std::filesystem::path temporary = std::filesystem::temp_directory_path(error);
    for (uint32_t attempt = 0; attempt < 100 && folder_.empty(); ++attempt) {
        const std::filesystem::path candidate =
            temporary / ("punctual-video-" + std::to_string(getpid()) + "-" + std::to_string(attempt));
        if (!error && std::filesystem::create_directory(candidate, error) && !error) folder_ = candidate;
    }
    if (folder_.empty()) throw Error("--video", "could not make a temporary folder for the frames in " + temporary.string());
}

SequenceVideo::~SequenceVideo() {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
}

void SequenceVideo::addFrame(const std::string& png) {
    const std::filesystem::path path = folder_ / frameFileName(frames_);
    std::ofstream file(path, std::ios::binary);
    file.write(png.data(), std::streamsize(png.size()));
    if (!file.flush()) throw Error("--video", "could not write a frame to " + path.string());
    ++frames_;
}

std::string SequenceVideo::encode(double fps) const {
    const std::filesystem::path video = folder_ / "frames.mp4";
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.6g", fps);
    const int status = runProgram(ffmpeg_, {"-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-framerate", rate,
                                            "-i", (folder_ / "frame-%05d.png").string(), "-vf",
                                            "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                            "-crf", "18", video.string()});
    if (status != 0) {
        endAsTheChildEnded(status);
        throw Error("--video", ffmpeg_ + " exited with status " + std::to_string(status) + " encoding the frames");
    }
    std::ifstream file(video, std::ios::binary);
    std::ostringstream bytes;
    bytes << file.rdbuf();
    if (!file || bytes.str().empty()) throw Error("--video", ffmpeg_ + " wrote no video");
    return bytes.str();
}

}  // namespace punctual::report
