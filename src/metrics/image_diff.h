#pragma once
// How far one 8-bit image is from another (e.g. a method's image from brute force's).
#include "core/image.h"

namespace punctual {

struct ImageDifference {
    double meanAbsolute = 0.0;  // mean absolute difference per colour channel, 0..1
    double pixelsOff = 0.0;     // share of pixels with a channel more than 2/255 off
};

// The images must have the same size.
ImageDifference compareImages(const ImageRgba8& a, const ImageRgba8& b);

}  // namespace punctual
