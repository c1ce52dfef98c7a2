#pragma once
// The render options, one row each: name, value, help and what it sets. parseRenderOptions reads
// arguments through it, `punctual render --help` prints it, and the README's synopsis is checked
// against that help (tests/gpu/test_variant_help.cpp). An option is added in one place: its row.
#include <span>
#include <string>

#include "cli/options.h"

namespace punctual::cli {

// What the parse noted beyond the options themselves: options that must not be given together.
struct RenderOptionNotes {
    bool cascadeSplits = false;  // --cascade-splits and --cascade-lambda say one thing two ways
    bool cascadeLambda = false;
};

struct RenderOptionSpec {
    const char* name;       // "--shadow-res"
    const char* valueName;  // "auto|N", shown in the help; nullptr: a flag without a value
    const char* help;       // the help text, its lines separated by '\n' (wrapped by hand)
    // Sets the option from its value (empty for a flag); throws punctual::Error naming `name`.
    void (*apply)(RenderOptions& options, const std::string& value, RenderOptionNotes& notes);
    // The variant list printed under the help (a table's names and descriptions), or nullptr.
    std::string (*variants)(const RenderOptions& defaults, size_t indent) = nullptr;
};

// Every render option, in the order --help lists them.
std::span<const RenderOptionSpec> renderOptionTable();

// The row of `name`, or nullptr.
const RenderOptionSpec* findRenderOption(const std::string& name);

// The options part of `punctual render --help`: each row's name and value in a column of
// kHelpColumn characters, its help beside it, continuation lines and variant lists indented.
std::string renderOptionsHelp();

}  // namespace punctual::cli
