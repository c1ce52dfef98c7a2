#include "cli/output_paths.h"

#include "core/concat.h"
#include "core/error.h"
#include "core/output_target.h"

namespace punctual::cli {

void checkOutputPaths(const std::vector<NamedOutput>& outputs) {
    std::vector<std::pair<const NamedOutput*, OutputTarget>> targets;
    for (const NamedOutput& output : outputs) {
        if (!output.path) continue;
        if (output.path->empty()) throw Error(output.option, "empty file name");
        OutputTarget target = resolveOutputTarget(*output.path);
        for (const auto& [other, otherTarget] : targets) {
            if (target.sameFileAs(otherTarget)) {
                throw Error(*output.path, concat(output.option, " names the same file as ", other->option, " '",
                                                 *other->path, "'; two outputs cannot share a file"));
            }
        }
        checkOutputTargetWritable(target);
        targets.emplace_back(&output, std::move(target));
    }
}

void checkOutputPath(const std::optional<std::string>& path) { checkOutputPaths({{"output", path}}); }

}  // namespace punctual::cli
