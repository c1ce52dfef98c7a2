#pragma once
#include <string>
#include <vector>

namespace punctual::app {

// `punctual compare [SCENE] [render options]`: renders the frame with every light-list method
// and prints them side by side: GPU time per pass, the image error against brute force, and the
// shadow accuracy against Embree's ray-cast visibility. The README's main job ends with it.
int runCompareCommand(const std::vector<std::string>& args);

}  // namespace punctual::app
