#pragma once
// Errors as values with a message: every failure the user can cause (bad files, bad options,
// bad light parameters) is reported as one line naming the subject (usually a file) and the
// problem, e.g. "scene.gltf: accessor 3 reads past the end of buffer 0".
#include <stdexcept>
#include <string>

namespace punctual {

class Error : public std::runtime_error {
public:
    // `subject` is what the error is about: a file path, an option name ("--lights") or a
    // subsystem ("vulkan"). `problem` says what is wrong with it.
    Error(const std::string& subject, const std::string& problem)
        : std::runtime_error(subject.empty() ? problem : subject + ": " + problem),
          subject_(subject), problem_(problem) {}

    const std::string& subject() const { return subject_; }
    const std::string& problem() const { return problem_; }

private:
    std::string subject_;
    std::string problem_;
};

}  // namespace punctual
