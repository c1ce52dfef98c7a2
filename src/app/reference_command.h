#pragma once
#include <string>
#include <vector>

#include "cli/options.h"
#include "reference/reference_renderer.h"

namespace punctual::app {

// `punctual reference [SCENE] [options] --out FILE.png [--no-shadows]`: ray traces the CPU
// reference image with Embree. Returns the process exit code. Throws punctual::Error on bad input.
int runReferenceCommand(const std::vector<std::string>& args);

std::string referenceUsage();

// The CPU reference's settings for what `options` ask: their size, exposure and transparent
// shadow mode; shadows on or off. Shared by `reference` and `validate`, which compare with it.
reference::ReferenceSettings referenceSettingsFrom(const cli::RenderOptions& options, bool shadows);

}  // namespace punctual::app
